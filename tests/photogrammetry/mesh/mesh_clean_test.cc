#include "photogrammetry/mesh/mesh_clean.h"

#include <algorithm>
#include <map>
#include <set>
#include <utility>

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include "tests/photogrammetry/surface_test_meshes.h"

namespace cinepath::photogrammetry {
namespace {

// Directed edge use counts: a consistently oriented 2-manifold uses each directed edge once.
void ExpectOrientedManifold(const TriangleMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> directed;
  for (const auto& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) ++directed[{f[k], f[(k + 1) % 3]}];
  }
  for (const auto& [edge, count] : directed) {
    EXPECT_EQ(count, 1) << "directed edge " << edge.first << "->" << edge.second;
  }
}

int CountBoundaryEdges(const TriangleMesh& mesh) {
  std::map<std::pair<uint32_t, uint32_t>, int> undirected;
  for (const auto& f : mesh.faces) {
    for (int k = 0; k < 3; ++k) {
      ++undirected[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}];
    }
  }
  return static_cast<int>(
      std::count_if(undirected.begin(), undirected.end(), [](const auto& e) { return e.second == 1; }));
}

double NormalUp(const TriangleMesh& mesh, const std::array<uint32_t, 3>& f) {
  const auto& a = mesh.vertices_m[f[0]];
  return (mesh.vertices_m[f[1]] - a).cross(mesh.vertices_m[f[2]] - a).z();
}

TEST(CleanMesh, CleanGridIsUnchangedAndItsOuterBorderIsNotAHole) {
  const TriangleMesh grid = testing::TerrainGrid(10, 10, 1.0);
  MeshCleanReport report;
  const TriangleMesh out = CleanMesh(grid, MeshCleanOptions{}, &report);
  EXPECT_EQ(out.num_faces(), grid.num_faces());
  EXPECT_EQ(out.num_vertices(), grid.num_vertices());
  EXPECT_EQ(report.holes_filled, 0);
  EXPECT_EQ(report.holes_left_open, 1);
  EXPECT_EQ(report.small_components_removed, 0);
  EXPECT_EQ(CountBoundaryEdges(out), 4 * 9);
  ASSERT_EQ(out.colors_rgb.size(), out.num_vertices());
  ExpectOrientedManifold(out);
}

