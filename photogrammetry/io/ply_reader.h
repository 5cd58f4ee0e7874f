// PLY reader (ASCII, binary little- and big-endian) for COLMAP/OpenMVS/ODM outputs: a point cloud
// (fused.ply: x y z, optional nx ny nz, red green blue) or a mesh (meshed-*.ply: vertices + faces as
// `list <count type> <index type> vertex_indices|vertex_index`). Coordinates become doubles; polygons
// with more than 3 vertices are split into a triangle fan; properties and elements it does not know are
// skipped. Colours of any integer type are taken as 0..255 (uchar) or scaled from 0..65535 (ushort);
// float colours as 0..1.
//
// Errors are InputError naming the file and the header line, body line (ASCII) or byte offset (binary):
// truncation, unknown types or formats, NaN/Inf coordinates, face indices out of range, lists of fewer
// than 3 vertices.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

#include "photogrammetry/io/point_cloud.h"
#include "photogrammetry/mesh/triangle_mesh.h"

namespace cinepath::photogrammetry {

struct PlyData {
  PointCloud points;  // every vertex (positions, and normals/colours when present)
  TriangleMesh mesh;  // the same vertices + the faces; no faces for a point cloud
  bool has_faces() const { return !mesh.faces.empty(); }
};

PlyData ParsePly(std::string_view data, const std::string& source);
PlyData ReadPly(const std::filesystem::path& path);

}  // namespace cinepath::photogrammetry
