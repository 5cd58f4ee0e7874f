// DJI WPML KMZ for DJI Pilot 2 / FlightHub 2 / MSDK v5 (docs/mission-formats.md §4.1): a ZIP with
// wpmz/template.kml (editable template, heights in the editor's reference) and wpmz/waylines.wpml
// (what the aircraft executes), namespace http://www.dji.com/wpmz/1.0.2, coordinates "lon,lat".
//
// Heights: --altitude-ref relative → heightMode/executeHeightMode relativeToStartPoint (metres above
// the take-off point = home); amsl or ellipsoid → template heightMode EGM96 (height = AMSL) and
// waylines executeHeightMode WGS84 (executeHeight = ellipsoidal), as DJI's conversion guidance says.
// Every template placemark carries both `height` and `ellipsoidHeight`.
// Turns: coordinateTurn with the waypoint's fitted waypointTurnDampingDist (dji_turns.h), or
// toPointAndStopWithDiscontinuityCurvature where it is 0; useStraightLine 1.
// Heading: smoothTransition to each waypoint's heading (shortest way); on the legs of a point of
// interest (Mission::rois, roi_tracking kHeading) towardPOI with waypointPoiPoint. Gimbal: gimbalRotate at the
// first waypoint (pitch and yaw, north-based), then gimbalEvenlyRotate on every leg. Zoom: the
// `zoom` action with the 35 mm-equivalent focal length whenever it changes. Recording: startRecord at
// the first waypoint, stopRecord at the last. Speeds are clamped into [1, 15] m/s (validation reports
// any leg outside). Focus distance and aperture have no WPML action: reported in `notes`.
#pragma once

#include <string>
#include <vector>

#include "core/drone_profile.h"
#include "export/mission.h"
#include "export/platform.h"

namespace cinepath::exporter {

struct WpmlDocuments {
  std::string template_kml;
  std::string waylines_wpml;
  std::vector<std::string> notes;
};

WpmlDocuments WriteWpmlDocuments(const Mission& mission, const DroneProfile& profile, AltitudeRef ref);
// The KMZ (ZIP) holding both documents.
std::string WriteDjiKmz(const WpmlDocuments& documents);

}  // namespace cinepath::exporter
