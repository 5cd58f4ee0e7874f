// One frame of a plan, rendered: a pinhole pre-pass, then as many thin-lens rays per pixel as the
// pixel's blur and motion ask for (docs/render.md, "Sampling"), or, for draft, a depth-aware gather
// blur of the pre-pass.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <Eigen/Core>

#include "core/trajectory.h"
#include "preview/preview_scene.h"
#include "preview/render_options.h"

namespace cinepath::preview {

struct FrameImage {
  int width = 0;
  int height = 0;
  std::vector<Eigen::Vector3f> rgb_linear;  // row-major, rows from the top
  std::vector<float> depth_m;               // along the optical axis at the pixel centre; +inf for sky
  std::vector<float> blur_px;               // blur-circle diameter at that depth (px)
  std::vector<float> subject_id;            // the subject at the pixel centre: index + 1; 0 for none
  std::vector<uint16_t> samples;            // rays the pixel got
  uint64_t total_samples = 0;
};

struct FrameSettings {
  int width_px = 0;
  int height_px = 0;
  SamplingPreset preset;
  Exposure exposure = Exposure::kFixed;
  double iso = 100;
};

// The shutter interval of sample k: centred on its time, shutter_s long, kept within the samples of
// k's shot (motion never blurs across a cut).
std::pair<double, double> ShutterInterval(const Trajectory& plan, size_t k);

// Relative exposure t * ISO / N^2, 1 at 1/50 s, ISO 100, f/4.
double RelativeExposure(double shutter_s, double iso, double f_number);

FrameImage RenderFrame(const PreviewScene& scene, const Trajectory& plan, size_t sample_index,
                       const FrameSettings& settings);

// The output size: the plan's camera, or `width_px` with its aspect kept (height rounded, at least 1).
std::pair<int, int> OutputSize(const CameraSpec& camera, std::optional<int> width_px);

}  // namespace cinepath::preview
