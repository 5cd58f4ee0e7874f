#include "preview/image_files.h"

#include <libdeflate.h>
#include <png.h>
#include <sys/mman.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_group.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <csetjmp>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <mutex>

// jpeglib.h needs FILE and size_t declared first.
#include <jpeglib.h>

#include <Imath/half.h>
#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfIO.h>
#include <OpenEXR/ImfOutputFile.h>
#include <OpenEXR/ImfStringAttribute.h>

#define STB_TRUETYPE_IMPLEMENTATION
#define STBTT_STATIC
#include <stb/stb_truetype.h>

#include "core/error.h"
#include "core/file_io.h"

namespace cinepath::preview {
namespace {

namespace fs = std::filesystem;

fs::path TempPathFor(const fs::path& target) {
  return target.parent_path() /
         ("." + target.stem().string() + ".tmp" + std::to_string(getpid()) + target.extension().string());
}

// Writes through `write(FILE*)` into a temporary file beside `path`, renamed once complete.
template <typename Write>
void WriteFileAtomicWith(const fs::path& path, Write write) {
  const fs::path temp = TempPathFor(path);
  FILE* file = std::fopen(temp.c_str(), "wb");
  if (!file) throw RuntimeError(path.string() + ": cannot write: " + std::strerror(errno));
  std::string error;
  try {
    write(file);
  } catch (const std::exception& e) {
    error = e.what();
  }
  if (std::fflush(file) != 0 && error.empty()) error = std::strerror(errno);
  if (std::fclose(file) != 0 && error.empty()) error = std::strerror(errno);
  std::error_code ignored;
  if (!error.empty()) {
    fs::remove(temp, ignored);
    throw RuntimeError(path.string() + ": cannot write: " + error);
  }
  std::error_code rename_error;
  fs::rename(temp, path, rename_error);
  if (rename_error) {
    fs::remove(temp, ignored);
    throw RuntimeError(path.string() + ": cannot write: " + rename_error.message());
  }
}

// PNG's chunk: length, type, data, CRC-32 of type and data.
void AppendPngChunk(std::vector<uint8_t>* out, const char* type, const uint8_t* data, size_t size) {
  auto put32 = [out](uint32_t v) {
    for (int shift = 24; shift >= 0; shift -= 8) out->push_back(uint8_t(v >> shift));
  };
  put32(uint32_t(size));
  const size_t start = out->size();
  out->insert(out->end(), type, type + 4);
  if (size > 0) out->insert(out->end(), data, data + size);
  put32(libdeflate_crc32(0, out->data() + start, size + 4));
}

// The PNG file's bytes (8-bit RGB, sRGB, a Software text; the chunks libpng wrote here before): every row
// with the Sub filter (filter byte 1, each byte minus the one a pixel left), the whole as one zlib stream
// deflated by libdeflate at level 1. On a 640 x 360 draft frame that took 5.8 ms of one core against 13.3
// ms for zlib's level 1 (which the writer used before, in two bands of rows at once), for a file 2 % smaller
// (docs/render.md, "Start-up: where the time goes"). One stream on one thread: the same bytes on any thread count.
std::vector<uint8_t> EncodePng(const Srgb8Image& image) {
  const size_t row_bytes = size_t(image.width) * 3 + 1;
  std::vector<uint8_t> filtered(row_bytes * size_t(image.height));
  for (int y = 0; y < image.height; ++y) {
    const uint8_t* in = &image.rgb[size_t(y) * image.width * 3];
    uint8_t* row = &filtered[row_bytes * size_t(y)];
    row[0] = 1;
    for (size_t i = 0; i + 1 < row_bytes; ++i) row[i + 1] = uint8_t(i < 3 ? in[i] : in[i] - in[i - 3]);
  }
  // A compressor per thread (its tables are a few hundred kB, allocated once, not per frame).
  thread_local std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)> compressor(
      libdeflate_alloc_compressor(1), libdeflate_free_compressor);
  if (!compressor) throw RuntimeError("libdeflate: cannot allocate a compressor");
  std::vector<uint8_t> zlib_stream(libdeflate_zlib_compress_bound(compressor.get(), filtered.size()));
  const size_t size = libdeflate_zlib_compress(compressor.get(), filtered.data(), filtered.size(), zlib_stream.data(),
                                               zlib_stream.size());
  if (size == 0) throw RuntimeError("libdeflate: deflate failed");
  zlib_stream.resize(size);

