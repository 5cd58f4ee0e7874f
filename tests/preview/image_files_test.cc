// The EXR writer read back through the OpenEXR library's InputFile: channels (stored in name order),
// size, ZIP compression, every value bit for bit; the same bytes on every call and in the file, no
// temporary file left behind. JPEG decoding in bands. The PNG writer read back. The sRGB encoding's ends.
#include "preview/image_files.h"

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <png.h>
#include <tbb/task_arena.h>
#include <unistd.h>
#include <algorithm>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>

#include <gtest/gtest.h>
// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>

#include "core/error.h"

namespace cinepath::preview {
namespace {

// An EXR file read back through OpenEXR's InputFile: its channels as stored, its size and compression, and
// the values in the order `channels` names them, interleaved per pixel.
struct ExrRead {
  std::vector<std::string> stored_channels;
  Imf::Compression compression = Imf::NO_COMPRESSION;
  std::vector<Imf::PixelType> types;  // each stored channel's
  int width = 0, height = 0;
  std::vector<float> values;
};

ExrRead ReadExr(const std::filesystem::path& path, const std::vector<std::string>& channels) {
  Imf::InputFile file(path.c_str(), 0);
  ExrRead r;
  const Imf::Header& header = file.header();
  for (auto it = header.channels().begin(); it != header.channels().end(); ++it) {
    r.types.push_back(it.channel().type);
    r.stored_channels.push_back(it.name());
  }
  r.compression = header.compression();
  const Imath::Box2i window = header.dataWindow();
  EXPECT_EQ(window.min, Imath::V2i(0, 0));
  EXPECT_EQ(header.displayWindow(), window);
  EXPECT_EQ(header.lineOrder(), Imf::INCREASING_Y);
  r.width = window.max.x + 1;
  r.height = window.max.y + 1;
  const size_t nc = channels.size();
  r.values.assign(size_t(r.width) * r.height * nc, std::numeric_limits<float>::quiet_NaN());
  Imf::FrameBuffer frame;
  for (size_t c = 0; c < nc; ++c) {
    frame.insert(channels[c], Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(r.values.data() + c), nc * sizeof(float),
                                         nc * sizeof(float) * size_t(r.width)));
  }
  file.setFrameBuffer(frame);
  file.readPixels(window.min.y, window.max.y);
  return r;
}

std::vector<uint8_t> FileBytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// A fresh directory for one test's files.
std::filesystem::path TestDir(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("cinepath_image_files_test_" + name + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

void ExpectBitIdentical(const std::vector<float>& written, const std::vector<float>& back) {
  ASSERT_EQ(written.size(), back.size());
  for (size_t i = 0; i < written.size(); ++i) {
    ASSERT_EQ(std::memcmp(&written[i], &back[i], 4), 0) << "value " << i;
  }
}

TEST(ExrWriter, OpenExrReadsEveryValueBackBitForBit) {
  const int w = 37, h = 41;  // ZIP blocks of 16 lines and a short last one
  const std::vector<std::string> channels{"R", "G", "B"};
  std::vector<float> values(size_t(w) * h * 3);
  for (size_t i = 0; i < values.size(); ++i) {
    values[i] = (i % 3 == 0) ? float(i) * 0.001f : (i % 3 == 1 ? 0.25f : -std::sqrt(float(i)));
  }
  values[5] = std::numeric_limits<float>::infinity();
  values[7] = std::numeric_limits<float>::denorm_min();
  values[8] = -0.0f;
  const auto dir = TestDir("rgb");
  const auto path = dir / "frame.exr";
  WriteExrAtomic(path, w, h, channels, values);
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir), std::filesystem::directory_iterator()), 1)
      << "the temporary file is renamed, not left beside";
  const ExrRead read = ReadExr(path, channels);
  EXPECT_EQ(read.compression, Imf::ZIP_COMPRESSION);
  EXPECT_EQ(read.width, w);
  EXPECT_EQ(read.height, h);
  EXPECT_EQ(read.stored_channels, (std::vector<std::string>{"B", "G", "R"}));  // OpenEXR's name order
  EXPECT_EQ(read.types, std::vector<Imf::PixelType>(3, Imf::FLOAT));
  ExpectBitIdentical(values, read.values);
  // The same input, the same bytes: from the file and from two more encodings.
  const std::vector<uint8_t> bytes = EncodeExr(w, h, channels, values);
  EXPECT_EQ(bytes, FileBytes(path));
  EXPECT_EQ(bytes, EncodeExr(w, h, channels, values));
  std::filesystem::remove_all(dir);
}

