// Surfaces that face their cameras. A reconstructed surface must show its front to the cameras that
// photographed it: texturing only takes a photo for a face whose front it sees, and renderers cull or
// shade back faces. Poisson's winding follows its implicit function's sign, which an open surface (a
// facade seen from one side, a patch of ground) does not fix: measured on a real facade, 99 % of the faces
// came out facing away from the cameras.
//
// Each connected piece (faces joined through shared vertices) votes: every face asks the input point
// nearest its centroid which cameras saw it, and counts, weighted by its area, whether its normal points to
// their side (the mean of the unit directions to them). A piece whose vote is negative is turned over
// whole, so a piece is never left half one way, half the other. Faces whose nearest point has no
// observer do not vote; a piece with no vote is left as it is.
#pragma once

#include <cstdint>

#include "core/json.h"
#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct OrientReport {
  int64_t components = 0;
  int64_t components_flipped = 0;
  int64_t faces_flipped = 0;
  int64_t faces_without_observers = 0;  // faces that did not vote
  Json ToJson() const;
};

// Turns over, in place, each connected piece of `mesh` that faces away from the cameras of `cloud`
// (PointCloud::observers, camera_centers_m). A cloud without observers leaves the mesh as it is.
OrientReport OrientTowardCameras(TriangleMesh* mesh, const PointCloud& cloud);

}  // namespace cinepath::photogrammetry
