#include "photogrammetry/mesh/mesh_decimate.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <meshoptimizer.h>
#include <tbb/blocked_range.h>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>
#include <OpenMesh/Tools/Decimater/DecimaterT.hh>
#include <OpenMesh/Tools/Decimater/ModQuadricT.hh>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

struct MeshoptInput {
  std::vector<float> positions;  // xyz relative to `center`, float for meshoptimizer
  std::vector<uint32_t> indices;
};

MeshoptInput MakeMeshoptInput(const TriangleMesh& mesh) {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  if (mesh.num_vertices() > 0) {
    Eigen::Vector3d lo = mesh.vertices_m.front(), hi = mesh.vertices_m.front();
    for (const auto& v : mesh.vertices_m) {
      lo = lo.cwiseMin(v);
      hi = hi.cwiseMax(v);
    }
    center = 0.5 * (lo + hi);
  }
  MeshoptInput in;
  in.positions.reserve(3 * mesh.num_vertices());
  for (const auto& v : mesh.vertices_m) {
    const Eigen::Vector3d d = v - center;
    in.positions.insert(in.positions.end(),
                        {static_cast<float>(d.x()), static_cast<float>(d.y()), static_cast<float>(d.z())});
  }
  in.indices.reserve(3 * mesh.num_faces());
  for (const auto& f : mesh.faces) in.indices.insert(in.indices.end(), f.begin(), f.end());
  return in;
}

// Simplifies one index list; returns the kept indices. `error_m` receives meshoptimizer's error.
std::vector<uint32_t> MeshoptSimplify(const MeshoptInput& in, const std::vector<uint32_t>& indices,
                                      int64_t target_faces, double max_error_m, float scale, double* error_m) {
  std::vector<uint32_t> out(indices.size());
  const float target_error = max_error_m > 0 ? static_cast<float>(max_error_m / std::max(scale, 1e-30f)) : 1e6f;
  float result_error = 0;
  const size_t target_index_count =
      std::min(indices.size(), static_cast<size_t>(std::max<int64_t>(0, target_faces)) * 3);
  const size_t count =
      meshopt_simplify(out.data(), indices.data(), indices.size(), in.positions.data(), in.positions.size() / 3,
                       3 * sizeof(float), target_index_count, target_error, meshopt_SimplifyLockBorder, &result_error);
  out.resize(count);
  if (error_m) *error_m = static_cast<double>(result_error) * scale;
  return out;
}

// MeshoptSimplify on a compact vertex buffer (the vertices `indices` uses, in global order):
// meshoptimizer's work is proportional to the vertex count it is given, so handing a tile (or the
// merged tiles) the whole buffer would cost tiles × vertices. `scratch` (one per thread, one entry
// per global vertex) maps global → local indices. Returns global indices.
std::vector<uint32_t> SimplifyCompact(const MeshoptInput& in, const std::vector<uint32_t>& indices,
                                      int64_t target_faces, double max_error_m, float scale, double* error_m,
                                      std::vector<uint32_t>& scratch) {
  std::vector<uint32_t> global(indices);
  std::sort(global.begin(), global.end());
  global.erase(std::unique(global.begin(), global.end()), global.end());
  MeshoptInput local;
  local.positions.resize(3 * global.size());
  for (size_t k = 0; k < global.size(); ++k) {
    scratch[global[k]] = static_cast<uint32_t>(k);
    std::copy_n(in.positions.begin() + 3 * static_cast<size_t>(global[k]), 3, local.positions.begin() + 3 * k);
  }
  local.indices.resize(indices.size());
  for (size_t k = 0; k < indices.size(); ++k) local.indices[k] = scratch[indices[k]];
  std::vector<uint32_t> kept = MeshoptSimplify(local, local.indices, target_faces, max_error_m, scale, error_m);
  for (uint32_t& i : kept) i = global[i];
  return kept;
}

TriangleMesh DecimateMeshopt(const TriangleMesh& mesh, const DecimateOptions& options, double* error_m) {
  const MeshoptInput in = MakeMeshoptInput(mesh);
  const float scale = meshopt_simplifyScale(in.positions.data(), in.positions.size() / 3, 3 * sizeof(float));
  const std::vector<uint32_t> kept =
      MeshoptSimplify(in, in.indices, options.target_faces, options.max_error_m, scale, error_m);
  return internal::FromKeptIndices(mesh, kept);
}