  std::vector<uint8_t> png{0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  uint8_t header[13] = {};
  for (int k = 0; k < 4; ++k) {
    header[k] = uint8_t(uint32_t(image.width) >> (24 - 8 * k));
    header[4 + k] = uint8_t(uint32_t(image.height) >> (24 - 8 * k));
  }
  header[8] = 8;  // bits per channel; colour type 2 (RGB), deflate, adaptive filters, no interlace
  header[9] = 2;
  AppendPngChunk(&png, "IHDR", header, sizeof header);
  const uint8_t perceptual = 0;
  AppendPngChunk(&png, "sRGB", &perceptual, 1);
  static const char kText[] = "Software\0cinepath render";
  AppendPngChunk(&png, "tEXt", reinterpret_cast<const uint8_t*>(kText), sizeof kText - 1);
  AppendPngChunk(&png, "IDAT", zlib_stream.data(), zlib_stream.size());
  AppendPngChunk(&png, "IEND", nullptr, 0);
  return png;
}

void WritePng(FILE* file, const Srgb8Image& image) {
  const std::vector<uint8_t> png = EncodePng(image);
  if (std::fwrite(png.data(), 1, png.size(), file) != png.size()) throw RuntimeError(std::strerror(errno));
}

struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX];
};

void JpegErrorExit(j_common_ptr info) {
  auto* error = reinterpret_cast<JpegError*>(info->err);
  info->err->format_message(info, error->message);
  std::longjmp(error->jump, 1);
}

void WriteJpeg(FILE* file, const Srgb8Image& image) {
  jpeg_compress_struct jpeg{};
  JpegError error{};
  jpeg.err = jpeg_std_error(&error.manager);
  error.manager.error_exit = JpegErrorExit;
  if (setjmp(error.jump)) {
    jpeg_destroy_compress(&jpeg);
    throw RuntimeError(std::string("libjpeg: ") + error.message);
  }
  jpeg_create_compress(&jpeg);
  jpeg_stdio_dest(&jpeg, file);
  jpeg.image_width = JDIMENSION(image.width);
  jpeg.image_height = JDIMENSION(image.height);
  jpeg.input_components = 3;
  jpeg.in_color_space = JCS_RGB;
  jpeg_set_defaults(&jpeg);
  jpeg_set_quality(&jpeg, 95, TRUE);
  jpeg.comp_info[0].h_samp_factor = jpeg.comp_info[0].v_samp_factor = 1;  // full-resolution chroma
  jpeg_start_compress(&jpeg, TRUE);
  while (jpeg.next_scanline < jpeg.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(&image.rgb[size_t(jpeg.next_scanline) * image.width * 3]);
    jpeg_write_scanlines(&jpeg, &row, 1);
  }
  jpeg_finish_compress(&jpeg);
  jpeg_destroy_compress(&jpeg);
}

// Rows [begin, end) of a JPEG into `image` (sized already), with libjpeg's default decode (islow IDCT,
// fancy upsampling): the texels OpenImageIO's JPEG reader gave. The rows before `begin` are skipped
// (jpeg_skip_scanlines: entropy-decoded, not transformed). Without `image`, only the size is read.
//
// With `claim`, the decoder takes its rows a few at a time: at each claimed end it asks `claim(row)` for
// the next end (at most `end`), and stops when that is not past `row` (another decoder took the rest).
// With `wanted` (a flag per row), the rows it does not flag are skipped too, within the claimed rows, and
// left unwritten.
void DecodeJpegRows(const std::vector<uint8_t>& encoded, const std::string& where, int begin, int end,
                    Srgb8Image* image, int* width = nullptr, int* height = nullptr,
                    const std::function<int(int)>& claim = nullptr, const std::vector<uint8_t>* wanted = nullptr) {
  jpeg_decompress_struct jpeg{};
  JpegError error{};
  jpeg.err = jpeg_std_error(&error.manager);
  error.manager.error_exit = JpegErrorExit;
  error.manager.output_message = [](j_common_ptr) {};  // warnings (a truncated scan) are not printed
  if (setjmp(error.jump)) {
    jpeg_destroy_decompress(&jpeg);
    throw InputError(where + ": cannot decode the JPEG: " + error.message);
  }
  jpeg_create_decompress(&jpeg);
  jpeg_mem_src(&jpeg, encoded.data(), static_cast<unsigned long>(encoded.size()));
  jpeg_read_header(&jpeg, TRUE);
  if (width) *width = int(jpeg.image_width);
  if (height) *height = int(jpeg.image_height);
  if (image) {
    jpeg.out_color_space = JCS_RGB;  // grey and YCbCr alike
    jpeg_start_decompress(&jpeg);
    if (begin > 0) jpeg_skip_scanlines(&jpeg, JDIMENSION(begin));
    int claimed = claim ? int(jpeg.output_scanline) : end;
    while (int(jpeg.output_scanline) < end) {
      const int at = int(jpeg.output_scanline);
      if (at >= claimed && (claimed = std::min(end, claim(at))) <= at) break;
      if (wanted && !(*wanted)[size_t(at)]) {
        int next = at + 1;
        while (next < claimed && !(*wanted)[size_t(next)]) ++next;
        jpeg_skip_scanlines(&jpeg, JDIMENSION(next - at));
        continue;
      }
      JSAMPROW row = &image->rgb[size_t(at) * image->width * 3];
      jpeg_read_scanlines(&jpeg, &row, 1);
    }
  }
  jpeg_abort_decompress(&jpeg);
  jpeg_destroy_decompress(&jpeg);
}