TEST(CleanMesh, RepairsEveryDefectKind) {
  TriangleMesh mesh = testing::TerrainGrid(10, 10, 1.0);
  const size_t grid_faces = mesh.num_faces();
  auto id = [](int i, int j) { return static_cast<uint32_t>(j * 10 + i); };
  // A hole: drop the two triangles of cell (4, 4).
  mesh.faces.erase(
      std::remove_if(mesh.faces.begin(), mesh.faces.end(), [&](const auto& f) { return f[0] == id(4, 4); }),
      mesh.faces.end());
  ASSERT_EQ(mesh.num_faces(), grid_faces - 2);
  // A duplicate vertex (copy of (2, 2)) used by one face instead of the original.
  mesh.vertices_m.push_back(mesh.vertices_m[id(2, 2)]);
  mesh.colors_rgb.push_back(mesh.colors_rgb[id(2, 2)]);
  const uint32_t copy = static_cast<uint32_t>(mesh.num_vertices() - 1);
  for (auto& f : mesh.faces) {
    if (f[0] == id(2, 2)) {
      f[0] = copy;
      break;
    }
  }
  // A duplicate face (reversed) and a face with a repeated corner.
  mesh.faces.push_back({mesh.faces[0][0], mesh.faces[0][2], mesh.faces[0][1]});
  mesh.faces.push_back({id(0, 0), id(0, 0), id(1, 0)});
  // A zero-area face: a new vertex on the segment between (6,0) and (7,0).
  mesh.vertices_m.push_back(0.5 * (mesh.vertices_m[id(6, 0)] + mesh.vertices_m[id(7, 0)]));
  mesh.colors_rgb.push_back({0, 0, 0});
  mesh.faces.push_back({id(6, 0), static_cast<uint32_t>(mesh.num_vertices() - 1), id(7, 0)});
  // A fin: a third triangle on the interior edge (7,7)-(8,8) makes it non-manifold.
  mesh.vertices_m.push_back(mesh.vertices_m[id(7, 7)] + Eigen::Vector3d(0, 0, 2));
  mesh.colors_rgb.push_back({0, 0, 0});
  mesh.faces.push_back({id(7, 7), id(8, 8), static_cast<uint32_t>(mesh.num_vertices() - 1)});
  // A floating blob: a 3 × 3-vertex patch (8 faces) 100 m away.
  const uint32_t base = static_cast<uint32_t>(mesh.num_vertices());
  for (int j = 0; j < 3; ++j) {
    for (int i = 0; i < 3; ++i) {
      mesh.vertices_m.emplace_back(100.0 + i, 100.0 + j, 5.0);
      mesh.colors_rgb.push_back({1, 2, 3});
    }
  }
  for (int j = 0; j < 2; ++j) {
    for (int i = 0; i < 2; ++i) {
      const uint32_t a = base + j * 3 + i;
      mesh.faces.push_back({a, a + 1, a + 4});
      mesh.faces.push_back({a, a + 4, a + 3});
    }
  }
  // An isolated vertex.
  mesh.vertices_m.emplace_back(-50.0, -50.0, 0.0);
  mesh.colors_rgb.push_back({9, 9, 9});

  MeshCleanReport report;
  const TriangleMesh out = CleanMesh(mesh, MeshCleanOptions{}, &report);
  EXPECT_EQ(report.duplicate_vertices_merged, 1);
  EXPECT_EQ(report.duplicate_faces_removed, 1);
  EXPECT_EQ(report.invalid_faces_removed, 1);
  EXPECT_EQ(report.degenerate_faces_removed, 1);
  EXPECT_GE(report.non_manifold_vertices_split, 2);
  EXPECT_TRUE(report.general_path);               // the fin is a non-manifold edge
  EXPECT_EQ(report.small_components_removed, 2);  // the blob and the split-off fin
  EXPECT_EQ(report.faces_in_small_components, 9);
  EXPECT_EQ(report.components_kept, 1);
  EXPECT_EQ(report.holes_filled, 1);
  EXPECT_GE(report.hole_faces_added, 2);
  EXPECT_EQ(report.holes_left_open, 1);
  EXPECT_GE(report.isolated_vertices_removed, 2);  // the lone vertex and the degenerate face's

  EXPECT_EQ(static_cast<int64_t>(out.num_faces()), report.faces_out);
  EXPECT_GE(out.num_faces(), grid_faces);
  EXPECT_EQ(CountBoundaryEdges(out), 4 * 9);  // only the outer border is left open
  ExpectOrientedManifold(out);
  for (const auto& f : out.faces) EXPECT_GT(NormalUp(out, f), 0.0);
  ASSERT_EQ(out.colors_rgb.size(), out.num_vertices());
  for (const auto& v : out.vertices_m) EXPECT_LT(v.x(), 50.0);  // the blob is gone
}

TEST(CleanMesh, InconsistentOrientationIsRepairedTowardTheMajority) {
  TriangleMesh mesh = testing::TerrainGrid(8, 8, 1.0);
  for (size_t f = 0; f < mesh.num_faces(); f += 7) std::swap(mesh.faces[f][1], mesh.faces[f][2]);
  MeshCleanReport report;
  const TriangleMesh out = CleanMesh(mesh, MeshCleanOptions{}, &report);
  EXPECT_EQ(out.num_faces(), mesh.num_faces());
  EXPECT_EQ(report.faces_reoriented, static_cast<int64_t>((mesh.num_faces() + 6) / 7));
  ExpectOrientedManifold(out);
  for (const auto& f : out.faces) EXPECT_GT(NormalUp(out, f), 0.0);
}

