#include "preview/render_job.h"

#include <malloc.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>
#include <sstream>

#include <tbb/parallel_invoke.h>
#include <tbb/task_group.h>

#include "core/error.h"
#include "core/file_io.h"
#include "core/number_format.h"
#include "core/plan_file.h"
#include "core/reframe.h"
#include "core/scene_file.h"
#include "core/team_plan.h"
#include "preview/aov.h"
#include "preview/image_files.h"
#include "preview/preview_scene.h"
#include "preview/sun_position.h"
#include "preview/thin_lens_camera.h"
#include "scene/glb_reader.h"
#include "scene/ray_caster.h"

namespace cinepath::preview {
namespace {

namespace fs = std::filesystem;

constexpr int kThumbWidthPx = 320;
constexpr int kSheetColumns = 4;
constexpr int kLabelPx = 12;

// `drone`: the flight's name in a team's frames (empty for one drone).
std::vector<std::string> LabelLines(const Trajectory& plan, size_t k, const std::string& drone = "") {
  const TrajectorySample& s = plan.samples[k];
  const std::string focus = std::isinf(s.focus_distance_m) ? "inf" : FormatSignificant(s.focus_distance_m, 3) + " m";
  return {"#" + std::to_string(k) + "  t " + FormatFixed(s.time_s, 3) + " s  " + (drone.empty() ? "" : drone + "  ") +
              s.shot,
          FormatSignificant(s.focal_length_mm, 4) + " mm  focus " + focus + "  f/" + FormatSignificant(s.f_number, 3)};
}

void CheckWritableFolder(const fs::path& dir) {
  try {
    EnsureDirectory(dir);
  } catch (const Error& e) {
    throw InputError(dir.string() + ": cannot create the output folder (" + e.what() + ")");
  }
  const fs::path probe = dir / (".cinepath-render-probe" + std::to_string(getpid()));
  FILE* f = std::fopen(probe.c_str(), "w");
  if (!f) throw InputError(dir.string() + ": the output folder is not writable");
  std::fclose(f);
  fs::remove(probe);
}

std::string FindOnPath(const std::string& program) {
  const char* path = std::getenv("PATH");
  std::stringstream dirs(path ? path : "");
  std::string dir;
  while (std::getline(dirs, dir, ':')) {
    const fs::path candidate = fs::path(dir.empty() ? "." : dir) / program;
    if (access(candidate.c_str(), X_OK) == 0) return candidate.string();
  }
  return {};
}

// The rule of thirds and the frame's label, burnt in.
void BurnOverlay(Srgb8Image* image, const Trajectory& plan, size_t k, const std::string& drone) {
  auto blend = [&](int x, int y) {
    uint8_t* p = &image->rgb[3 * (size_t(y) * image->width + x)];
    for (int c = 0; c < 3; ++c) p[c] = uint8_t((p[c] + 255 * 2) / 3);
  };
  for (int third = 1; third <= 2; ++third) {
    const int x = image->width * third / 3, y = image->height * third / 3;
    for (int j = 0; j < image->height; ++j) blend(x, j);
    for (int i = 0; i < image->width; ++i) blend(i, y);
  }
  const int size = std::max(10, image->height / 36);
  const auto lines = LabelLines(plan, k, drone);
  for (size_t l = 0; l < lines.size(); ++l)
    DrawText(image, size / 2, size / 2 + int(l) * (size + size / 3), size, lines[l]);
}

Srgb8Image Thumbnail(const FrameImage& frame) {
  const int tw = std::min(kThumbWidthPx, frame.width);
  const int th = std::max(1, int(std::lround(double(tw) * frame.height / frame.width)));
  std::vector<Eigen::Vector3f> small(size_t(tw) * th, Eigen::Vector3f::Zero());
  std::vector<int> count(small.size(), 0);
  for (int y = 0; y < frame.height; ++y) {
    for (int x = 0; x < frame.width; ++x) {
      const size_t t = size_t(std::min(th - 1, y * th / frame.height)) * tw + std::min(tw - 1, x * tw / frame.width);
      small[t] += frame.rgb_linear[size_t(y) * frame.width + x];
      ++count[t];
    }
  }
  for (size_t i = 0; i < small.size(); ++i) small[i] /= float(std::max(1, count[i]));
  return EncodeSrgb8(small, tw, th);
}

Srgb8Image ContactSheet(const std::vector<Srgb8Image>& thumbs, const std::vector<std::vector<std::string>>& labels) {
  const int tw = thumbs.front().width, th = thumbs.front().height;
  const int columns = std::min<int>(kSheetColumns, int(thumbs.size()));
  const int rows = (int(thumbs.size()) + columns - 1) / columns;
  const int pad = 6, label_h = 2 * (kLabelPx + 4) + 2;
  size_t longest = 0;  // DejaVu Sans Mono advances 0.6 em per character
  for (const auto& lines : labels) {
    for (const auto& line : lines) longest = std::max(longest, line.size());
  }
  const int cell_w = std::max(tw, int(std::ceil(0.6 * kLabelPx * longest)) + 4) + pad, cell_h = th + label_h + pad;
  Srgb8Image sheet{pad + columns * cell_w, pad + rows * cell_h, {}};
  sheet.rgb.assign(size_t(sheet.width) * sheet.height * 3, 24);
  for (size_t i = 0; i < thumbs.size(); ++i) {
    const int x0 = pad + int(i % columns) * cell_w, y0 = pad + int(i / columns) * cell_h;
    for (int y = 0; y < thumbs[i].height; ++y) {
      std::copy_n(&thumbs[i].rgb[size_t(y) * thumbs[i].width * 3], thumbs[i].width * 3,
                  &sheet.rgb[(size_t(y0 + y) * sheet.width + x0) * 3]);
    }
    for (size_t l = 0; l < labels[i].size(); ++l) {
      DrawText(&sheet, x0 + 2, y0 + th + 2 + int(l) * (kLabelPx + 4), kLabelPx, labels[i][l]);
    }
  }
  return sheet;
}

// Frames piped as raw RGB into ffmpeg (libx264, yuv420p, the plan's rate / every), into a temporary
// file renamed on success.
class VideoWriter {
 public:
  VideoWriter(const fs::path& target, int width, int height, double rate_hz) : target_(target) {
    temp_ = target.parent_path() / ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) + ".mp4");
    std::ostringstream command;
    command << "ffmpeg -loglevel error -y -f rawvideo -pix_fmt rgb24 -s " << width << "x" << height << " -r "
            << FormatSignificant(rate_hz, 9) << " -i - -vf pad=ceil(iw/2)*2:ceil(ih/2)*2 -c:v libx264 -pix_fmt yuv420p"
            << " -movflags +faststart '" << temp_.string() << "'";
    pipe_ = popen(command.str().c_str(), "w");
    if (!pipe_) throw RuntimeError(target.string() + ": cannot start ffmpeg");
  }
  ~VideoWriter() {
    if (pipe_) pclose(pipe_);
    std::error_code ignored;
    fs::remove(temp_, ignored);
  }
  void Add(const Srgb8Image& frame) {
    if (std::fwrite(frame.rgb.data(), 1, frame.rgb.size(), pipe_) != frame.rgb.size()) {
      throw RuntimeError(target_.string() + ": ffmpeg stopped reading frames");
    }
  }
  void Finish() {
    const int status = pclose(pipe_);
    pipe_ = nullptr;
    if (status != 0)
      throw RuntimeError(target_.string() + ": ffmpeg failed (exit status " + std::to_string(status) + ")");
    fs::rename(temp_, target_);
  }

