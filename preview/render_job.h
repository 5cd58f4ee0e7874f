// `cinepath render` as a library call: plan.json + scene.json -> DIR/frame_%06d.<ext> for the selected
// samples, with the AOVs, labels, contact sheet and video asked for (docs/render.md).
//
// Everything that can be refused is checked before the first frame is written: the plan, the frame
// selection, the scene and its mesh, the output folder's writability, ffmpeg for --video. Each frame is
// written atomically; a frame is the same bytes whatever the thread count or shard.
#pragma once

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "core/trajectory.h"
#include "preview/frame_renderer.h"
#include "preview/render_options.h"

namespace cinepath::preview {

struct RenderedFrame {
  size_t sample_index = 0;
  double seconds = 0;  // wall-clock render time (reported, never written into an image)
  double mean_samples = 0;
};

struct RenderLog {
  std::function<void(const RenderedFrame&, size_t done, size_t total)> frame_done;
  // Each loading step before the first frame, with its wall-clock seconds (`render -v`): "read plan.json
  // and scene.json", "open GLB (parse, Draco)", "decode textures", "BVH", "ground past the edge".
  std::function<void(const std::string& step, double seconds)> step_done;
};

struct RenderSummary {
  std::vector<std::string> inputs;   // what was read (for --depfile)
  std::vector<std::string> outputs;  // what was written
  std::vector<RenderedFrame> frames;
  std::vector<std::string> notes;  // the plan reader's (core/plan_file.h TeamPlanNotes), for warnings
};

// "t 12.400 s  orbit  35 mm  focus 12.3 m  f/4" (focus "inf" at infinity): the label of overlays and
// contact sheets.
std::string FrameLabel(const Trajectory& plan, size_t sample_index);

// The frame's file name: "frame_000012.png".
std::string FrameFileName(size_t sample_index, ImageFormat format);

RenderSummary RenderPlan(const std::filesystem::path& plan_json, const std::filesystem::path& scene_json,
                         const RenderOptions& options, const RenderLog& log = {});

}  // namespace cinepath::preview