TEST(ExrWriter, HalfPixelsComeBackRoundedToElevenSignificantBits) {
  const int w = 37, h = 41;
  const std::vector<std::string> channels{"R", "G", "B"};
  std::vector<float> values(size_t(w) * h * 3);
  uint32_t state = 777;
  for (float& v : values) {  // linear radiance over eight decades, both signs
    state = state * 1664525u + 1013904223u;
    v = std::pow(10.0f, float(state >> 8) / float(1 << 24) * 8 - 4) * ((state & 1) ? 1.0f : -1.0f);
  }
  values[0] = 0.0f;
  values[1] = 65504.0f;  // the largest finite half
  values[2] = 1.0f / 3;
  const auto dir = TestDir("half");
  WriteExrAtomic(dir / "frame.exr", w, h, channels, values, ExrPixel::kHalf);
  const ExrRead read = ReadExr(dir / "frame.exr", channels);
  EXPECT_EQ(read.types, std::vector<Imf::PixelType>(3, Imf::HALF));
  EXPECT_EQ(read.compression, Imf::ZIP_COMPRESSION);
  ASSERT_EQ(read.values.size(), values.size());
  EXPECT_EQ(read.values[0], 0.0f);
  EXPECT_EQ(read.values[1], 65504.0f);
  EXPECT_EQ(read.values[2], 0.333251953125f);  // 1/3 to the nearest half: 1365 / 4096
  for (size_t i = 0; i < values.size(); ++i) {
    // Normal halves (|v| >= 2^-14) keep a relative error of at most 2^-11; smaller ones an absolute 2^-25.
    const float bound = std::max(std::abs(values[i]) * 0x1p-11f, 0x1p-25f);
    ASSERT_LE(std::abs(read.values[i] - values[i]), bound) << "value " << i << ": " << values[i];
  }
  // About half of float's bytes (this noise compresses in neither), and the same bytes every time.
  const std::vector<uint8_t> half_bytes = EncodeExr(w, h, channels, values, ExrPixel::kHalf);
  EXPECT_EQ(half_bytes, FileBytes(dir / "frame.exr"));
  EXPECT_LT(double(half_bytes.size()), 0.55 * double(EncodeExr(w, h, channels, values).size()));
  std::filesystem::remove_all(dir);
}

TEST(ExrWriter, NoiseThatDoesNotCompressComesBackBitForBit) {
  std::vector<float> values(64 * 16);
  uint32_t state = 12345;
  for (float& v : values) {
    state = state * 1664525u + 1013904223u;
    std::memcpy(&v, &state, 4);
    if (!std::isfinite(v)) v = 1;
  }
  const auto dir = TestDir("noise");
  WriteExrAtomic(dir / "depth.exr", 64, 16, {"Z"}, values);
  const ExrRead read = ReadExr(dir / "depth.exr", {"Z"});
  EXPECT_EQ(read.stored_channels, (std::vector<std::string>{"Z"}));
  EXPECT_EQ(read.width, 64);
  EXPECT_EQ(read.height, 16);
  ExpectBitIdentical(values, read.values);
  EXPECT_EQ(EncodeExr(64, 16, {"Z"}, values), EncodeExr(64, 16, {"Z"}, values));
  std::filesystem::remove_all(dir);
}

