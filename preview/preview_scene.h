// What a frame is traced against: the scene mesh (scene/ray_caster.h, Embree), its colours and
// textures, the plan's subject proxies, and the light. Radiance is linear RGB.
//
// Shading (docs/render.md, "Shading"):
//   flat  each surface shows its colour unlit (vertex colour x base colour x texture), as an emission
//         shader with no bounces; rays that miss see a sky gradient.
//   sun   colour x (sun * max(0, n.l) * visible + sky * (1 + n.up)/2): a directional sun of
//         irradiance 1 (one shadow ray) and a uniform sky of 0.25 (no bounces), normalised so a level
//         surface under a 45 deg sun shows about its flat colour.
#pragma once

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include <Eigen/Core>

#include "preview/render_options.h"
#include "preview/subject_proxies.h"
#include "preview/texture.h"
#include "scene/border_ring.h"
#include "scene/ray_caster.h"
#include "scene/scene_mesh.h"

namespace cinepath::preview {

// TraceHit::face of the ground past the mesh's edge.
constexpr uint32_t kGroundFace = 0xffffffffu;

struct TraceHit {
  double distance_m = 0;
  Eigen::Vector3d position_enu_m = Eigen::Vector3d::Zero();
  int subject = -1;  // >= 0 for a subject proxy
  uint32_t face = 0;
};

// The ground past the mesh's edge (Backdrop::kGround): the plane z = height_m, the mesh's border ring
// carried outward: seen from the border's centre, each 5-degree sector of azimuth takes the mean linear
// colour of the border faces in it (an empty sector its nearest neighbours'), so the sand beyond the sand
// and the grass beyond the grass, fading into their mean farther out; hazed toward the horizon's sky colour with
// distance (a visibility of `visibility_m`: the haze takes 1 - exp(-3 d / visibility) of the colour).
struct GroundBackdrop {
  static constexpr int kSectors = scene::BorderRing::kSectors;
  double height_m = 0;
  Eigen::Vector2d centre_m = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector3f> sector_color = std::vector<Eigen::Vector3f>(kSectors, Eigen::Vector3f::Constant(0.5f));
  // Farther out than the border's median radius about the centre, the sectors' colours fade into their
  // mean over `blend_m` (1 - exp(-(r - radius) / blend)), so the ring does not fan out to the horizon.
  double border_radius_m = 0;
  double blend_m = 150;
  Eigen::Vector3f mean_color = Eigen::Vector3f::Constant(0.5f);
  double visibility_m = 5000;
  Eigen::Vector3f ColorAt(const Eigen::Vector3d& position) const;
};

// Wall-clock seconds of each loading step (`render -v` prints them; never written into an image).
struct SceneLoadTimes {
  double bvh_s = 0;       // Embree's BVH of the mesh (0 when it was given built)
  double textures_s = 0;  // decoding the base-colour images (JPEG/PNG) to 8-bit texels
  double ground_s = 0;    // the ground past the edge (border ring, unless given found, and its colours)
};

class PreviewScene {
 public:
  // Builds the BVH and decodes the textures, at once. InputError for an empty or broken mesh.
  PreviewScene(scene::SceneMesh mesh, const Trajectory& plan, Shading shading, SunDirection sun,
               Backdrop backdrop = Backdrop::kNone);
  // What render's loading makes of the mesh beside the plan's reading, shared by every flight's scene:
  // its BVH (a RayCaster of this mesh: its queries are const) and, for Backdrop::kGround, its border ring
  // (scene::FindBorderRing; found here when null).
  struct Prepared {
    std::shared_ptr<const scene::RayCaster> caster;
    std::shared_ptr<const scene::BorderRing> ring;
  };
  // The same with the textures decoded already (DecodeTextures(mesh)) and the BVH built already.
  PreviewScene(scene::SceneMesh mesh, std::vector<Texture> textures, const Prepared& prepared, const Trajectory& plan,
               Shading shading, SunDirection sun, Backdrop backdrop);
  ~PreviewScene();

