// cinepath render: plan.json + scene.json -> ray-traced thin-lens previews, one image per planned
// frame (docs/render.md). A plugin module (cli/command_plugin.h): Embree, libjpeg and libpng load only
// when this command runs.
#include <unistd.h>

#include <cstdio>
#include <cstring>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "cli/command.h"
#include "cli/command_plugin.h"
#include "cli/common_options.h"
#include "core/error.h"
#include "core/heap_pages.h"
#include "core/number_format.h"
#include "core/progress.h"
#include "preview/aov.h"
#include "preview/render_job.h"
#include "preview/sun_position.h"

namespace cinepath::cli {
namespace {

using namespace cinepath::preview;

// Wall-clock seconds since this process started (/proc: the kernel's start time in clock ticks against
// the uptime; 10 ms resolution): what the dynamic loader and the module's libraries took before Run.
double ProcessAgeSeconds() {
  FILE* stat = std::fopen("/proc/self/stat", "r");
  FILE* uptime = std::fopen("/proc/uptime", "r");
  double age = 0;
  if (stat && uptime) {
    char buffer[4096];
    const size_t n = std::fread(buffer, 1, sizeof buffer - 1, stat);
    buffer[n] = 0;
    const char* p = std::strrchr(buffer, ')');  // the command name may hold spaces
    unsigned long long start_ticks = 0;
    double up = 0;
    // After ") ": state, then fields 4..21; field 22 is starttime.
    if (p &&
        std::sscanf(p + 2, "%*c %*d %*d %*d %*d %*d %*u %*u %*u %*u %*u %*u %*u %*d %*d %*d %*d %*d %*d %llu",
                    &start_ticks) == 1 &&
        std::fscanf(uptime, "%lf", &up) == 1) {
      age = up - double(start_ticks) / double(sysconf(_SC_CLK_TCK));
    }
  }
  if (stat) std::fclose(stat);
  if (uptime) std::fclose(uptime);
  return age;
}

class RenderCommand : public Command {
 public:
  void Setup(CLI::App& app) override {
    app.add_option("plan", plan_path_, "plan.json (docs/plan-format.md)")->required();
    app.add_option("--scene", scene_path_, "scene.json; its mesh (the GLB beside it) is what is rendered")->required();
    app.add_option("-o,--output", output_dir_, "Folder for frame_%06d.<ext> (k = sample index)")->required();
    app.add_option("--frames", frames_, "Sample range A-B (zero-based, inclusive)");
    app.add_option("--every", every_, "Keep every N-th sample of the range")->check(CLI::PositiveNumber);
    app.add_option("--shard", shard_, "i/N: this machine's share (every N-th selected frame from the i-th)");
    AddQualityOption(app, &quality_, "draft is a pinhole ray with gathered blur; standard and final sample the lens");
    app.add_option("--spp", spp_, "Cap on rays per pixel (overrides the preset's)")->check(CLI::PositiveNumber);
    app.add_option("--min-spp", min_spp_, "Rays for every pixel at least, sharp ones too (a converged reference)")
        ->check(CLI::PositiveNumber);
    app.add_flag("--denoise", options_.denoise,
                 "Filter the noise of few lens rays, guided by each pixel's blur (standard and final; draft has none)");
    app.add_option("--format", format_, "png | exr (linear) | jpg")->check(CLI::IsMember({"png", "exr", "jpg"}));
    app.add_option("--exr-pixel", exr_pixel_, "half (default) | float: the values of an EXR frame (AOVs are float)")
        ->check(CLI::IsMember({"half", "float"}));
    app.add_option("--width-px", width_px_, "Output width; the plan camera's aspect is kept")
        ->check(CLI::PositiveNumber);
    shading_option_ = app.add_option("--shading", shading_, "flat (vertex colours, unlit) | sun")
                          ->check(CLI::IsMember({"flat", "sun"}));
    app.add_option("--sun", sun_, "Sun AZIMUTH,ELEVATION in degrees for --shading sun (default 135,45)");
    app.add_option("--sun-time", sun_time_,
                   "The sun of this UTC moment (YYYY-MM-DDTHH:MM[:SS]Z) at the scene's origin; implies --shading sun")
        ->excludes("--sun");
    app.add_option("--exposure", exposure_, "fixed (default) | physical (t * ISO / N^2, 1 at 1/50 s ISO 100 f/4)")
        ->check(CLI::IsMember({"fixed", "physical"}));
    app.add_option("--iso", options_.iso, "ISO for --exposure physical")->check(PositiveFinite());
    app.add_option("--backdrop", backdrop_,
                   "ground (default: the ground continues past the mesh's edge as a hazed plane) | none")
        ->check(CLI::IsMember({"ground", "none"}));
    std::vector<std::string> aovs;
    for (const auto& info : AovTable()) aovs.push_back(std::string(info.name) + " (" + info.unit + ")");
    app.add_option("--aov", aov_, "Extra EXR images per frame, comma-separated: " + JoinNames(aovs));
    app.add_flag("--overlay", options_.overlay, "Burn in the frame's time, shot and lens, and a rule-of-thirds guide");
    app.add_option("--contact-sheet", contact_sheet_, "Also write a labelled grid of the rendered frames (PNG/JPEG)");
    app.add_option("--video", video_, "Also write an H.264 MP4 at the plan's frame rate / --every (needs ffmpeg)");
    app.add_flag("-v,--verbose", verbose_,
                 "On stderr: the time of each loading step, then one line per frame (its time and rays per pixel)");
    common_.Add(app);
  }