// libpng's simplified API, to 8-bit sRGB RGB (grey replicated, alpha dropped).
Srgb8Image DecodePng(const std::vector<uint8_t>& encoded, const std::string& where) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_memory(&image, encoded.data(), encoded.size())) {
    throw InputError(where + ": cannot decode the PNG: " + image.message);
  }
  image.format = PNG_FORMAT_RGB;
  Srgb8Image texture;
  texture.width = int(image.width);
  texture.height = int(image.height);
  texture.rgb.resize(PNG_IMAGE_SIZE(image));
  if (!png_image_finish_read(&image, nullptr, texture.rgb.data(), 0, nullptr)) {
    png_image_free(&image);
    throw InputError(where + ": cannot decode the PNG: " + image.message);
  }
  return texture;
}

// An OpenEXR output stream into memory: OutputFile seeks back to fill in the line offset table.
class ExrMemoryStream : public Imf::OStream {
 public:
  ExrMemoryStream() : Imf::OStream("memory") {}
  void write(const char c[], int n) override {
    if (position_ + size_t(n) > bytes_.size()) bytes_.resize(position_ + size_t(n));
    std::memcpy(bytes_.data() + position_, c, size_t(n));
    position_ += size_t(n);
  }
  uint64_t tellp() override { return position_; }
  void seekp(uint64_t position) override { position_ = size_t(position); }
  std::vector<uint8_t>& bytes() { return bytes_; }

 private:
  std::vector<uint8_t> bytes_;
  size_t position_ = 0;
};

}  // namespace

uint8_t LinearToSrgb8(float linear) {
  if (!(linear > 0)) return 0;
  if (linear >= 1) return 255;
  const float encoded = linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1 / 2.4f) - 0.055f;
  return uint8_t(std::lround(encoded * 255));
}

namespace {

// The byte of a float x in (0, 1) in two steps. thresholds[v - 1] is the smallest float with
// LinearToSrgb8(x) >= v (v = 1 .. 255), found by bisection over the floats' bit patterns (for x > 0 they
// order as the values do); start[b] is the byte at the smallest float of the bit patterns' block b (its top
// 17 bits). LinearToSrgb8 never decreases, so x's byte is start[its block], stepped up past the thresholds
// at or below x: at most one or two (a block spans 2^15 floats, far less than a step). The same bytes as
// LinearToSrgb8, without a pow() per channel.
struct SrgbTable {
  static constexpr int kShift = 15;
  std::array<float, 255> thresholds{};
  std::vector<uint8_t> start;
  SrgbTable() {
    auto at = [](uint32_t bits) {
      float x;
      std::memcpy(&x, &bits, sizeof x);
      return x;
    };
    for (int v = 1; v <= 255; ++v) {
      uint32_t lo = 0, hi = 0x3f800000u;  // 0 gives 0; 1.0f gives 255
      while (hi - lo > 1) {
        const uint32_t mid = lo + (hi - lo) / 2;
        (LinearToSrgb8(at(mid)) >= v ? hi : lo) = mid;
      }
      thresholds[size_t(v - 1)] = at(hi);
    }
    start.resize((0x3f800000u >> kShift) + 1);
    for (uint32_t b = 0; b < start.size(); ++b) start[b] = LinearToSrgb8(at(b << kShift));
  }
};

const SrgbTable& SrgbTableOnce() {
  static const SrgbTable table;
  return table;
}

uint8_t LinearToSrgb8ByTable(const SrgbTable& table, float linear) {
  if (!(linear > 0)) return 0;
  if (linear >= 1) return 255;
  uint32_t bits;
  std::memcpy(&bits, &linear, sizeof bits);
  int v = table.start[bits >> SrgbTable::kShift];
  while (v < 255 && linear >= table.thresholds[size_t(v)]) ++v;
  return uint8_t(v);
}

}  // namespace