TEST(ExrWriter, ValuesThatDoNotMatchTheSizeAreAnError) {
  EXPECT_THROW(EncodeExr(4, 4, {"R", "G", "B"}, std::vector<float>(4 * 4)), RuntimeError);
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

// libjpeg's own decode of a JPEG, row by row into a zero-filled buffer: the reference bytes.
std::vector<uint8_t> ReferenceDecode(const std::vector<uint8_t>& encoded) {
  jpeg_decompress_struct jpeg{};
  jpeg_error_mgr error{};
  jpeg.err = jpeg_std_error(&error);
  jpeg_create_decompress(&jpeg);
  jpeg_mem_src(&jpeg, encoded.data(), static_cast<unsigned long>(encoded.size()));
  jpeg_read_header(&jpeg, TRUE);
  jpeg.out_color_space = JCS_RGB;
  jpeg_start_decompress(&jpeg);
  std::vector<uint8_t> rgb(size_t(jpeg.output_width) * jpeg.output_height * 3);
  while (jpeg.output_scanline < jpeg.output_height) {
    JSAMPROW row = &rgb[size_t(jpeg.output_scanline) * jpeg.output_width * 3];
    jpeg_read_scanlines(&jpeg, &row, 1);
  }
  jpeg_finish_decompress(&jpeg);
  jpeg_destroy_decompress(&jpeg);
  return rgb;
}

// The texels' buffer is neither zero-filled first nor, past 8 MB, in 4 KiB pages (huge pages are asked
// for): every byte must still be the decoder's.
TEST(JpegDecode, ALargeImageIsDecodedInFullIntoItsUnfilledBuffer) {
  const std::vector<uint8_t> jpeg = TestJpeg(1800, 1700, 2, 2);  // 9.2 MB of texels
  const std::vector<uint8_t> reference = ReferenceDecode(jpeg);
  for (int parts : {1, 2}) {
    const Srgb8Image image = DecodeJpeg(jpeg, "test", parts);
    ASSERT_EQ(image.rgb.size(), reference.size());
    EXPECT_TRUE(std::equal(image.rgb.begin(), image.rgb.end(), reference.begin())) << parts << " bands";
  }
}

// The shared decode splits where the second decoder finds the first when it starts: whenever that is,
// the same bytes as one decoder.
TEST(JpegDecode, TwoDecodersSplittingWhenTheSecondStartsGiveTheBytesOfOne) {
  for (const auto& [h, v] : {std::pair{1, 1}, std::pair{2, 2}, std::pair{2, 1}}) {
    const std::vector<uint8_t> jpeg = TestJpeg(301, 777, h, v);
    const Srgb8Image one = DecodeJpeg(jpeg, "test", 1);
    for (int run = 0; run < 20; ++run) {
      const Srgb8Image shared = DecodeJpegShared(jpeg, "test");
      ASSERT_EQ(shared.width, 301);
      ASSERT_EQ(shared.height, 777);
      EXPECT_TRUE(shared.rgb == one.rgb) << "sampling " << h << "x" << v << ", run " << run;
    }
  }
}

// Only the rows asked for: each of them holds the bytes of a full decode, whatever rows are skipped
// before, between and after them, and wherever the two decoders split.
TEST(JpegDecode, TheRowsWantedHoldTheBytesOfAFullDecode) {
  for (const auto& [h, v] : {std::pair{1, 1}, std::pair{2, 2}, std::pair{2, 1}}) {
    const std::vector<uint8_t> jpeg = TestJpeg(301, 777, h, v);
    const std::vector<uint8_t> reference = ReferenceDecode(jpeg);
    const std::vector<std::vector<std::pair<int, int>>> patterns = {
        {{0, 777}}, {{0, 1}}, {{776, 777}}, {{100, 300}, {500, 520}}, {{3, 4}, {17, 18}, {33, 40}, {700, 777}},
        {{0, 600}}, {}};
    for (const auto& pattern : patterns) {
      std::vector<uint8_t> wanted(777, 0);
      for (const auto& [begin, end] : pattern) std::fill(wanted.begin() + begin, wanted.begin() + end, 1);
      for (int run = 0; run < 5; ++run) {
        const Srgb8Image image = DecodeSrgb8(jpeg, "test", [&](int width, int height) {
          EXPECT_EQ(width, 301);
          EXPECT_EQ(height, 777);
          return wanted;
        });
        ASSERT_EQ(image.rgb.size(), reference.size());
        const size_t row_bytes = 301 * 3;
        for (size_t y = 0; y < 777; ++y) {
          if (!wanted[y]) continue;
          ASSERT_TRUE(std::equal(image.rgb.begin() + long(y * row_bytes), image.rgb.begin() + long((y + 1) * row_bytes),
                                 reference.begin() + long(y * row_bytes)))
              << "sampling " << h << "x" << v << ", row " << y << ", " << pattern.size() << " runs, run " << run;
        }
      }
    }
  }
  const std::vector<uint8_t> jpeg = TestJpeg(64, 64, 2, 2);
  EXPECT_THROW(DecodeSrgb8(jpeg, "test", [](int, int) { return std::vector<uint8_t>(3, 1); }), InternalError);
}

TEST(JpegDecode, TheSecondBandStartsOnAnMcuRowAfterTheFirstsRows) {
  for (int height : {512, 777, 4096}) {
    for (int done = 0; done <= height; done += 16) {
      const int start = JpegSecondBandStart(height, done);
      EXPECT_GE(start, std::min(done, height)) << height << " " << done;
      EXPECT_TRUE(start == height || start % 16 == 0) << height << " " << done;
      EXPECT_LE(start, height);
    }
    EXPECT_GT(JpegSecondBandStart(height, 0), height / 2);  // the skipped rows cost the second decoder
    EXPECT_EQ(JpegSecondBandStart(height, height - 16), height);
  }
}

TEST(JpegDecode, BrokenBytesAreAnInputError) {
  std::vector<uint8_t> jpeg = TestJpeg(64, 64, 2, 2);
  jpeg.resize(40);
  EXPECT_THROW(DecodeSrgb8(jpeg, "test"), InputError);
  EXPECT_THROW(DecodeSrgb8(std::vector<uint8_t>{1, 2, 3, 4}, "test"), InputError);
}

// The PNG writer (its own chunks, the zlib stream deflated by libdeflate) read back by libpng: the same
// size and bytes, for a small image and a tall one; the same file bytes whether one thread or several
// write it.
TEST(PngWriter, LibpngReadsBackEveryByteAndTheFileIsTheSameOnOneThread) {
  const auto dir = TestDir("png");
  for (const auto& [width, height] : {std::pair{7, 5}, std::pair{301, 777}}) {
    Srgb8Image image{width, height, ImageBytes(size_t(width) * height * 3)};
    uint32_t state = 11;
    for (auto& byte : image.rgb) byte = uint8_t((state = state * 1664525u + 1013904223u) >> 24);
    const std::filesystem::path path = dir / ("image_" + std::to_string(height) + ".png");
    WriteSrgb8Atomic(path, image);
    png_image read{};
    read.version = PNG_IMAGE_VERSION;
    ASSERT_TRUE(png_image_begin_read_from_file(&read, path.c_str())) << read.message;
    read.format = PNG_FORMAT_RGB;
    std::vector<uint8_t> rgb(PNG_IMAGE_SIZE(read));
    ASSERT_TRUE(png_image_finish_read(&read, nullptr, rgb.data(), 0, nullptr)) << read.message;
    EXPECT_EQ(int(read.width), width);
    EXPECT_EQ(int(read.height), height);
    EXPECT_TRUE(std::equal(rgb.begin(), rgb.end(), image.rgb.begin(), image.rgb.end())) << height << " rows";
    const std::filesystem::path one_thread = dir / ("one_" + std::to_string(height) + ".png");
    tbb::task_arena(1).execute([&] { WriteSrgb8Atomic(one_thread, image); });
    std::ifstream a(path, std::ios::binary), b(one_thread, std::ios::binary);
    EXPECT_TRUE(std::equal(std::istreambuf_iterator<char>(a), {}, std::istreambuf_iterator<char>(b), {}));
  }
  std::filesystem::remove_all(dir);
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

namespace cinepath::preview {
namespace {

// The table gives LinearToSrgb8's byte for every 61st float in [0, 1] (17 M of them), for the 7 floats
// around each of the 255 steps, and at the ends (below 0, 1 and above, infinity, NaN).
TEST(SrgbEncoding, TheTableGivesTheTransferFunctionsBytes) {
  auto at = [](uint32_t bits) {
    float x;
    std::memcpy(&x, &bits, sizeof x);
    return x;
  };
  for (uint32_t bits = 0; bits <= 0x3f800000u; bits += 61)
    ASSERT_EQ(LinearToSrgb8ByTable(at(bits)), LinearToSrgb8(at(bits))) << bits;
  for (int v = 1; v <= 255; ++v) {  // the steps themselves, to the bit
    uint32_t lo = 0, hi = 0x3f800000u;
    while (hi - lo > 1) (LinearToSrgb8(at(lo + (hi - lo) / 2)) >= v ? hi : lo) = lo + (hi - lo) / 2;
    for (uint32_t b = hi - 3; b <= hi + 3; ++b) EXPECT_EQ(LinearToSrgb8ByTable(at(b)), LinearToSrgb8(at(b))) << v;
  }
  for (float x :
       {-1.0f, 0.0f, 1.0f, 2.0f, std::numeric_limits<float>::infinity(), std::numeric_limits<float>::quiet_NaN()}) {
    EXPECT_EQ(LinearToSrgb8ByTable(x), LinearToSrgb8(x)) << x;
  }
}

}  // namespace
}  // namespace cinepath::preview