  int Run() override {
    // Before the plan's DOM and the frames' buffers: those of the main thread in 2 MiB pages, reused
    // from frame to frame (core/heap_pages.h).
    PrepareHeapForLargeBuffers(kCommandHeapReserveBytes);
    shading_given_ = shading_option_ && shading_option_->count() > 0;
    options_.output_dir = output_dir_;
    if (!frames_.empty()) options_.frames.range = ParseFrameRange(frames_);
    options_.frames.every = size_t(every_);
    if (!shard_.empty()) options_.frames.shard = ParseShard(shard_);
    options_.quality = ParseQuality(quality_);
    if (spp_) options_.max_samples = *spp_;
    if (min_spp_) options_.min_samples = *min_spp_;
    options_.format = ParseImageFormat(format_);
    options_.exr_pixel = ParseExrPixel(exr_pixel_);
    options_.width_px = width_px_;
    options_.shading = ParseShading(shading_);
    if (!sun_.empty()) options_.sun = ParseSunDirection(sun_);
    if (!sun_time_.empty()) {
      if (shading_ == "flat" && shading_given_) throw InputError("--sun-time lights the scene: it needs --shading sun");
      options_.sun_time_unix_s = ParseUtcTime(sun_time_, "--sun-time");
      options_.shading = Shading::kSun;
    }
    options_.backdrop = ParseBackdrop(backdrop_);
    options_.exposure = exposure_ == "physical" ? Exposure::kPhysical : Exposure::kFixed;
    if (!aov_.empty()) options_.aovs = ParseAovList(aov_);
    if (!contact_sheet_.empty()) options_.contact_sheet = contact_sheet_;
    if (!video_.empty()) options_.video = video_;
    if (options_.denoise && options_.quality == Quality::kDraft) {
      std::cerr << "cinepath render: warning: --denoise does nothing at --quality draft (it traces no lens rays)\n";
    }

    std::optional<Progress> progress;
    RenderLog log;
    log.frame_done = [&](const RenderedFrame& frame, size_t done, size_t total) {
      if (!progress) progress.emplace("render", double(total), common_.progress_mode());
      progress->Update(double(done));
      if (!progress->enabled() && verbose_) {
        std::fprintf(stderr, "render: frame %zu (%zu/%zu) %.2f s, %.1f rays/px\n", frame.sample_index, done, total,
                     frame.seconds, frame.mean_samples);
      }
    };
    if (verbose_) {
      std::fprintf(stderr, "render: %.3f s  process start to here (executable, the render module and its libraries)\n",
                   ProcessAgeSeconds());
      log.step_done = [](const std::string& step, double seconds) {
        std::fprintf(stderr, "render: %.3f s  %s\n", seconds, step.c_str());
      };
    }
    const RenderSummary summary = RenderPlan(plan_path_, scene_path_, options_, log);
    if (progress) progress->Finish();
    PrintWarnings("render", summary.notes);
    common_.WriteDepfileIfAsked(summary.outputs, summary.inputs);
    return 0;
  }

  FieldFlags field_flags() const override { return {{"progress", "--progress"}}; }

 private:
  std::string plan_path_, scene_path_, output_dir_;
  std::string frames_, shard_, quality_ = "standard", format_ = "png", exr_pixel_ = "half", shading_ = "flat",
                               backdrop_ = "ground", sun_, exposure_ = "fixed";
  std::string aov_, contact_sheet_, video_, sun_time_;
  CLI::Option* shading_option_ = nullptr;
  bool shading_given_ = false;
  int every_ = 1;
  std::optional<int> spp_, min_spp_, width_px_;
  bool verbose_ = false;
  RenderOptions options_;
  CommonOptions common_;
};

}  // namespace

std::unique_ptr<Command> MakeRenderCommand() { return std::make_unique<RenderCommand>(); }

}  // namespace cinepath::cli

CINEPATH_COMMAND_PLUGIN(MakeRenderCommand)