 private:
  fs::path target_, temp_;
  FILE* pipe_ = nullptr;
};

// --sun AZ,EL as given, or with --sun-time the sun of that moment at the scene's WGS84 origin.
SunDirection SunForOptions(const RenderOptions& options, const Trajectory& plan, const SceneFile& scene_file) {
  if (!options.sun_time_unix_s) return options.sun;
  const std::optional<Geodetic>& where = scene_file.origin ? scene_file.origin : plan.origin;
  if (!where) throw InputError("--sun-time: neither the scene nor the plan has a WGS84 origin to find the sun from");
  const SunDirection sun = SunPositionAt(*where, *options.sun_time_unix_s);
  if (sun.elevation_deg <= 0) {
    throw InputError("--sun-time: the sun is " + FormatFixed(-sun.elevation_deg, 1) +
                     " deg below the horizon then at the scene (azimuth " + FormatFixed(sun.azimuth_deg, 1) + " deg)");
  }
  return sun;
}

// The GLB read, then its textures decoded, its BVH built and its border ring found at once, on other
// threads while the plan is read and the options are checked (the plan's JSON and the atlas's JPEG are
// the two longest loading steps of the bundled scene, and independent; a large mesh's BVH and border ring
// take longer than its atlas). Its errors are raised where the GLB used to be read, after the plan's and
// the options' own: the GLB's, then the textures', then the BVH's (the order of the steps before they
// overlapped; the ring raises none).
class SceneLoader {
 public:
  // `ring`: also the mesh's border ring (for the ground past the edge); `texture_levels`: the levels of
  // each texture's pyramid (1: the image alone).
  SceneLoader(const SceneFile& scene_file, bool ring, int texture_levels) {
    group_.run([this, &scene_file, ring, texture_levels] {
      using Clock = std::chrono::steady_clock;
      try {
        const auto start = Clock::now();
        mesh_ = scene::ReadGlbFile(scene_file.RequireMesh());
        glb_s_ = std::chrono::duration<double>(Clock::now() - start).count();
        tbb::parallel_invoke(
            [this, texture_levels] {
              const auto begin = Clock::now();
              try {
                textures_ = DecodeTextures(mesh_, texture_levels);
              } catch (...) {
                textures_error_ = std::current_exception();
              }
              textures_s_ = std::chrono::duration<double>(Clock::now() - begin).count();
            },
            [this] {
              const auto begin = Clock::now();
              try {
                prepared_.caster = std::make_shared<const scene::RayCaster>(mesh_);
              } catch (...) {
                bvh_error_ = std::current_exception();
              }
              bvh_s_ = std::chrono::duration<double>(Clock::now() - begin).count();
            },
            [this, ring] {
              const auto begin = Clock::now();
              if (ring) prepared_.ring = std::make_shared<const scene::BorderRing>(scene::FindBorderRing(mesh_));
              ring_s_ = std::chrono::duration<double>(Clock::now() - begin).count();
            });
      } catch (...) {
        error_ = std::current_exception();
      }
    });
  }
  ~SceneLoader() { group_.wait(); }
  SceneLoader(const SceneLoader&) = delete;
  SceneLoader& operator=(const SceneLoader&) = delete;