// Tiles on a grid over the xy bounding box of the face centroids; each tile is simplified on its
// own (its cut edges are borders, so meshoptimizer keeps them), in parallel; then one global pass
// removes what the locked cuts kept. Tiles depend only on the geometry: any thread count gives the
// same mesh.
TriangleMesh DecimateMeshoptPartitioned(const TriangleMesh& mesh, const DecimateOptions& options, double* error_m) {
  const MeshoptInput in = MakeMeshoptInput(mesh);
  const float scale = meshopt_simplifyScale(in.positions.data(), in.positions.size() / 3, 3 * sizeof(float));
  const int partitions = std::max(1, options.partitions);
  const int grid = std::max(1, static_cast<int>(std::lround(std::sqrt(partitions))));
  Eigen::Vector2d lo(INFINITY, INFINITY), hi(-INFINITY, -INFINITY);
  std::vector<Eigen::Vector2d> centroids(mesh.num_faces());
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    const auto& t = mesh.faces[f];
    centroids[f] = ((mesh.vertices_m[t[0]] + mesh.vertices_m[t[1]] + mesh.vertices_m[t[2]]) / 3.0).head<2>();
    lo = lo.cwiseMin(centroids[f]);
    hi = hi.cwiseMax(centroids[f]);
  }
  const Eigen::Vector2d extent = (hi - lo).cwiseMax(Eigen::Vector2d(1e-9, 1e-9));
  std::vector<std::vector<uint32_t>> tiles(static_cast<size_t>(grid) * grid);
  for (size_t f = 0; f < mesh.num_faces(); ++f) {
    const int ix = std::min(grid - 1, static_cast<int>((centroids[f].x() - lo.x()) / extent.x() * grid));
    const int iy = std::min(grid - 1, static_cast<int>((centroids[f].y() - lo.y()) / extent.y() * grid));
    auto& tile = tiles[static_cast<size_t>(iy) * grid + ix];
    tile.insert(tile.end(), mesh.faces[f].begin(), mesh.faces[f].end());
  }
  const double keep_ratio = options.target_faces > 0
                                ? static_cast<double>(options.target_faces) / std::max<size_t>(1, mesh.num_faces())
                                : 0.0;
  // Per-thread scratch: global → local vertex index (only entries written for the current tile
  // are read, so it is never cleared).
  tbb::enumerable_thread_specific<std::vector<uint32_t>> scratch(
      [&] { return std::vector<uint32_t>(mesh.num_vertices()); });
  std::vector<std::vector<uint32_t>> simplified(tiles.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, tiles.size(), 1), [&](const tbb::blocked_range<size_t>& range) {
    for (size_t t = range.begin(); t != range.end(); ++t) {
      if (tiles[t].empty()) continue;
      const int64_t tile_target =
          static_cast<int64_t>(std::llround(keep_ratio * static_cast<double>(tiles[t].size() / 3)));
      simplified[t] = SimplifyCompact(in, tiles[t], tile_target, options.max_error_m, scale, nullptr, scratch.local());
    }
  });
  std::vector<uint32_t> merged;
  for (const auto& s : simplified) merged.insert(merged.end(), s.begin(), s.end());
  const std::vector<uint32_t> kept =
      SimplifyCompact(in, merged, options.target_faces, options.max_error_m, scale, error_m, scratch.local());
  return internal::FromKeptIndices(mesh, kept);
}

using OmMesh = OpenMesh::TriMesh_ArrayKernelT<>;

TriangleMesh DecimateOpenMesh(const TriangleMesh& mesh, int64_t target_faces) {
  OmMesh om;
  OpenMesh::VPropHandleT<uint32_t> original;
  om.add_property(original);
  std::vector<OmMesh::VertexHandle> handles;
  handles.reserve(mesh.num_vertices());
  for (size_t i = 0; i < mesh.num_vertices(); ++i) {
    const auto& v = mesh.vertices_m[i];
    handles.push_back(
        om.add_vertex(OmMesh::Point(static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z()))));
    om.property(original, handles.back()) = static_cast<uint32_t>(i);
  }
  for (const auto& f : mesh.faces) {
    om.add_face(handles[f[0]], handles[f[1]], handles[f[2]]);  // complex faces are skipped
  }
  om.request_vertex_status();
  om.request_edge_status();
  om.request_face_status();
  for (auto vh : om.vertices()) {
    if (om.is_boundary(vh)) om.status(vh).set_locked(true);
  }
  OpenMesh::Decimater::DecimaterT<OmMesh> decimater(om);
  OpenMesh::Decimater::ModQuadricT<OmMesh>::Handle quadric;
  decimater.add(quadric);
  decimater.module(quadric).unset_max_err();
  decimater.initialize();
  decimater.decimate_to_faces(0, static_cast<size_t>(std::max<int64_t>(1, target_faces)));
  om.garbage_collection();

  TriangleMesh out;
  for (auto vh : om.vertices()) {
    const uint32_t i = om.property(original, vh);
    out.vertices_m.push_back(mesh.vertices_m[i]);  // halfedge collapse keeps input positions
    if (mesh.has_colors()) out.colors_rgb.push_back(mesh.colors_rgb[i]);
  }
  for (auto fh : om.faces()) {
    std::array<uint32_t, 3> tri{};
    int k = 0;
    for (auto vh : om.fv_range(fh)) {
      if (k < 3) tri[k] = static_cast<uint32_t>(vh.idx());
      ++k;
    }
    if (k == 3) out.faces.push_back(tri);
  }
  return out;
}

}  // namespace

