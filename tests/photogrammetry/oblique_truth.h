// How far a cinepath mesh stands from the exact surface of a synthetic scene (tests/data/photogrammetry/
// oblique/: truth.ply, the rendered geometry in local ENU metres about truth.json's origin).
//
// Each distinct vertex position of the mesh (texture-seam copies counted once) is measured to the
// nearest point of the truth's triangles (an exact closest-point query); the distribution is reported,
// and also by the vertex's horizontal distance from the scene's centre (the orbits' target), in rings:
// an orbit sees the ground farther out more thinly and more obliquely. Shared by the CTest case
// (oblique_truth_test.cc) and the bench (bench/mesh_vs_truth.cc).
#pragma once

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <vector>

#include "core/geodesy.h"
#include "core/json.h"
#include "photogrammetry/io/ply_reader.h"
#include "photogrammetry/mesh/mesh_distance.h"
#include "scene/glb_reader.h"

namespace cinepath::testing {

struct TruthDistances {
  std::vector<double> distance_m;           // one per distinct vertex position
  std::vector<double> radius_m;             // its horizontal distance from the centre
  std::vector<Eigen::Vector3d> position_m;  // the vertex, in the truth's frame
  size_t size() const { return distance_m.size(); }
  // The q-quantile (0..1) of the distances of the vertices with r_lo <= radius < r_hi.
  double Quantile(double q, double r_lo = 0, double r_hi = INFINITY) const {
    std::vector<double> d = In(r_lo, r_hi);
    if (d.empty()) return 0;
    const size_t k = std::min(d.size() - 1, static_cast<size_t>(q * static_cast<double>(d.size())));
    std::nth_element(d.begin(), d.begin() + k, d.end());
    return d[k];
  }
  // The share of those vertices within `limit_m` of the truth.
  double ShareWithin(double limit_m, double r_lo = 0, double r_hi = INFINITY) const {
    const std::vector<double> d = In(r_lo, r_hi);
    if (d.empty()) return 1;
    return static_cast<double>(std::count_if(d.begin(), d.end(), [&](double x) { return x <= limit_m; })) /
           static_cast<double>(d.size());
  }
  size_t CountIn(double r_lo, double r_hi) const { return In(r_lo, r_hi).size(); }

 private:
  std::vector<double> In(double r_lo, double r_hi) const {
    std::vector<double> d;
    for (size_t i = 0; i < distance_m.size(); ++i) {
      if (radius_m[i] >= r_lo && radius_m[i] < r_hi) d.push_back(distance_m[i]);
    }
    return d;
  }
};

// The scene's ENU frame (scene.json's origin, which `cinepath mesh` takes as the references' mean unless
// --origin says otherwise) is not the truth's (truth.json's origin): each vertex goes through WGS84
// from one to the other (exact, GeographicLib).
inline TruthDistances MeasureAgainstTruth(const std::filesystem::path& scene_dir,
                                          const std::filesystem::path& truth_dir) {
  const Json truth_json = Json::parse(std::ifstream(truth_dir / "truth.json"));
  const Json scene_json = Json::parse(std::ifstream(scene_dir / "scene.json"));
  const Json& to = truth_json["origin"];
  const Json& so = scene_json["origin"];
  const EnuFrame truth_frame(
      Geodetic{to["latitude_deg"].get<double>(), to["longitude_deg"].get<double>(), to["height_m"].get<double>()});
  const EnuFrame scene_frame(
      Geodetic{so["lat_deg"].get<double>(), so["lon_deg"].get<double>(), so["height_m"].get<double>()});
  const Json& target = truth_json["cameras"][0]["look_at_enu_m"];
  const Eigen::Vector2d centre_en_m(target[0].get<double>(), target[1].get<double>());

  const photogrammetry::TriangleMesh truth = photogrammetry::ReadPly(truth_dir / "truth.ply").mesh;
  const photogrammetry::MeshDistanceIndex index(truth, "truth");
  std::vector<Eigen::Vector3d> positions = scene::ReadGlbFile(scene_dir / "scene.glb").positions_enu_m;
  std::sort(positions.begin(), positions.end(), [](const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
    return std::lexicographical_compare(a.data(), a.data() + 3, b.data(), b.data() + 3);
  });
  positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
  TruthDistances out;
  for (const auto& scene_p : positions) {
    const Eigen::Vector3d p = truth_frame.EnuFromGeodetic(scene_frame.GeodeticFromEnu(scene_p));
    out.distance_m.push_back(index.DistanceM(p));
    out.radius_m.push_back((p.head<2>() - centre_en_m).norm());
    out.position_m.push_back(p);
  }
  return out;
}

}  // namespace cinepath::testing