TEST(CleanMesh, LargeHolesStayOpen) {
  TriangleMesh mesh = testing::TerrainGrid(20, 20, 1.0);
  // Remove a 6 × 6-cell block: its border has 24 edges and a perimeter of ~24 m.
  auto in_block = [](const Eigen::Vector3d& v) { return v.x() > 5 && v.x() < 12 && v.y() > 5 && v.y() < 12; };
  mesh.faces.erase(std::remove_if(mesh.faces.begin(), mesh.faces.end(),
                                  [&](const auto& f) {
                                    const Eigen::Vector3d c =
                                        (mesh.vertices_m[f[0]] + mesh.vertices_m[f[1]] + mesh.vertices_m[f[2]]) / 3.0;
                                    return c.x() > 6 && c.x() < 12 && c.y() > 6 && c.y() < 12;
                                  }),
                   mesh.faces.end());
  (void)in_block;
  MeshCleanOptions small_holes_only;
  small_holes_only.max_hole_perimeter_m = 10.0;
  MeshCleanReport report;
  CleanMesh(mesh, small_holes_only, &report);
  EXPECT_EQ(report.holes_filled, 0);
  EXPECT_EQ(report.holes_left_open, 2);
  MeshCleanOptions fill_all;
  fill_all.max_hole_perimeter_m = 100.0;
  CleanMesh(mesh, fill_all, &report);
  EXPECT_EQ(report.holes_filled, 1);
}

// A manifold soup (after merging duplicates) takes the fast path: no Surface_mesh of the whole
// mesh. Same repairs as the general path: small components dropped, small holes filled (on a local
// Surface_mesh), duplicates and degenerate faces removed, isolated vertices dropped.
TEST(CleanMesh, ManifoldSoupFastPathRepairsHolesBlobsAndDuplicates) {
  TriangleMesh mesh = testing::TerrainGrid(20, 20, 1.0);
  const size_t grid_faces = mesh.num_faces();
  auto id = [](int i, int j) { return static_cast<uint32_t>(j * 20 + i); };
  // Three separate one-cell holes and a 2 × 1-cell hole.
  auto drop_cell = [&](int i, int j) {
    mesh.faces.erase(
        std::remove_if(mesh.faces.begin(), mesh.faces.end(), [&](const auto& f) { return f[0] == id(i, j); }),
        mesh.faces.end());
  };
  drop_cell(4, 4);
  drop_cell(10, 4);
  drop_cell(4, 12);
  drop_cell(12, 12);
  drop_cell(13, 12);
  ASSERT_EQ(mesh.num_faces(), grid_faces - 10);
  // A duplicate vertex used by one face, a duplicate face, a zero-area face, an isolated vertex.
  mesh.vertices_m.push_back(mesh.vertices_m[id(2, 2)]);
  mesh.colors_rgb.push_back(mesh.colors_rgb[id(2, 2)]);
  for (auto& f : mesh.faces) {
    if (f[0] == id(2, 2)) {
      f[0] = static_cast<uint32_t>(mesh.num_vertices() - 1);
      break;
    }
  }
  mesh.faces.push_back(mesh.faces[7]);
  mesh.faces.push_back({id(6, 0), id(7, 0), id(6, 0)});
  mesh.vertices_m.emplace_back(-50.0, -50.0, 0.0);
  mesh.colors_rgb.push_back({9, 9, 9});
  // Two floating blobs (8 faces each), 100 m away.
  for (int b = 0; b < 2; ++b) {
    const uint32_t base = static_cast<uint32_t>(mesh.num_vertices());
    for (int j = 0; j < 3; ++j) {
      for (int i = 0; i < 3; ++i) {
        mesh.vertices_m.emplace_back(100.0 + i + 10 * b, 100.0 + j, 5.0);
        mesh.colors_rgb.push_back({1, 2, 3});
      }
    }
    for (uint32_t j = 0; j < 2; ++j) {
      for (uint32_t i = 0; i < 2; ++i) {
        const uint32_t a = base + j * 3 + i;
        mesh.faces.push_back({a, a + 1, a + 4});
        mesh.faces.push_back({a, a + 4, a + 3});
      }
    }
  }
  MeshCleanReport report;
  const TriangleMesh out = CleanMesh(mesh, MeshCleanOptions{}, &report);
  EXPECT_EQ(report.duplicate_vertices_merged, 1);
  EXPECT_EQ(report.duplicate_faces_removed, 1);
  EXPECT_EQ(report.invalid_faces_removed, 1);
  EXPECT_EQ(report.non_manifold_vertices_split, 0);
  EXPECT_FALSE(report.general_path);
  EXPECT_EQ(report.faces_reoriented, 0);
  EXPECT_EQ(report.small_components_removed, 2);
  EXPECT_EQ(report.faces_in_small_components, 16);
  EXPECT_EQ(report.components_kept, 1);
  EXPECT_EQ(report.holes_filled, 4);
  EXPECT_GE(report.hole_faces_added, 10);
  EXPECT_EQ(report.holes_left_open, 1);
  EXPECT_EQ(report.isolated_vertices_removed, 1);
  EXPECT_EQ(CountBoundaryEdges(out), 4 * 19);
  ExpectOrientedManifold(out);
  for (const auto& f : out.faces) EXPECT_GT(NormalUp(out, f), 0.0);
  ASSERT_EQ(out.colors_rgb.size(), out.num_vertices());
  for (const auto& v : out.vertices_m) EXPECT_LT(v.x(), 50.0);
  EXPECT_EQ(static_cast<int64_t>(out.num_faces()), report.faces_out);
  EXPECT_EQ(static_cast<int64_t>(out.num_vertices()), report.vertices_out);

  // Deterministic at any thread count.
  TriangleMesh one_thread;
  {
    tbb::global_control cap(tbb::global_control::max_allowed_parallelism, 1);
    one_thread = CleanMesh(mesh, MeshCleanOptions{}, nullptr);
  }
  EXPECT_EQ(one_thread.faces, out.faces);
  EXPECT_EQ(one_thread.vertices_m, out.vertices_m);
  EXPECT_EQ(one_thread.colors_rgb, out.colors_rgb);
}