  // Waits; the loading steps' first error if one failed. Call once.
  void Wait(const RenderLog& log) {
    group_.wait();
    for (const std::exception_ptr& error : {error_, textures_error_, bvh_error_}) {
      if (error) std::rethrow_exception(error);
    }
    if (log.step_done) {
      log.step_done("open GLB (parse, Draco), beside the plan", glb_s_);
      log.step_done("decode textures, beside the plan", textures_s_);
      log.step_done("BVH, beside the textures", bvh_s_);
      log.step_done("border ring of the ground past the edge, beside them", ring_s_);
    }
  }
  scene::SceneMesh& mesh() { return mesh_; }
  std::vector<Texture>& textures() { return textures_; }
  const PreviewScene::Prepared& prepared() const { return prepared_; }

 private:
  tbb::task_group group_;
  scene::SceneMesh mesh_;
  std::vector<Texture> textures_;
  PreviewScene::Prepared prepared_;
  std::exception_ptr error_, textures_error_, bvh_error_;
  double glb_s_ = 0, textures_s_ = 0, bvh_s_ = 0, ring_s_ = 0;
};

}  // namespace

std::string FrameLabel(const Trajectory& plan, size_t k) {
  const auto lines = LabelLines(plan, k);
  return lines[0] + "  " + lines[1];
}

std::string FrameFileName(size_t k, ImageFormat format) {
  char name[64];
  std::snprintf(name, sizeof name, "frame_%06zu.%s", k, FileExtension(format));
  return name;
}

