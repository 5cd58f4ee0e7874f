// libFuzzer target: plan.json through `render`'s preparation, in process: the plan moved onto a scene's
// origin, the frame selection (every frame, and every third of a range), the output size, and for each
// selected frame the thin-lens camera, its shutter interval, the pose at the shutter's open, middle and
// close, the centre and corner rays and the subjects projected into the image, and the frame's label.
// The scene's mesh and the tracing need Embree and a mesh; fuzz_glb reads meshes.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <optional>

#include "core/reframe.h"
#include "preview/frame_renderer.h"
#include "preview/frame_selection.h"
#include "preview/render_job.h"
#include "preview/thin_lens_camera.h"
#include "tests/fuzz/plan_stage_input.h"

namespace {

using namespace cinepath;
using namespace cinepath::preview;

void PrepareFrames(const Trajectory& plan, size_t num_samples, const FrameSelection& selection,
                   std::optional<int> width_px) {
  const std::vector<size_t> frames = SelectFrames(num_samples, selection);
  const auto [width, height] = OutputSize(plan.camera, width_px);
  for (size_t k : frames) {
    if (k >= plan.samples.size()) break;  // a shorter flight of a team
    const TrajectorySample& s = plan.samples[k];
    const ThinLensCamera camera(plan.camera, width, height, s.focal_length_mm, s.f_number, s.focus_distance_m);
    const auto [t0, t1] = ShutterInterval(plan, k);
    for (double t : {t0, 0.5 * (t0 + t1), t1}) {
      const CameraPose pose = PoseAt(plan, t);
      for (const auto& [x, y] : {std::pair{0.5 * width, 0.5 * height}, std::pair{0.0, 0.0}}) {
        const CameraRay ray = camera.Ray(pose, x, y, 0.5, -0.5);
        if (!ray.direction_enu.allFinite() || !ray.origin_enu_m.allFinite()) __builtin_trap();
      }
      for (const auto& subject : plan.subjects) {
        double depth_m = 0;
        camera.Project(pose, subject.positions_enu_m.at(k), &depth_m);
        if (depth_m > 0) camera.BlurPx(depth_m);
      }
    }
    FrameLabel(plan, k);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  auto team = fuzz::ReadPlanInput(data, size);
  if (!team) return 0;
  // As over a scene made about another origin (render reframes the plan onto the mesh's).
  if (team->origin) team = ReframeToOrigin(std::move(*team), Geodetic{team->origin->lat_deg, team->origin->lon_deg, 0});
  for (const auto& flight : team->flights) {
    const size_t n = team->SampleCount();
    fuzz::RunStage([&] { PrepareFrames(flight.plan, n, FrameSelection{}, 64); });
    FrameSelection some;
    some.range = FrameRange{1, 7};
    some.every = 3;
    some.shard = Shard{1, 2};
    fuzz::RunStage([&] { PrepareFrames(flight.plan, n, some, std::nullopt); });
  }
  return 0;
}
