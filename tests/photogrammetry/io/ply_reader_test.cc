#include "photogrammetry/io/ply_reader.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

#include "core/error.h"

namespace cinepath::photogrammetry {
namespace {

template <typename T>
void Put(std::string& out, T v, bool big) {
  char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (big) std::reverse(b, b + sizeof(T));
  out.append(b, sizeof(T));
}

// COLMAP's fused.ply layout: float x y z, float nx ny nz, uchar red green blue.
std::string FusedPly(bool big) {
  std::string s = std::string("ply\nformat ") + (big ? "binary_big_endian" : "binary_little_endian") +
                  " 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
                  "property float nx\nproperty float ny\nproperty float nz\nproperty uchar red\n"
                  "property uchar green\nproperty uchar blue\nend_header\n";
  const float v[2][6] = {{1.5f, -2.25f, 3.0f, 0, 0, 2}, {4, 5, 6, 1, 0, 0}};
  for (int i = 0; i < 2; ++i) {
    for (float f : v[i]) Put<float>(s, f, big);
    for (uint8_t c : {uint8_t(10 + i), uint8_t(20), uint8_t(255)}) s.push_back(static_cast<char>(c));
  }
  return s;
}

TEST(PlyReader, BinaryPointCloudsInBothEndiannesses) {
  for (bool big : {false, true}) {
    const PlyData d = ParsePly(FusedPly(big), "fused.ply");
    ASSERT_EQ(d.points.size(), 2u);
    EXPECT_EQ(d.points.positions_m[0], Eigen::Vector3d(1.5, -2.25, 3.0));
    EXPECT_EQ(d.points.normals[0], Eigen::Vector3d(0, 0, 1));  // normalized
    EXPECT_EQ(d.points.colors_rgb[1], (std::array<uint8_t, 3>{11, 20, 255}));
    EXPECT_FALSE(d.has_faces());
  }
}

TEST(PlyReader, AsciiMeshWithQuadAndExtraElements) {
  const std::string text =
      "ply\nformat ascii 1.0\ncomment made by hand\nelement vertex 4\nproperty double x\nproperty double y\n"
      "property double z\nproperty float value\nelement face 2\nproperty list uchar int vertex_indices\n"
      "element edge 1\nproperty int v1\nproperty int v2\nend_header\n"
      "0 0 0 0.5\n1 0 0 0.5\n1 1 0 0.5\n0 1 0.25 0.5\n3 0 1 2\n4 0 1 2 3\n0 1\n";
  const PlyData d = ParsePly(text, "m.ply");
  ASSERT_EQ(d.mesh.num_vertices(), 4u);
  ASSERT_EQ(d.mesh.num_faces(), 3u);  // the quad becomes a fan of 2
  EXPECT_EQ(d.mesh.faces[2], (std::array<uint32_t, 3>{0, 2, 3}));
  EXPECT_EQ(d.mesh.vertices_m[3], Eigen::Vector3d(0, 1, 0.25));
}

std::string ErrorOf(const std::string& data) {
  try {
    ParsePly(data, "x.ply");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PlyReader, ErrorsNameLineOrByteOffset) {
  const std::string head =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  EXPECT_EQ(ErrorOf(head + "0 0 0\n1 1 nan\n3 0 1 1\n"), "x.ply: line 11: vertex 1 is not finite");
  EXPECT_EQ(ErrorOf(head + "0 0 0\n1 1 1\n3 0 1 2\n"), "x.ply: line 12: face 0 refers to vertex 2, but there are 2");
  EXPECT_EQ(ErrorOf(head + "0 0 0\n1 1 1\n2 0 1\n"), "x.ply: line 12: face 0 has 2 vertices (needs 3 or more)");
  EXPECT_EQ(ErrorOf(head + "0 0 0\n"), "x.ply: line 10: truncated: expected another element line");
  EXPECT_EQ(ErrorOf("ply\nformat ascii 1.0\nelement vertex 1\nproperty quad x\nend_header\n"),
            "x.ply: line 4: unknown property type 'quad'");
  EXPECT_EQ(ErrorOf("PLY\n"), "x.ply: line 1: not a PLY file (no 'ply' magic line)");
  // Binary: every truncation is an error with a byte offset.
  const std::string bin = FusedPly(false);
  const size_t header = bin.find("end_header\n") + 11;
  for (size_t len = header; len < bin.size(); ++len) {
    const std::string msg = ErrorOf(bin.substr(0, len));
    EXPECT_NE(msg.find("x.ply: byte "), std::string::npos) << len << ": " << msg;
  }
  EXPECT_NE(ErrorOf(bin + "zz").find("2 unexpected trailing bytes"), std::string::npos);
  // Absurd counts fail before allocating.
  std::string huge = bin;
  huge.replace(huge.find("vertex 2"), 8, "vertex 99999999999");
  EXPECT_NE(ErrorOf(huge).find("truncated: element 'vertex' declares 99999999999"), std::string::npos);
  // An element without properties takes no bytes in binary: a huge count is read at once (found by
  // fuzz_ply: it used to loop 5e13 times), and a vertex element without x y z is an error.
  std::string empty_element = bin;
  empty_element.insert(empty_element.find("end_header"), "element note 50000050600079\n");
  EXPECT_EQ(ParsePly(empty_element, "x.ply").points.positions_m.size(), 2u);
  EXPECT_EQ(ErrorOf("ply\nformat binary_little_endian 1.0\nelement vertex 50000050600079\nend_header\n"),
            "x.ply: byte 77: element 'vertex' has no x, y, z properties");
  // ASCII counts are bounded by the text left, list lengths by the values on their line (fuzz_ply).
  EXPECT_EQ(ErrorOf("ply\nformat ascii 1.0\nelement vertex 5555555553\nproperty float x\nproperty float y\n"
                    "property float z\nend_header\n0 0 0\n"),
            "x.ply: line 7: truncated: element 'vertex' declares 5555555553 lines, 6 bytes left");
  EXPECT_EQ(ErrorOf(head + "0 0 0\n1 1 1\n3 0 1 1e127\n"),
            "x.ply: line 12: vertex index: '1e127' is out of range for its type");
  EXPECT_EQ(ErrorOf(head + "0 0 0\n1 1 1\n256 0 1\n"),
            "x.ply: line 12: list count: '256' is out of range for its type");
  std::string long_list = head;
  long_list.replace(long_list.find("uchar int"), 9, "uint int");
  EXPECT_EQ(ErrorOf(long_list + "0 0 0\n1 1 1\n4 0 1 1\n"),
            "x.ply: line 12: list count 4 exceeds the values left on the line");
}

}  // namespace
}  // namespace cinepath::photogrammetry