uint8_t LinearToSrgb8ByTable(float linear) { return LinearToSrgb8ByTable(SrgbTableOnce(), linear); }

void LinearToSrgb8ByTable(const float* linear, size_t count, uint8_t* out) {
  const SrgbTable& table = SrgbTableOnce();
  for (size_t i = 0; i < count; ++i) out[i] = LinearToSrgb8ByTable(table, linear[i]);
}

Srgb8Image EncodeSrgb8(const std::vector<Eigen::Vector3f>& rgb_linear, int width, int height) {
  Srgb8Image image{width, height, ImageBytes(size_t(width) * height * 3)};
  const SrgbTable& table = SrgbTableOnce();
  tbb::parallel_for(tbb::blocked_range<size_t>(0, rgb_linear.size(), 4096), [&](const tbb::blocked_range<size_t>& r) {
    uint8_t* out = image.rgb.data() + 3 * r.begin();
    for (size_t i = r.begin(); i < r.end(); ++i, out += 3) {
      const Eigen::Vector3f& pixel = rgb_linear[i];
      out[0] = LinearToSrgb8ByTable(table, pixel.x());
      out[1] = LinearToSrgb8ByTable(table, pixel.y());
      out[2] = LinearToSrgb8ByTable(table, pixel.z());
    }
  });
  return image;
}

namespace {

// Asks the kernel for 2 MB pages over a large fresh buffer (Linux's transparent huge pages, when set to
// "madvise" as Debian ships them): a 4096² atlas's 50 MB in 2 MB pages, not ~12,800 faults of 4 KiB (the
// whole render of one bundled frame: 20,650 faults before, 9,180 with the buffer also left unfilled).
// Only a hint: where it is refused, the buffer is as before.
void AdviseHugePages(uint8_t* data, size_t size) {
  constexpr uintptr_t kPage = 4096;
  if (size < (8u << 20)) return;
  const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + kPage - 1) & ~(kPage - 1);
  const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + size) & ~(kPage - 1);
#ifdef MADV_HUGEPAGE
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#endif
}

}  // namespace

Srgb8Image DecodeJpeg(const std::vector<uint8_t>& encoded, const std::string& where, int parts) {
  Srgb8Image image;
  DecodeJpegRows(encoded, where, 0, 0, nullptr, &image.width, &image.height);
  image.rgb.resize(size_t(image.width) * image.height * 3);
  AdviseHugePages(image.rgb.data(), image.rgb.size());
  // Small images, or one part: one decoder. Otherwise the rows in bands, one decoder each, the later
  // bands smaller (their decoder also entropy-decodes the rows it skips); the same bytes either way.
  if (parts <= 1 || image.height < 512) {
    DecodeJpegRows(encoded, where, 0, image.height, &image);
    return image;
  }
  std::vector<int> bounds{0};
  for (int p = 1; p < parts; ++p)
    bounds.push_back(std::min(image.height, int(image.height * 1.15 * p / parts) / 16 * 16));
  bounds.push_back(image.height);
  tbb::parallel_for(0, parts,
                    [&](int p) { DecodeJpegRows(encoded, where, bounds[size_t(p)], bounds[size_t(p) + 1], &image); });
  return image;
}

int JpegSecondBandStart(int height, int first_done) {
  // The first decoder does rows [done, split) at the full cost f a row; the second skips [0, split) at
  // the entropy-decoding cost h (0.36 f measured on the bundled 4096² atlas) and then does [split,
  // height): both end together when split (2 f - h) = (height + done) f.
  constexpr double kSkipCost = 0.36;
  const int split = (int(double(height + first_done) / (2 - kSkipCost)) + 15) / 16 * 16;
  return split >= height - 64 ? height : std::max(split, first_done);
}

