// Which photo textures each face (after Waechter, Moehrle & Goesele 2014, "Let There Be Color!
// Large-Scale Texturing of 3D Reconstructions", ECCV, and Lempitsky & Ivanov 2007, "Seamless Mosaicing
// of Image-Based Texture Maps", CVPR: a labelling of faces with views, a data term per face and view and
// a seam penalty between neighbours).
//
// A view can texture a face when the face is in front of the camera and turned toward it (cosine of
// the viewing angle over `min_cosine`), its three corners project into the image (`margin_px` from the
// border, through the full camera model), and nothing hides it: rays from its centroid and from three
// points near its corners to the camera centre hit no other face (Embree, scene/ray_caster.h).
//
// Quality of a view for a face: its projected area in pixels times the cosine of the viewing angle,
// i.e. pixels per square metre with an extra weight on frontal views (the projected area alone already
// holds distance and obliquity once). Data cost D(f, v) = 1 - q(f, v) / max_w q(f, w), in [0, 1).
// The labelling minimises sum_f D(f, l_f) + seam_penalty * #{edges whose faces differ}, by iterated
// conditional modes (Besag 1986) from the best-quality labels: faces visited in index order, each
// taking the label that minimises its own data cost plus the penalty toward its edge neighbours, for
// `smoothing_iterations` sweeps or until nothing changes. Deterministic; the visibility tests run in
// parallel but each face writes only its own entry.
//
// Photo-consistency (Waechter et al. 2014, section 3.2, after Sinha et al. 2008): the visibility test sees
// only the mesh, so a photo with a tree, a car or a passer-by in front of a wall still passes it, and
// would paint the occluder onto the wall. Before the labelling, every face that three or more photos see
// compares its colour in each of them (linear RGB over its centroid and three points near its corners,
// compared as square roots, close to sRGB's perceptual steps): the consensus is the per-channel median;
// a photo whose colour lies farther from it than max(`min_deviation`, `spread_factor` x the robust
// spread (1.4826 x the median distance)) is dropped for that face. mvs-texturing fits a Gaussian by
// mean shift instead; the median is the same idea in one pass, and as robust while under half of the
// photos disagree.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include <Eigen/Core>

#include "photogrammetry/mesh/triangle_mesh.h"
#include "photogrammetry/texture/texture_view.h"

namespace cinepath::scene {
class RayCaster;
}

namespace cinepath::photogrammetry {

struct PhotoConsistencyOptions {
  bool enabled = true;
  int min_views = 3;            // fewer photos of a face cannot outvote one
  double min_deviation = 0.12;  // square-root-linear units (~ sRGB / 255 x 255): 0.12 ~ 30 sRGB levels
  double spread_factor = 3.0;
};

struct ViewSelectionOptions {
  double min_cosine = 0.1;       // views more than ~84 degrees off the face normal do not texture it
  double margin_px = 2;          // the corners' distance from the image border
  double seam_penalty = 0.3;     // per edge between faces of different photos (data costs are in [0, 1))
  int smoothing_iterations = 8;  // ICM sweeps (0: each face its best view)
  PhotoConsistencyOptions consistency;
};

struct FaceView {
  int view = -1;
  float quality = 0;  // projected pixels x cosine
};

struct ViewSelection {
  std::vector<int> label;                         // per face: the index of its view, -1 = none sees it
  std::vector<std::vector<FaceView>> candidates;  // per face: every view that sees it, in view order
  int64_t faces_seen = 0;                         // faces with at least one candidate
  int64_t seam_edges_before = 0;                  // edges between faces of different labels, best-quality labels
  int64_t seam_edges_after = 0;                   // ... after smoothing
  int iterations_run = 0;
  int64_t views_inconsistent = 0;  // (face, photo) pairs dropped by the photo-consistency check
  int64_t faces_with_inconsistent_views = 0;
};

// The colour of face `face` in view `view` (linear RGB), false when it cannot be sampled. Called from
// several threads at once.
using FaceColorFn = std::function<bool(uint32_t face, int view, Eigen::Vector3f* linear_rgb)>;

// `caster` holds the same mesh (for occlusion). With `face_color`, the photo-consistency check runs
// before the labelling (options.consistency).
ViewSelection SelectViews(const TriangleMesh& mesh, const std::vector<TextureView>& views,
                          const scene::RayCaster& caster, const ViewSelectionOptions& options = {},
                          const FaceColorFn* face_color = nullptr);

// The photo-consistency check alone, on one face's candidates: drops those whose colour disagrees with the
// consensus; returns how many it dropped.
int RemoveInconsistentViews(uint32_t face, std::vector<FaceView>* candidates, const FaceColorFn& face_color,
                            const PhotoConsistencyOptions& options);

// Face pairs sharing an edge (each pair once, a < b, sorted): the neighbourhood of the seam penalty.
std::vector<std::pair<uint32_t, uint32_t>> FaceEdgeNeighbours(const TriangleMesh& mesh);

}  // namespace cinepath::photogrammetry