  // One instant of the scene: the time and where the subjects stand then, worked out once for the many
  // rays of that instant (a frame's pinhole pass, every ray of a frame without motion blur).
  struct Instant {
    double time_s = 0;
    std::vector<Eigen::Vector3d> subject_bases;
  };
  void SetInstant(double time_s, Instant* instant, size_t sample_hint = 0) const;
  Instant At(double time_s) const {
    Instant instant;
    SetInstant(time_s, &instant);
    return instant;
  }

  // Radiance along a unit-direction ray at time t: the shade of the closest surface (mesh or subject
  // proxy), or the sky; `hit_out` gets that surface (distance +inf for the sky).
  Eigen::Vector3f Radiance(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const Instant& at,
                           TraceHit* hit_out = nullptr) const;
  Eigen::Vector3f Radiance(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double time_s,
                           TraceHit* hit_out = nullptr) const {
    return Radiance(origin, direction, At(time_s), hit_out);
  }
  // The same for `count` (1 to 8) rays at once, traced as one packet (the pinhole pass's rows): radiance[i]
  // and hits_out[i] (when not null) are what Radiance gives ray i. Bit i of `may_see_subject` clear: ray i
  // is known to miss every subject (SubjectsInImage), and is not intersected with them. `pixel_angle_rad`
  // > 0 (draft's pinhole pass: the angle a pixel spans): each texture lookup reads the level of the
  // texture's pyramid that the pixel's footprint on the surface spans (when the textures have levels).
  void Radiance8(const Eigen::Vector3d* origins, const Eigen::Vector3d* directions, int count, const Instant& at,
                 Eigen::Vector3f* radiance, TraceHit* hits_out = nullptr, unsigned may_see_subject = 0xffu,
                 float pixel_angle_rad = 0) const;
  Eigen::Vector3f Sky(const Eigen::Vector3d& direction) const;
  // Where a pinhole ray of `camera` at `frame` may meet one of the subjects Radiance draws, at instant `at`
  // (for Radiance8's may_see_subject).
  SubjectsInImage SubjectsSeen(const Instant& at, const ThinLensCamera& camera, const CameraFrame& frame) const {
    return subjects_.InImage(at.subject_bases, camera, frame);
  }

  const scene::SceneMesh& mesh() const { return mesh_; }
  const std::optional<GroundBackdrop>& ground() const { return ground_; }
  const SceneLoadTimes& load_times() const { return load_times_; }

 private:
  // What a ray sees, given the mesh's hit along it (or none): the closer of it and the subjects, the
  // ground past the edge, or the sky.
  Eigen::Vector3f Shade(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, const Instant& at,
                        const std::optional<scene::RayHit>& mesh_hit, TraceHit* hit_out, bool may_see_subject = true,
                        float pixel_angle_rad = 0) const;
  // The surface's colour at a hit; with `pixel_angle_rad` > 0 its texture read at the level the footprint
  // of a pixel of that angle spans there, seen along `direction`.
  Eigen::Vector3f SurfaceColor(const scene::RayHit& hit, const Eigen::Vector3d& direction = Eigen::Vector3d::Zero(),
                               float pixel_angle_rad = 0) const;
  // Which level of the hit face's texture a lookup at `hit` reads for a pixel of `pixel_angle_rad` seen along
  // `direction` (docs/render.md, "Texture levels").
  int TextureLevelAt(const scene::RayHit& hit, const Eigen::Vector3d& direction, float pixel_angle_rad) const;
  GroundBackdrop BorderGround(const scene::BorderRing& ring) const;
  // The sun's direction and the ground past the edge (from `ring` when given).
  void Finish(SunDirection sun, Backdrop backdrop, const scene::BorderRing* ring = nullptr);
  Eigen::Vector3f Light(const Eigen::Vector3d& position, const Eigen::Vector3d& normal, const Instant& at) const;

  scene::SceneMesh mesh_;
  std::shared_ptr<const scene::RayCaster> caster_;
  SubjectProxies subjects_;
  std::vector<Texture> textures_;         // one per mesh image
  std::vector<float> face_texels_per_m_;  // FaceTexelsPerMetre, when a texture has coarser levels
  Shading shading_;
  Eigen::Vector3d sun_direction_enu_;  // towards the sun
  std::optional<GroundBackdrop> ground_;
  SceneLoadTimes load_times_;
};

}  // namespace cinepath::preview