namespace {

FrameSettings SettingsFor(const RenderOptions& options, int width, int height) {
  FrameSettings settings;
  settings.width_px = width;
  settings.height_px = height;
  settings.preset = PresetFor(options.quality);
  if (options.max_samples) settings.preset.max_samples = *options.max_samples;
  if (options.min_samples) {
    settings.preset.min_samples = *options.min_samples;
    settings.preset.max_samples = std::max(settings.preset.max_samples, *options.min_samples);
  }
  settings.preset.denoise = options.denoise;
  settings.exposure = options.exposure;
  settings.iso = options.iso;
  return settings;
}

// frame_%06d.<aov>.exr beside the frame at `path`, one per --aov (preview/aov.h).
void WriteAovs(const FrameImage& frame, const fs::path& path, const RenderOptions& options, int width, int height,
               RenderSummary* summary) {
  for (const Aov aov : options.aovs) {
    const AovInfo& info = AovTable()[size_t(aov)];
    const fs::path file = path.parent_path() / (path.stem().string() + "." + info.name + ".exr");
    WriteExrAtomic(file, width, height, {info.channel}, AovValues(frame, aov));
    summary->outputs.push_back(file.string());
  }
}

// The same frame (and AOVs) under another name, byte for byte.
void CopyFrame(const fs::path& from, const fs::path& to, const RenderOptions& options, RenderSummary* summary) {
  WriteFileAtomic(to, ReadFileToString(from));
  summary->outputs.push_back(to.string());
  for (const Aov aov : options.aovs) {
    const std::string suffix = std::string(".") + AovTable()[size_t(aov)].name + ".exr";
    const fs::path aov_to = to.parent_path() / (to.stem().string() + suffix);
    WriteFileAtomic(aov_to, ReadFileToString(from.parent_path() / (from.stem().string() + suffix)));
    summary->outputs.push_back(aov_to.string());
  }
}

// One flight's frames: `targets` (sample index, file) rendered in order, each written (encoded, its
// AOVs, the video's frame, its thumbnail when `thumbs` asks) on another thread while the next renders:
// the encoders run on one core, and the render's rows fill the other. One frame is written at a time, in
// order, so the files, the video and the log are as with one thread.
struct FrameWriting {
  const RenderOptions& options;
  const FrameSettings& settings;
  VideoWriter* video = nullptr;
  std::map<size_t, Srgb8Image>* thumbs = nullptr;
  std::function<void(const RenderedFrame&)> frame_done;
  std::string drone;  // the flight's name on the overlay in a team's frames (empty for one drone)
};

void RenderFlightFrames(const PreviewScene& scene, const Trajectory& plan,
                        const std::vector<std::pair<size_t, fs::path>>& targets, const FrameWriting& writing_options,
                        RenderSummary* summary) {
  using Clock = std::chrono::steady_clock;
  const RenderOptions& options = writing_options.options;
  const int width = writing_options.settings.width_px, height = writing_options.settings.height_px;
  VideoWriter* video = writing_options.video;
  tbb::task_group writing;
  std::exception_ptr write_error;
  struct WaitOnExit {
    tbb::task_group& group;
    ~WaitOnExit() { group.wait(); }
  } wait_on_exit{writing};
  auto finish_writing = [&] {
    writing.wait();
    if (write_error) std::rethrow_exception(write_error);
  };
  for (const auto& [k, path] : targets) {
    const auto start = Clock::now();
    auto frame = std::make_shared<const FrameImage>(RenderFrame(scene, plan, k, writing_options.settings));
    const double render_s = std::chrono::duration<double>(Clock::now() - start).count();
    finish_writing();  // the previous frame's
    writing.run([&, frame, k = k, path = path, render_s] {
      try {
        const auto write_start = Clock::now();
        Srgb8Image encoded;
        if (options.format != ImageFormat::kExr || video) {
          encoded = EncodeSrgb8(frame->rgb_linear, width, height);
          if (options.overlay) BurnOverlay(&encoded, plan, k, writing_options.drone);
        }
        if (options.format == ImageFormat::kExr) {
          std::vector<float> values(frame->rgb_linear.size() * 3);
          for (size_t i = 0; i < frame->rgb_linear.size(); ++i) {
            for (int c = 0; c < 3; ++c) values[3 * i + c] = frame->rgb_linear[i][c];
          }
          WriteExrAtomic(path, width, height, {"R", "G", "B"}, values, options.exr_pixel);
        } else {
          WriteSrgb8Atomic(path, encoded);
        }
        summary->outputs.push_back(path.string());
        WriteAovs(*frame, path, options, width, height, summary);
        if (video) video->Add(encoded);
        if (writing_options.thumbs) (*writing_options.thumbs)[k] = Thumbnail(*frame);
        const double write_s = std::chrono::duration<double>(Clock::now() - write_start).count();
        RenderedFrame rendered{k, render_s + write_s, double(frame->total_samples) / (double(width) * height)};
        summary->frames.push_back(rendered);
        if (writing_options.frame_done) writing_options.frame_done(rendered);
      } catch (...) {
        write_error = std::current_exception();
      }
    });
  }
  finish_writing();
}

// The (flight, sample) of the edit's frame k: the live drone's (before the first cut, the first cut's
// drone); a flight that has ended holds its last sample.
std::pair<size_t, size_t> EditSource(const TeamPlan& team, size_t k) {
  const double t = double(k) / team.frame_rate_hz;
  int live = LiveFlightAt(team, t);
  if (live < 0) live = team.FindFlight(team.edit.front().drone);
  const size_t n = team.flights[size_t(live)].plan.samples.size();
  return std::pair<size_t, size_t>(size_t(live), std::min(k, n - 1));
}

// The edit's (flight, sample) pairs whose sample no drone folder holds: rendered into the edit folder
// only to be copied.
std::vector<std::pair<size_t, size_t>> HeldEditFrames(const TeamPlan& team, const std::vector<size_t>& frames) {
  std::vector<std::pair<size_t, size_t>> extra;
  if (team.edit.empty()) return extra;
  for (size_t k : frames) {
    const auto [f, j] = EditSource(team, k);
    if (!std::binary_search(frames.begin(), frames.end(), j)) extra.push_back({f, j});
  }
  std::sort(extra.begin(), extra.end());
  extra.erase(std::unique(extra.begin(), extra.end()), extra.end());
  return extra;
}

// A contact-sheet tile's label for flight f's sample j as frame k: the frame's label, and for several
// drones the time on the shared clock and the drone's name.
std::vector<std::string> TileLabel(const TeamPlan& team, size_t f, size_t j, size_t k) {
  const Trajectory& plan = team.flights[f].plan;
  std::vector<std::string> lines = LabelLines(plan, j);
  if (team.single) return lines;
  lines[0] = "#" + std::to_string(k) + "  t " + FormatFixed(double(k) / team.frame_rate_hz, 3) + " s  " +
             team.flights[f].name + "  " + plan.samples[j].shot;
  return lines;
}

// What the flights' renders left: thumbs[f][j], flight f's sample j (when sheets are asked for); the
// edit's held frames; each flight's folder.
struct RenderedFlights {
  std::vector<std::map<size_t, Srgb8Image>> thumbs;
  std::map<std::pair<size_t, size_t>, fs::path> held;
  std::vector<fs::path> folders;
};

// OUTPUT/edit/frame_%06d.<ext>, each copied from its drone's folder or its held frame (the held frames
// then removed), and the edit's contact sheet.
void WriteEdit(const TeamPlan& team, const std::vector<size_t>& frames, const RenderedFlights& rendered,
               const RenderOptions& options, RenderSummary* summary) {
  std::vector<Srgb8Image> edit_thumbs;
  std::vector<std::vector<std::string>> edit_labels;
  for (size_t k : frames) {
    const auto [f, j] = EditSource(team, k);
    const fs::path to = options.output_dir / "edit" / FrameFileName(k, options.format);
    const auto h = rendered.held.find({f, j});
    const fs::path from = h != rendered.held.end() ? h->second : rendered.folders[f] / FrameFileName(j, options.format);
    CopyFrame(from, to, options, summary);
    edit_thumbs.push_back(rendered.thumbs[f].at(j));
    edit_labels.push_back(TileLabel(team, f, j, k));
  }
  for (const auto& [key, path] : rendered.held) {  // held frames were written only to be copied
    std::error_code ignored;
    fs::remove(path, ignored);
    for (const AovInfo& aov : AovTable()) {
      fs::remove(path.parent_path() / (path.stem().string() + "." + aov.name + ".exr"), ignored);
    }
  }
  summary->outputs.erase(std::remove_if(summary->outputs.begin(), summary->outputs.end(),
                                        [](const std::string& o) { return o.find("/.held_") != std::string::npos; }),
                         summary->outputs.end());
  if (edit_thumbs.empty()) return;
  fs::path sheet = options.output_dir / "edit" / "contact_sheet.png";
  if (options.contact_sheet) {
    const fs::path& given = *options.contact_sheet;
    sheet = given.parent_path() / (given.stem().string() + ".edit" + given.extension().string());
  }
  WriteSrgb8Atomic(sheet, ContactSheet(edit_thumbs, edit_labels));
  summary->outputs.push_back(sheet.string());
}

// --contact-sheet PATH: every flight's tiles, frame by frame.
void WriteContactSheet(const TeamPlan& team, const std::vector<size_t>& frames, const RenderedFlights& rendered,
                       const RenderOptions& options, RenderSummary* summary) {
  std::vector<Srgb8Image> all;
  std::vector<std::vector<std::string>> labels;
  for (size_t k : frames) {
    for (size_t f = 0; f < team.flights.size(); ++f) {
      const auto t = rendered.thumbs[f].find(k);
      if (t == rendered.thumbs[f].end()) continue;
      all.push_back(t->second);
      labels.push_back(TileLabel(team, f, k, k));
    }
  }
  if (all.empty()) return;
  WriteSrgb8Atomic(*options.contact_sheet, ContactSheet(all, labels));
  summary->outputs.push_back(options.contact_sheet->string());
}

// One output size for every drone (the edit cuts between them): the first flight's camera's; InputError
// naming the drone whose camera differs. Every frame's lens is checked as the camera will take it.
std::pair<int, int> CheckedFrameSize(const TeamPlan& team, const std::vector<size_t>& frames,
                                     const RenderOptions& options, const fs::path& plan_json) {
  const std::pair<int, int> size = OutputSize(team.flights.front().plan.camera, options.width_px);
  const int width = size.first, height = size.second;
  for (const auto& flight : team.flights) {
    const auto [w, h] = OutputSize(flight.plan.camera, options.width_px);
    if (w != width || h != height) {
      throw InputError(plan_json.string() + ": drone " + flight.name + "'s camera renders " + std::to_string(w) + "x" +
                       std::to_string(h) + " px, drone " + team.flights.front().name + "'s " + std::to_string(width) +
                       "x" + std::to_string(height) + ": the edit needs one frame size (give the cameras one aspect)");
    }
    for (size_t k : frames) {
      if (k >= flight.plan.samples.size()) break;
      const auto& s = flight.plan.samples[k];
      ThinLensCamera(flight.plan.camera, width, height, s.focal_length_mm, s.f_number, s.focus_distance_m);
    }
  }
  return size;
}

// Each flight's folder (OUTPUT itself for one drone, OUTPUT/<drone> for several) and the edit's, each
// checked writable before anything renders.
RenderedFlights OutputFolders(const TeamPlan& team, const RenderOptions& options) {
  RenderedFlights rendered;
  rendered.thumbs.resize(team.flights.size());
  for (const auto& flight : team.flights) {
    rendered.folders.push_back(team.single ? options.output_dir : options.output_dir / flight.name);
    if (!team.single) CheckWritableFolder(rendered.folders.back());
  }
  if (!team.edit.empty()) CheckWritableFolder(options.output_dir / "edit");
  return rendered;
}

// Frames to render in all: each flight's selected samples it has, and the edit's held frames.
size_t FrameCount(const TeamPlan& team, const std::vector<size_t>& frames,
                  const std::vector<std::pair<size_t, size_t>>& held) {
  size_t total = held.size();
  for (const auto& flight : team.flights) {
    for (size_t k : frames) total += k < flight.plan.samples.size() ? 1 : 0;
  }
  return total;
}

}  // namespace

