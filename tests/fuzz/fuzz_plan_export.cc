// libFuzzer target: plan.json through `export`'s preparation, in process: every flight's missions built,
// checked and written in every format (MAVLink for PX4 and ArduPilot, DJI WPML and MSDK, Litchi), with
// relative and AMSL altitudes, and the report, as `cinepath export --force` builds them before writing;
// and every flight's camera track in the camera-track formats (glTF, Nuke .chan).
#include <cstddef>
#include <cstdint>

#include "core/geodesy.h"
#include "export/exporter.h"
#include "export/formats.h"
#include "tests/fuzz/plan_stage_input.h"

namespace {

using namespace cinepath;
using namespace cinepath::exporter;

void Export(const Trajectory& plan, std::vector<Format> formats, Firmware firmware, AltitudeRef altitude_ref) {
  ExportOptions options;
  options.formats = std::move(formats);
  options.firmware = firmware;
  options.altitude_ref = altitude_ref;
  options.force = true;  // past the platform limits into every writer
  // A plan without an origin is placed as `--scene` would place it.
  if (!plan.origin) options.build.scene_origin = Geodetic{47.3977, 8.5456, 488.0};
  fuzz::RunStage([&] {
    const ExportResult result = ExportMission(plan, options);
    DumpJson(ReportJson(result, options));
    ReportText(result, options);
  });
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const auto team = fuzz::ReadPlanInput(data, size);
  if (!team) return 0;
  std::vector<Format> all;
  std::vector<const FormatInfo*> cameras;
  for (const FormatInfo& f : Formats()) {
    if (f.kind == FormatKind::kCameraTrack) {
      cameras.push_back(&f);
    } else {
      all.push_back(f.format);
    }
  }
  for (const auto& flight : team->flights) {
    fuzz::RunStage([&] {
      const std::vector<CameraTrack> tracks = {TrackOfFlight(flight.plan, flight.name, "plan.json", !team->single)};
      for (const FormatInfo* f : cameras) f->write_cameras({tracks, {}, ""});
    });
    Export(flight.plan, all, Firmware::kPx4, AltitudeRef::kRelative);
    Export(flight.plan, {Format::kQgcPlan, Format::kQgcWpl, Format::kMavlinkBin, Format::kDjiWpml},
           Firmware::kArduPilot, AltitudeRef::kAmsl);
  }
  return 0;
}
