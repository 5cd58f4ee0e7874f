// The EXR writer against a reader written here from the OpenEXR file layout (header attributes, offset
// table, ZIP blocks: zlib, then the delta predictor and the even/odd byte split undone): every value
// comes back bit for bit, channels in name order; the same bytes on every call. The sRGB encoding's ends.
#include "preview/image_files.h"

#include <zlib.h>

#include <cstdio>
#include <cstdlib>

#include <cmath>
#include <cstring>
#include <limits>
#include <map>

#include <gtest/gtest.h>
// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>

#include "core/error.h"

namespace cinepath::preview {
namespace {

struct ExrRead {
  std::map<std::string, std::string> attribute_types;
  std::vector<std::string> channels;  // as stored
  int compression = -1;
  int width = 0, height = 0;
  std::vector<float> values;  // per pixel, channels as stored
};

uint32_t U32(const std::vector<uint8_t>& b, size_t at) {
  return uint32_t(b[at]) | uint32_t(b[at + 1]) << 8 | uint32_t(b[at + 2]) << 16 | uint32_t(b[at + 3]) << 24;
}

ExrRead ReadExr(const std::vector<uint8_t>& b) {
  ExrRead r;
  EXPECT_EQ(U32(b, 0), 20000630u);
  EXPECT_EQ(U32(b, 4), 2u);
  size_t at = 8;
  auto str = [&] {
    std::string s(reinterpret_cast<const char*>(&b[at]));
    at += s.size() + 1;
    return s;
  };
  while (b[at] != 0) {
    const std::string name = str(), type = str();
    const uint32_t size = U32(b, at);
    at += 4;
    r.attribute_types[name] = type;
    if (name == "channels") {
      size_t c = at;
      while (b[c] != 0) {
        std::string channel(reinterpret_cast<const char*>(&b[c]));
        c += channel.size() + 1;
        EXPECT_EQ(U32(b, c), 2u);  // FLOAT
        c += 16;
        r.channels.push_back(channel);
      }
    } else if (name == "compression") {
      r.compression = b[at];
    } else if (name == "dataWindow") {
      r.width = int(U32(b, at + 8)) + 1;
      r.height = int(U32(b, at + 12)) + 1;
    }
    at += size;
  }
  ++at;
  const size_t nc = r.channels.size();
  r.values.resize(size_t(r.width) * r.height * nc);
  const int blocks = (r.height + 15) / 16;
  for (int k = 0; k < blocks; ++k) {
    const size_t offset = size_t(U32(b, at + 8 * size_t(k)));
    const int y0 = int(U32(b, offset));
    const uint32_t size = U32(b, offset + 4);
    const int lines = std::min(16, r.height - y0);
    const size_t raw_size = size_t(lines) * r.width * nc * 4;
    std::vector<uint8_t> raw(raw_size);
    if (size < raw_size) {
      std::vector<uint8_t> t(raw_size);
      uLongf n = uLongf(raw_size);
      EXPECT_EQ(uncompress(t.data(), &n, &b[offset + 8], size), Z_OK);
      EXPECT_EQ(n, raw_size);
      for (size_t i = 1; i < t.size(); ++i) t[i] = uint8_t(int(t[i - 1]) + int(t[i]) - 128);
      const size_t half = (raw_size + 1) / 2;
      for (size_t i = 0; i < raw_size; ++i) raw[i] = i % 2 == 0 ? t[i / 2] : t[half + i / 2];
    } else {
      std::memcpy(raw.data(), &b[offset + 8], raw_size);
    }
    size_t p = 0;
    for (int y = y0; y < y0 + lines; ++y) {
      for (size_t c = 0; c < nc; ++c) {
        for (int x = 0; x < r.width; ++x, p += 4)
          std::memcpy(&r.values[(size_t(y) * r.width + x) * nc + c], &raw[p], 4);
      }
    }
  }
  return r;
}

TEST(ExrWriter, EveryValueComesBackBitForBitInNameOrder) {
  const int w = 37, h = 41;  // blocks of 16 lines and a short last one
  std::vector<float> values(size_t(w) * h * 3);
  for (size_t i = 0; i < values.size(); ++i) {
    values[i] = (i % 3 == 0) ? float(i) * 0.001f : (i % 3 == 1 ? 0.25f : -std::sqrt(float(i)));
  }
  values[5] = std::numeric_limits<float>::infinity();
  const std::vector<uint8_t> bytes = EncodeExr(w, h, {"R", "G", "B"}, values);
  EXPECT_EQ(bytes, EncodeExr(w, h, {"R", "G", "B"}, values));
  const ExrRead read = ReadExr(bytes);
  EXPECT_EQ(read.compression, 3);  // ZIP
  EXPECT_EQ(read.width, w);
  EXPECT_EQ(read.height, h);
  ASSERT_EQ(read.channels, (std::vector<std::string>{"B", "G", "R"}));
  for (const char* required : {"channels", "compression", "dataWindow", "displayWindow", "lineOrder",
                               "pixelAspectRatio", "screenWindowCenter", "screenWindowWidth"}) {
    EXPECT_TRUE(read.attribute_types.count(required)) << required;
  }
  for (size_t i = 0; i < size_t(w) * h; ++i) {
    for (int c = 0; c < 3; ++c) {
      const float written = values[3 * i + size_t(c)], back = read.values[3 * i + size_t(2 - c)];
      ASSERT_EQ(std::memcmp(&written, &back, 4), 0) << "pixel " << i << " channel " << c;
    }
  }
}

TEST(ExrWriter, NoiseThatDoesNotCompressIsStoredRaw) {
  std::vector<float> values(64 * 16);
  uint32_t state = 12345;
  for (float& v : values) {
    state = state * 1664525u + 1013904223u;
    std::memcpy(&v, &state, 4);
    if (!std::isfinite(v)) v = 1;
  }
  const ExrRead read = ReadExr(EncodeExr(64, 16, {"Z"}, values));
  for (size_t i = 0; i < values.size(); ++i) ASSERT_EQ(std::memcmp(&values[i], &read.values[i], 4), 0);
}

// A JPEG of a smooth pattern with noise, through libjpeg with the given chroma subsampling.
std::vector<uint8_t> TestJpeg(int width, int height, int h_samp, int v_samp) {
  std::vector<uint8_t> rgb(size_t(width) * height * 3);
  uint32_t state = 7;
  for (size_t i = 0; i < rgb.size(); ++i) {
    state = state * 1664525u + 1013904223u;
    rgb[i] = uint8_t((i / 3 % size_t(width)) * 255 / size_t(width) / 2 + (i / 3 / size_t(width)) % 97 + (state >> 28));
  }
  jpeg_compress_struct jpeg{};
  jpeg_error_mgr error{};
  jpeg.err = jpeg_std_error(&error);
  jpeg_create_compress(&jpeg);
  unsigned char* out = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&jpeg, &out, &size);
  jpeg.image_width = JDIMENSION(width);
  jpeg.image_height = JDIMENSION(height);
  jpeg.input_components = 3;
  jpeg.in_color_space = JCS_RGB;
  jpeg_set_defaults(&jpeg);
  jpeg_set_quality(&jpeg, 90, TRUE);
  jpeg.comp_info[0].h_samp_factor = h_samp;
  jpeg.comp_info[0].v_samp_factor = v_samp;
  jpeg_start_compress(&jpeg, TRUE);
  while (jpeg.next_scanline < jpeg.image_height) {
    JSAMPROW row = &rgb[size_t(jpeg.next_scanline) * size_t(width) * 3];
    jpeg_write_scanlines(&jpeg, &row, 1);
  }
  jpeg_finish_compress(&jpeg);
  jpeg_destroy_compress(&jpeg);
  std::vector<uint8_t> bytes(out, out + size);
  free(out);
  return bytes;
}

TEST(JpegDecode, BandsDecodedAtOnceGiveTheBytesOfOneDecoder) {
  for (const auto& [h, v] : {std::pair{1, 1}, std::pair{2, 2}, std::pair{2, 1}}) {
    const std::vector<uint8_t> jpeg = TestJpeg(301, 777, h, v);  // not a multiple of the iMCU height
    const Srgb8Image one = DecodeJpeg(jpeg, "test", 1);
    ASSERT_EQ(one.width, 301);
    ASSERT_EQ(one.height, 777);
    for (int parts : {2, 3, 4}) {
      const Srgb8Image banded = DecodeJpeg(jpeg, "test", parts);
      EXPECT_TRUE(banded.rgb == one.rgb) << "sampling " << h << "x" << v << ", " << parts << " bands";
    }
    EXPECT_TRUE(DecodeSrgb8(jpeg, "test").rgb == one.rgb);
  }
}

TEST(JpegDecode, BrokenBytesAreAnInputError) {
  std::vector<uint8_t> jpeg = TestJpeg(64, 64, 2, 2);
  jpeg.resize(40);
  EXPECT_THROW(DecodeSrgb8(jpeg, "test"), InputError);
  EXPECT_THROW(DecodeSrgb8(std::vector<uint8_t>{1, 2, 3, 4}, "test"), InputError);
}

TEST(Srgb8, Ends) {
  EXPECT_EQ(LinearToSrgb8(-1), 0);
  EXPECT_EQ(LinearToSrgb8(0), 0);
  EXPECT_EQ(LinearToSrgb8(1), 255);
  EXPECT_EQ(LinearToSrgb8(std::numeric_limits<float>::quiet_NaN()), 0);
  EXPECT_EQ(LinearToSrgb8(0.2159f), 128);  // 128/255 in sRGB is 0.2159 linear
}

}  // namespace
}  // namespace cinepath::preview