// The fast path and the general path agree on a mesh both can clean: the same faces once the
// general path is forced by one inconsistently oriented face far from the holes.
TEST(CleanMesh, FastAndGeneralPathsFillTheSameHole) {
  TriangleMesh mesh = testing::TerrainGrid(12, 12, 1.0);
  mesh.faces.erase(
      std::remove_if(mesh.faces.begin(), mesh.faces.end(), [](const auto& f) { return f[0] == 5 * 12 + 5; }),
      mesh.faces.end());
  MeshCleanReport fast_report, general_report;
  const TriangleMesh fast = CleanMesh(mesh, MeshCleanOptions{}, &fast_report);
  TriangleMesh flipped = mesh;
  std::swap(flipped.faces[0][1], flipped.faces[0][2]);
  const TriangleMesh general = CleanMesh(flipped, MeshCleanOptions{}, &general_report);
  EXPECT_EQ(general_report.faces_reoriented, 1);
  EXPECT_EQ(fast_report.holes_filled, 1);
  EXPECT_EQ(general_report.holes_filled, 1);
  EXPECT_EQ(fast_report.hole_faces_added, general_report.hole_faces_added);
  EXPECT_EQ(fast.num_faces(), general.num_faces());
  EXPECT_EQ(fast.num_vertices(), general.num_vertices());
  ExpectOrientedManifold(fast);
}

}  // namespace
}  // namespace cinepath::photogrammetry