TriangleMesh internal::FromKeptIndices(const TriangleMesh& mesh, const std::vector<uint32_t>& indices) {
  std::vector<int64_t> remap(mesh.num_vertices(), -1);
  for (uint32_t i : indices) remap[i] = 0;
  TriangleMesh out;
  for (size_t i = 0; i < mesh.num_vertices(); ++i) {
    if (remap[i] < 0) continue;
    remap[i] = static_cast<int64_t>(out.vertices_m.size());
    out.vertices_m.push_back(mesh.vertices_m[i]);
    if (mesh.has_colors()) out.colors_rgb.push_back(mesh.colors_rgb[i]);
  }
  out.faces.reserve(indices.size() / 3);
  for (size_t k = 0; k + 2 < indices.size(); k += 3) {
    out.faces.push_back({static_cast<uint32_t>(remap[indices[k]]), static_cast<uint32_t>(remap[indices[k + 1]]),
                         static_cast<uint32_t>(remap[indices[k + 2]])});
  }
  return out;
}

const char* DecimationMethodName(DecimationMethod method) {
  switch (method) {
    case DecimationMethod::kMeshoptimizer: return "meshoptimizer";
    case DecimationMethod::kMeshoptimizerPartitioned: return "meshoptimizer_partitioned";
    case DecimationMethod::kCgalGarlandHeckbert: return "cgal_garland_heckbert";
    case DecimationMethod::kCgalGarlandHeckbertProbabilistic: return "cgal_garland_heckbert_probabilistic";
    case DecimationMethod::kOpenMeshQuadric: return "openmesh_quadric";
    case DecimationMethod::kQemTiled: return "qem_tiled";
  }
  return "?";
}

std::vector<DecimationMethod> AllDecimationMethods() {
  return {DecimationMethod::kMeshoptimizer,
          DecimationMethod::kMeshoptimizerPartitioned,
          DecimationMethod::kQemTiled,
          DecimationMethod::kCgalGarlandHeckbert,
          DecimationMethod::kCgalGarlandHeckbertProbabilistic,
          DecimationMethod::kOpenMeshQuadric};
}

DecimationMethod ParseDecimationMethod(const std::string& text, const std::string& where) {
  for (DecimationMethod m : AllDecimationMethods()) {
    if (text == DecimationMethodName(m)) return m;
  }
  throw InputError(Located(where, "unknown decimation method '" + text + "'"));
}

TriangleMesh DecimateMesh(const TriangleMesh& mesh, const DecimateOptions& options, DecimateStats* stats) {
  if (mesh.has_colors() && mesh.colors_rgb.size() != mesh.num_vertices()) {
    throw InputError("decimate: colours: one per vertex expected");
  }
  for (const auto& f : mesh.faces) {
    for (uint32_t i : f) {
      if (i >= mesh.num_vertices()) throw InputError("decimate: vertex index out of range");
    }
  }
  DecimateStats s;
  s.faces_in = static_cast<int64_t>(mesh.num_faces());
  s.vertices_in = static_cast<int64_t>(mesh.num_vertices());
  TriangleMesh out;
  const bool has_goal = options.target_faces > 0 || options.max_error_m > 0;
  if (!has_goal || (options.target_faces > 0 && options.target_faces >= s.faces_in)) {
    out = internal::FromKeptIndices(mesh, MakeMeshoptInput(mesh).indices);
    s.simplifier_error_m = 0;
  } else {
    switch (options.method) {
      case DecimationMethod::kMeshoptimizer: out = DecimateMeshopt(mesh, options, &s.simplifier_error_m); break;
      case DecimationMethod::kMeshoptimizerPartitioned:
        out = DecimateMeshoptPartitioned(mesh, options, &s.simplifier_error_m);
        break;
      case DecimationMethod::kCgalGarlandHeckbert:
      case DecimationMethod::kCgalGarlandHeckbertProbabilistic:
        if (options.target_faces <= 0) {
          throw InputError("decimate: the CGAL methods need a face budget");
        }
        out = internal::DecimateCgal(mesh, options.target_faces,
                                     options.method == DecimationMethod::kCgalGarlandHeckbertProbabilistic);
        break;
      case DecimationMethod::kOpenMeshQuadric:
        if (options.target_faces <= 0) {
          throw InputError("decimate: the OpenMesh method needs a face budget");
        }
        out = DecimateOpenMesh(mesh, options.target_faces);
        break;
      case DecimationMethod::kQemTiled:
        if (options.target_faces > 0 && options.max_error_m > 0) {
          throw InputError("decimate: the qem_tiled method takes a face budget or an error goal, not both");
        }
        if (options.max_error_m > 0) {
          // The same goal at every vertex: collapses while their RMS distance to their planes is within it.
          const std::vector<double> goal_m(mesh.num_vertices(), options.max_error_m);
          out = internal::DecimateQemTiled(mesh, 0, options.qem.tiles, options.qem, &goal_m);
        } else {
          out = internal::DecimateQemTiled(mesh, options.target_faces, options.qem.tiles, options.qem);
        }
        break;
    }
  }
  s.faces_out = static_cast<int64_t>(out.num_faces());
  s.vertices_out = static_cast<int64_t>(out.num_vertices());
  if (stats) *stats = s;
  return out;
}

}  // namespace cinepath::photogrammetry