Srgb8Image DecodeJpegShared(const std::vector<uint8_t>& encoded, const std::string& where,
                            const RowsWanted& rows_wanted) {
  Srgb8Image image;
  DecodeJpegRows(encoded, where, 0, 0, nullptr, &image.width, &image.height);
  image.rgb.resize(size_t(image.width) * image.height * 3);
  std::vector<uint8_t> wanted;
  if (rows_wanted) {
    wanted = rows_wanted(image.width, image.height);
    if (wanted.size() != size_t(image.height)) throw InternalError("DecodeJpegShared: one flag per row wanted");
  }
  // The decode ends after the last row wanted: the rest is not even entropy-decoded.
  int end = image.height;
  if (rows_wanted) {
    while (end > 0 && !wanted[size_t(end) - 1]) --end;
  }
  const std::vector<uint8_t>* wanted_rows = rows_wanted ? &wanted : nullptr;
  AdviseHugePages(image.rgb.data(), image.rgb.size());
  if (end == 0) return image;
  if (end < 512) {
    DecodeJpegRows(encoded, where, 0, end, &image, nullptr, nullptr, nullptr, wanted_rows);
    return image;
  }
  // Rows [0, claimed) are the first decoder's; from `second` on (end: none yet) the second's.
  std::mutex mutex;
  int claimed = 0, second = end;
  tbb::task_group group;
  group.run([&] {
    int begin;
    {
      const std::lock_guard<std::mutex> lock(mutex);
      begin = second = JpegSecondBandStart(end, claimed);
    }
    if (begin < end) DecodeJpegRows(encoded, where, begin, end, &image, nullptr, nullptr, nullptr, wanted_rows);
  });
  try {
    DecodeJpegRows(
        encoded, where, 0, end, &image, nullptr, nullptr,
        [&](int row) {
          const std::lock_guard<std::mutex> lock(mutex);
          claimed = std::min(second, row + 16);
          return claimed;
        },
        wanted_rows);
  } catch (...) {
    try {
      group.wait();
    } catch (...) {}
    throw;
  }
  group.wait();
  return image;
}

Srgb8Image DecodeSrgb8(const std::vector<uint8_t>& bytes, const std::string& where, const RowsWanted& rows_wanted) {
  const bool png = bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0;
  const bool jpeg = bytes.size() >= 3 && bytes[0] == 0xff && bytes[1] == 0xd8 && bytes[2] == 0xff;
  if (png) return DecodePng(bytes, where);
  if (jpeg) return DecodeJpegShared(bytes, where, rows_wanted);
  throw InputError(where + ": cannot decode: neither JPEG nor PNG");
}

void WriteSrgb8Atomic(const fs::path& path, const Srgb8Image& image) {
  std::string extension = path.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  const bool jpeg = extension == ".jpg" || extension == ".jpeg";
  WriteFileAtomicWith(path, [&](FILE* file) { jpeg ? WriteJpeg(file, image) : WritePng(file, image); });
}

std::vector<uint8_t> EncodeExr(int width, int height, const std::vector<std::string>& channels,
                               const std::vector<float>& values, ExrPixel pixel) {
  const size_t nc = channels.size();
  if (values.size() != size_t(width) * height * nc) throw RuntimeError("EXR: pixel values do not match the size");
  Imf::Header header(width, height);  // windows (0, 0)-(w-1, h-1), increasing Y, pixel aspect 1
  header.compression() = Imf::ZIP_COMPRESSION;
  // zlib's fastest level, as for PNG: half the compression time of its default, files ~5 % larger.
  header.zipCompressionLevel() = 1;
  header.insert("software", Imf::StringAttribute("cinepath render"));
  Imf::FrameBuffer frame;
  // Half values rounded to nearest even by Imath, here, so the file's bytes do not depend on OpenEXR's
  // conversion path.
  std::vector<Imath::half> halves;
  if (pixel == ExrPixel::kHalf) halves.assign(values.begin(), values.end());
  const Imf::PixelType type = pixel == ExrPixel::kHalf ? Imf::HALF : Imf::FLOAT;
  const size_t value_bytes = pixel == ExrPixel::kHalf ? sizeof(Imath::half) : sizeof(float);
  const size_t x_stride = nc * value_bytes, y_stride = x_stride * size_t(width);
  for (size_t c = 0; c < nc; ++c) {  // OpenEXR stores the channels in name order
    header.channels().insert(channels[c], Imf::Channel(type));
    // Slice wants a char*, but OutputFile only reads through it.
    char* base = pixel == ExrPixel::kHalf ? reinterpret_cast<char*>(halves.data() + c)
                                          : reinterpret_cast<char*>(const_cast<float*>(values.data() + c));
    frame.insert(channels[c], Imf::Slice(type, base, x_stride, y_stride));
  }
  ExrMemoryStream stream;
  {
    // No worker threads: the blocks compressed in order on this thread, the same bytes on every machine.
    Imf::OutputFile file(stream, header, 0);
    file.setFrameBuffer(frame);
    file.writePixels(height);
  }  // the destructor writes the line offset table
  return std::move(stream.bytes());
}