namespace cinepath::photogrammetry {
namespace {

TEST(CleanMesh, BowtieVertexIsSplit) {
  // Two fans that touch only at vertex 0: a non-manifold vertex (no non-manifold edge).
  TriangleMesh mesh;
  mesh.vertices_m = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {-1, 0, 0}, {-1, -1, 0}, {0, -1, 0}};
  mesh.faces = {{0, 1, 2}, {0, 2, 3}, {0, 4, 5}, {0, 5, 6}};
  MeshCleanOptions keep_everything;
  keep_everything.min_component_faces = 1;
  keep_everything.min_component_fraction = 0;
  MeshCleanReport report;
  const TriangleMesh out = CleanMesh(mesh, keep_everything, &report);
  EXPECT_EQ(report.non_manifold_vertices_split, 1);
  EXPECT_EQ(report.components_kept, 2);
  EXPECT_EQ(out.num_faces(), 4u);
  EXPECT_EQ(out.num_vertices(), 8u);
}

// A bowtie alone no longer sends the mesh to the general path: the fast path splits it and cleans
// the rest, with the same result as the general path (forced by one flipped face).
TEST(CleanMesh, BowtieOnTerrainFastAndGeneralPathsAgree) {
  TriangleMesh mesh = testing::TerrainGrid(12, 12, 1.0);
  const uint32_t pinch = 6 * 12 + 6;  // an interior vertex: its own fan is closed
  const uint32_t a = static_cast<uint32_t>(mesh.num_vertices());
  const Eigen::Vector3d p = mesh.vertices_m[pinch];
  for (const Eigen::Vector3d& d :
       {Eigen::Vector3d(0.3, 0, 2), Eigen::Vector3d(0, 0.3, 2), Eigen::Vector3d(-0.3, 0, 2)}) {
    mesh.vertices_m.push_back(p + d);
    mesh.colors_rgb.push_back({7, 7, 7});
  }
  mesh.faces.push_back({pinch, a, a + 1});  // a second fan at `pinch`, two faces
  mesh.faces.push_back({pinch, a + 1, a + 2});
  MeshCleanOptions keep_fans;
  keep_fans.min_component_faces = 1;
  keep_fans.min_component_fraction = 0;
  MeshCleanReport fast_report, general_report;
  const TriangleMesh fast = CleanMesh(mesh, keep_fans, &fast_report);
  TriangleMesh flipped = mesh;
  std::swap(flipped.faces[0][1], flipped.faces[0][2]);
  const TriangleMesh general = CleanMesh(flipped, keep_fans, &general_report);
  EXPECT_FALSE(fast_report.general_path);
  EXPECT_TRUE(general_report.general_path);
  EXPECT_EQ(fast_report.faces_reoriented, 0);
  EXPECT_EQ(general_report.faces_reoriented, 1);
  EXPECT_EQ(fast_report.non_manifold_vertices_split, 1);
  EXPECT_EQ(general_report.non_manifold_vertices_split, 1);
  EXPECT_EQ(fast_report.components_kept, 2);
  EXPECT_EQ(general_report.components_kept, 2);
  EXPECT_EQ(fast.num_faces(), mesh.num_faces());
  EXPECT_EQ(fast.num_vertices(), mesh.num_vertices() + 1);
  EXPECT_EQ(fast.num_faces(), general.num_faces());
  EXPECT_EQ(fast.num_vertices(), general.num_vertices());
  ExpectOrientedManifold(fast);
  ASSERT_EQ(fast.colors_rgb.size(), fast.num_vertices());
  // With the default small-component rule the two-face fan goes; the terrain stays whole.
  MeshCleanReport default_report;
  const TriangleMesh cleaned = CleanMesh(mesh, MeshCleanOptions{}, &default_report);
  EXPECT_EQ(default_report.small_components_removed, 1);
  EXPECT_EQ(cleaned.num_faces(), mesh.num_faces() - 2);
  EXPECT_EQ(cleaned.num_vertices(), mesh.num_vertices() - 3);
}

}  // namespace
}  // namespace cinepath::photogrammetry