// One drone's frames go into OUTPUT; a plan of several drones' (docs/render.md, "Several drones") into
// OUTPUT/<drone>/frame_%06d.<ext> for each flight's selected samples (the selection is of sample indexes
// on the shared clock), and with an edit OUTPUT/edit/frame_%06d.<ext>: frame k is the live drone's frame k
// (before the first cut, the first cut's drone; a flight that has ended holds its last sample), copied
// from its folder when it was rendered there. The edit's contact sheet, each tile labelled with its time
// and drone, goes to OUTPUT/edit/contact_sheet.png, or with --contact-sheet PATH beside PATH as
// STEM.edit.EXT (PATH then holds every drone's tiles).
RenderSummary RenderPlan(const fs::path& plan_json, const fs::path& scene_json, const RenderOptions& options,
                         const RenderLog& log) {
  RenderSummary summary;
  using Clock = std::chrono::steady_clock;
  Clock::time_point step_start = Clock::now();
  auto step = [&](const std::string& name) {
    const Clock::time_point now = Clock::now();
    if (log.step_done) log.step_done(name, std::chrono::duration<double>(now - step_start).count());
    step_start = now;
  };
  // Everything that can be refused, before anything is written.
  const SceneFile scene_file = ReadSceneFile(scene_json);
  SceneLoader loader(scene_file, options.backdrop == Backdrop::kGround,
                     PresetFor(options.quality).texture_lod ? kTextureLevels : 1);
  TeamPlan team = ReadTeamPlanFile(plan_json);
  summary.notes = TeamPlanNotes(team);
  summary.inputs.push_back(plan_json.string());
  const bool single = team.single;  // one drone: its frames in OUTPUT itself, no edit
  if (!single) {
    for (const auto& flight : team.flights) CheckDroneFolderName(flight.name, plan_json.string(), {"edit"});
  }
  // A plan planned about another origin than the mesh's is moved into the mesh's frame (exact).
  if (scene_file.origin) team = ReframeToOrigin(std::move(team), *scene_file.origin);
  if (options.video && !single) {
    throw InputError("--video: " + plan_json.string() +
                     " holds several drones; their frames and the edit's are image sequences (docs/render.md)");
  }
  const std::vector<size_t> frames = SelectFrames(team.SampleCount(), options.frames);
  if (options.width_px && *options.width_px <= 0) throw InputError("--width-px: must be at least 1");
  // Plain variables, not a structured binding (clang 14, which the fuzz build uses, cannot capture those).
  const std::pair<int, int> size = CheckedFrameSize(team, frames, options, plan_json);
  const int width = size.first, height = size.second;
  summary.inputs.push_back(scene_json.string());
  const fs::path& glb = scene_file.RequireMesh();
  summary.inputs.push_back(glb.string());
  if (options.video && FindOnPath("ffmpeg").empty()) {
    throw RuntimeError("--video needs ffmpeg on PATH (Debian package ffmpeg); nothing was rendered");
  }
  const bool has_edit = !team.edit.empty();
  const bool sheets = has_edit || options.contact_sheet;
  if (options.overlay || sheets) RequireLabelFont();
  const SunDirection sun = SunForOptions(options, team.flights.front().plan, scene_file);
  CheckWritableFolder(options.output_dir);
  RenderedFlights rendered = OutputFolders(team, options);
  step("read plan.json and scene.json, check the options");
  loader.Wait(log);
  step("wait for the GLB and its textures");
  // Every frame allocates the same few image-sized buffers: keep freed ones in the heap instead of
  // returning them to the kernel, so the next frame does not page-fault them in again (measured: a
  // fifth of a draft frame's time went to page faults and zeroing).
  mallopt(M_MMAP_THRESHOLD, 256 << 20);
  mallopt(M_TRIM_THRESHOLD, 512 << 20);
  const FrameSettings settings = SettingsFor(options, width, height);
  std::unique_ptr<VideoWriter> video;
  if (options.video) {
    video = std::make_unique<VideoWriter>(*options.video, width, height, team.frame_rate_hz / options.frames.every);
  }

  const std::vector<std::pair<size_t, size_t>> extra = HeldEditFrames(team, frames);
  const size_t total = FrameCount(team, frames, extra);

  size_t done = 0;
  for (size_t f = 0; f < team.flights.size(); ++f) {
    const Trajectory& plan = team.flights[f].plan;
    const bool last = f + 1 == team.flights.size();  // the last flight takes the mesh, the others a copy
    const PreviewScene scene(last ? std::move(loader.mesh()) : loader.mesh(),
                             last ? std::move(loader.textures()) : loader.textures(), loader.prepared(), plan,
                             options.shading, sun, options.backdrop);
    if (log.step_done) log.step_done("ground past the edge (its colours)", scene.load_times().ground_s);
    std::vector<std::pair<size_t, fs::path>> targets;
    for (size_t k : frames) {
      if (k >= plan.samples.size()) break;
      targets.push_back({k, rendered.folders[f] / FrameFileName(k, options.format)});
    }
    for (const auto& [ef, j] : extra) {
      if (ef != f) continue;
      const fs::path path = options.output_dir / "edit" / (".held_" + FrameFileName(j, options.format));
      targets.push_back({j, path});
      rendered.held[{ef, j}] = path;
    }
    FrameWriting writing{options,
                         settings,
                         video.get(),
                         sheets ? &rendered.thumbs[f] : nullptr,
                         [&](const RenderedFrame& rendered) {
                           if (log.frame_done) log.frame_done(rendered, ++done, total);
                         },
                         team.single ? std::string() : team.flights[f].name};
    RenderFlightFrames(scene, plan, targets, writing, &summary);
  }

  if (has_edit) WriteEdit(team, frames, rendered, options, &summary);
  if (options.contact_sheet) WriteContactSheet(team, frames, rendered, options, &summary);
  if (video) {
    video->Finish();
    summary.outputs.push_back(options.video->string());
  }
  return summary;
}

}  // namespace cinepath::preview