void WriteExrAtomic(const fs::path& path, int width, int height, const std::vector<std::string>& channels,
                    const std::vector<float>& values, ExrPixel pixel) {
  WriteFileAtomicWith(path, [&](FILE* file) {
    const std::vector<uint8_t> bytes = EncodeExr(width, height, channels, values, pixel);
    if (std::fwrite(bytes.data(), 1, bytes.size(), file) != bytes.size()) throw RuntimeError(std::strerror(errno));
  });
}

namespace {

const std::string& FontPath() {
  static const std::string path = [] {
    for (const char* candidate :
         {"/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf", "/usr/share/fonts/TTF/DejaVuSansMono.ttf",
          "/usr/share/fonts/dejavu/DejaVuSansMono.ttf"}) {
      if (fs::exists(candidate)) return std::string(candidate);
    }
    return std::string();
  }();
  return path;
}

// The label font, read and parsed once (stb_truetype).
struct LabelFont {
  std::string bytes;
  stbtt_fontinfo info{};
};

const LabelFont& Font() {
  static const std::unique_ptr<LabelFont> font = [] {
    auto f = std::make_unique<LabelFont>();
    f->bytes = ReadFileToString(FontPath());
    const auto* data = reinterpret_cast<const unsigned char*>(f->bytes.data());
    if (!stbtt_InitFont(&f->info, data, stbtt_GetFontOffsetForIndex(data, 0))) {
      throw RuntimeError(FontPath() + ": cannot read the label font");
    }
    return f;
  }();
  return *font;
}

// Text with its baseline at y, coloured `value` (0..255), blended by the glyphs' coverage.
void DrawTextAt(Srgb8Image* image, int x, int baseline, int size_px, const std::string& text, uint8_t value) {
  const LabelFont& font = Font();
  const float scale = stbtt_ScaleForMappingEmToPixels(&font.info, float(size_px));
  float pen = float(x);
  for (size_t i = 0; i < text.size(); ++i) {
    const int codepoint = static_cast<unsigned char>(text[i]);
    int advance = 0, bearing = 0;
    stbtt_GetCodepointHMetrics(&font.info, codepoint, &advance, &bearing);
    int gw = 0, gh = 0, gx = 0, gy = 0;
    const float shift = pen - std::floor(pen);
    unsigned char* glyph =
        stbtt_GetCodepointBitmapSubpixel(&font.info, scale, scale, shift, 0, codepoint, &gw, &gh, &gx, &gy);
    const int x0 = int(std::floor(pen)) + gx, y0 = baseline + gy;
    for (int j = 0; j < gh; ++j) {
      for (int k = 0; k < gw; ++k) {
        const int px = x0 + k, py = y0 + j;
        if (px < 0 || py < 0 || px >= image->width || py >= image->height) continue;
        const int a = glyph[j * gw + k];
        if (a == 0) continue;
        uint8_t* p = &image->rgb[(size_t(py) * image->width + px) * 3];
        for (int c = 0; c < 3; ++c) p[c] = uint8_t((p[c] * (255 - a) + value * a + 127) / 255);
      }
    }
    stbtt_FreeBitmap(glyph, nullptr);
    pen += float(advance) * scale;
    if (i + 1 < text.size()) {
      pen +=
          scale * float(stbtt_GetCodepointKernAdvance(&font.info, codepoint, static_cast<unsigned char>(text[i + 1])));
    }
  }
}

}  // namespace

void RequireLabelFont() {
  if (FontPath().empty()) {
    throw RuntimeError("labels need the DejaVu Sans Mono font (Debian package fonts-dejavu-core)");
  }
}

void DrawText(Srgb8Image* image, int x, int y, int size_px, const std::string& text) {
  RequireLabelFont();
  const int baseline = y + size_px;
  DrawTextAt(image, x + 1, baseline + 1, size_px, text, 0);
  DrawTextAt(image, x, baseline, size_px, text, 255);
}

}  // namespace cinepath::preview
