#include "tactile/capture/image.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>

#include <fmt/format.h>
#include <jpeglib.h>
#include <png.h>
#include <opencv2/imgcodecs.hpp>

#include <csetjmp>
#include <cstdio>
#include <cstring>

#include "camera/cv_image.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/image_write.hpp"

namespace tactile::capture {

namespace {

// OpenCV decodes PNG and JPEG with libpng's and libjpeg's default message handlers, which print
// "libpng error: ..." or "Corrupt JPEG data: ..." on stderr before OpenCV returns an empty
// image. These two formats are therefore read here with handlers that keep the library's words
// for our own message. The message buffers are plain arrays because libpng and libjpeg leave
// by longjmp, which must not skip a C++ destructor.
constexpr std::size_t kMaxImagePixels = std::size_t{1} << 30;  // OpenCV's own limit
constexpr const char* kTooManyPixels = "the image has more pixels than OpenCV decodes (2^30)";

struct PngSource {
  const std::uint8_t* data = nullptr;
  std::size_t size = 0;
  std::size_t at = 0;
  bool has_exif = false;  // OpenCV then rotates by its orientation
  char error[200] = {};
};

[[noreturn]] void png_fail(png_structp png, png_const_charp message) {
  auto* source = static_cast<PngSource*>(png_get_error_ptr(png));
  std::snprintf(source->error, sizeof source->error, "%s", message);
  png_longjmp(png, 1);
}

// Warnings (a colour profile libpng dislikes, a damaged optional chunk) leave the pixels intact.
void png_ignore_warning(png_structp, png_const_charp) {}

void png_read_source(png_structp png, png_bytep out, std::size_t count) {
  auto* source = static_cast<PngSource*>(png_get_io_ptr(png));
  if (count > source->size - source->at) png_error(png, "the file ends early (truncated)");
  std::memcpy(out, source->data + source->at, count);
  source->at += count;
}

// Decodes to 8-bit grey with the same libpng transformations as OpenCV's IMREAD_GRAYSCALE, so
// the pixels are those OpenCV would give. Returns false with `source.error` set.
bool decode_png_gray(PngSource& source, GrayImage& image) {
  png_structp png =
      png_create_read_struct(PNG_LIBPNG_VER_STRING, &source, png_fail, png_ignore_warning);
  if (png == nullptr) {
    std::snprintf(source.error, sizeof source.error, "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  volatile bool ok = false;
  if (info != nullptr && setjmp(png_jmpbuf(png)) == 0) {
    png_set_read_fn(png, &source, png_read_source);
    png_read_info(png, info);
    const png_uint_32 width = png_get_image_width(png, info);
    const png_uint_32 height = png_get_image_height(png, info);
    const int depth = png_get_bit_depth(png, info);
    const int color = png_get_color_type(png, info);
    if (std::uint64_t{width} * height > kMaxImagePixels) {
      std::snprintf(source.error, sizeof source.error, "%s", kTooManyPixels);
      png_longjmp(png, 1);
    }
    if (depth == 16) png_set_strip_16(png);
    png_set_strip_alpha(png);
    if (color == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
    if ((color & PNG_COLOR_MASK_COLOR) == 0 && depth < 8) png_set_expand_gray_1_2_4_to_8(png);
    png_set_rgb_to_gray(png, 1, 0.299, 0.587);
    const int passes = png_set_interlace_handling(png);
    png_read_update_info(png, info);
    image.width_px = static_cast<int>(width);
    image.height_px = static_cast<int>(height);
    image.pixels.resize(std::size_t{width} * height);
    for (int pass = 0; pass < passes; ++pass) {
      for (png_uint_32 y = 0; y < height; ++y) {
        png_read_row(png, image.pixels.data() + std::size_t{y} * width, nullptr);
      }
    }
    png_read_end(png, info);
    png_uint_32 exif_size = 0;
    png_bytep exif = nullptr;
    source.has_exif = png_get_eXIf_1(png, info, &exif_size, &exif) != 0;
    ok = true;
  }
  png_destroy_read_struct(&png, info != nullptr ? &info : nullptr, nullptr);
  return ok;
}

struct JpegErrors {
  jpeg_error_mgr library;
  std::jmp_buf jump;
  char error[JMSG_LENGTH_MAX];
};

[[noreturn]] void jpeg_fail(j_common_ptr jpeg) {
  auto* errors = reinterpret_cast<JpegErrors*>(jpeg->err);
  (*jpeg->err->format_message)(jpeg, errors->error);
  std::longjmp(errors->jump, 1);
}

// libjpeg goes on after "Corrupt JPEG data" or "Premature end of JPEG file" (filling the rest
// grey) and prints the warning; a damaged frame is an error here instead.
void jpeg_message(j_common_ptr jpeg, int level) {
  if (level < 0) jpeg_fail(jpeg);
}

// Decodes every scanline once with libjpeg itself, so that OpenCV (which rotates by the EXIF
// orientation too) is handed only files that decode without a complaint. Returns false with
// `errors.error` set.
bool check_jpeg(const std::vector<std::uint8_t>& bytes, JpegErrors& errors) {
  jpeg_decompress_struct jpeg{};
  jpeg.err = jpeg_std_error(&errors.library);
  errors.library.error_exit = jpeg_fail;
  errors.library.emit_message = jpeg_message;
  volatile bool ok = false;
  if (setjmp(errors.jump) == 0) {
    jpeg_create_decompress(&jpeg);
    jpeg_mem_src(&jpeg, bytes.data(), static_cast<unsigned long>(bytes.size()));
    jpeg_read_header(&jpeg, TRUE);
    if (std::uint64_t{jpeg.image_width} * jpeg.image_height > kMaxImagePixels) {
      std::snprintf(errors.error, sizeof errors.error, "%s", kTooManyPixels);
      std::longjmp(errors.jump, 1);
    }
    jpeg.out_color_space = JCS_GRAYSCALE;
    if (jpeg.jpeg_color_space == JCS_CMYK || jpeg.jpeg_color_space == JCS_YCCK) {
      jpeg.out_color_space = JCS_CMYK;
    }
    jpeg_start_decompress(&jpeg);
    JSAMPARRAY row = (*jpeg.mem->alloc_sarray)(reinterpret_cast<j_common_ptr>(&jpeg), JPOOL_IMAGE,
                                               jpeg.output_width * jpeg.output_components, 1);
    while (jpeg.output_scanline < jpeg.output_height) jpeg_read_scanlines(&jpeg, row, 1);
    jpeg_finish_decompress(&jpeg);
    ok = true;
  }
  jpeg_destroy_decompress(&jpeg);
  return ok;
}

bool starts_with(const std::vector<std::uint8_t>& bytes, std::initializer_list<std::uint8_t> head) {
  return bytes.size() >= head.size() && std::equal(head.begin(), head.end(), bytes.begin());
}

std::uint32_t little_endian(const std::vector<std::uint8_t>& bytes, std::size_t at, int size) {
  std::uint32_t value = 0;
  for (int i = size - 1; i >= 0; --i) value = value << 8 | bytes[at + static_cast<std::size_t>(i)];
  return value;
}

// OpenCV's BMP decoder reads through a stream that throws at the end of the data, and OpenCV
// prints that on stderr. A BMP whose header, palette or pixels go past the end of the file is
// found here first. Returns what is wrong, or nothing.
std::optional<std::string> bmp_problem(const std::vector<std::uint8_t>& bytes) {
  const std::string truncated = "the file ends early (truncated)";
  if (bytes.size() < 18) return truncated;
  const std::uint32_t offset = little_endian(bytes, 10, 4);
  const std::uint32_t header = little_endian(bytes, 14, 4);
  if (header != 12 && header < 40) return fmt::format("unknown BMP header of {} bytes", header);
  if (bytes.size() < 14 + std::uint64_t{header} || offset > bytes.size()) return truncated;
  const bool core = header == 12;
  const std::uint64_t width = core ? little_endian(bytes, 18, 2) : little_endian(bytes, 18, 4);
  // A negative height in the longer headers means rows from the top down.
  const std::uint64_t height =
      core ? little_endian(bytes, 20, 2)
           : static_cast<std::uint64_t>(
                 std::abs(std::int64_t{static_cast<std::int32_t>(little_endian(bytes, 22, 4))}));
  const std::uint32_t bits = core ? little_endian(bytes, 24, 2) : little_endian(bytes, 28, 2);
  const std::uint32_t compression = core ? 0 : little_endian(bytes, 30, 4);
  if (bits <= 8) {  // the palette follows the header: 3-byte entries in the short header
    const std::uint32_t used = core ? 0 : std::min<std::uint32_t>(little_endian(bytes, 46, 4), 256);
    const std::uint64_t palette = (used != 0 ? used : 1U << bits) * (core ? 3U : 4U);
    if (bytes.size() < 14 + std::uint64_t{header} + palette) return truncated;
  }
  if (compression == 0 || compression == 3) {  // rows of pixels, each padded to 4 bytes
    const std::uint64_t row = (width * bits + 31) / 32 * 4;
    if (height > 0 && row > (bytes.size() - offset) / height) return truncated;
    return std::nullopt;
  }
  if (compression != 1 && compression != 2) return std::nullopt;  // OpenCV refuses it quietly
  // Run-length codes: (count, value) pairs; 0 0 ends a row, 0 1 the image, 0 2 dx dy moves,
  // 0 n copies n literal pixels (bytes for RLE8, nibbles for RLE4) padded to 2 bytes.
  std::uint64_t y = 0;
  std::size_t at = offset;
  while (y < height) {
    if (at + 2 > bytes.size()) return truncated;
    const std::uint8_t count = bytes[at], code = bytes[at + 1];
    at += 2;
    if (count != 0) continue;
    if (code == 0) {
      ++y;
    } else if (code == 1) {
      return std::nullopt;
    } else if (code == 2) {
      if (at + 2 > bytes.size()) return truncated;
      y += bytes[at + 1];
      at += 2;
    } else {
      const std::size_t literal = compression == 1 ? code : (code + 1) / 2;
      at += literal + (literal & 1);
    }
  }
  return std::nullopt;
}

}  // namespace

GrayImage read_image(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) {
    throw FormatError(fmt::format("{}: no such image file", path.string()));
  }
  if (std::filesystem::file_size(path, ec) == 0) {
    throw FormatError(fmt::format("{}: image file is empty", path.string()));
  }
  std::ifstream in(path, std::ios::binary);
  std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                  std::istreambuf_iterator<char>());
  if (starts_with(bytes, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'})) {
    PngSource source;
    source.data = bytes.data();
    source.size = bytes.size();
    GrayImage image;
    if (!decode_png_gray(source, image)) {
      throw FormatError(fmt::format("{}: not a readable image ({})", path.string(), source.error));
    }
    // Decoded once without a complaint: OpenCV's second decode, which applies the orientation,
    // has nothing left to print.
    if (!source.has_exif) return image;
  }
  if (starts_with(bytes, {0xff, 0xd8, 0xff})) {
    JpegErrors errors{};
    if (!check_jpeg(bytes, errors)) {
      throw FormatError(fmt::format("{}: not a readable image ({})", path.string(), errors.error));
    }
  } else if (starts_with(bytes, {'B', 'M'})) {
    if (const auto problem = bmp_problem(bytes)) {
      throw FormatError(fmt::format("{}: not a readable image ({})", path.string(), *problem));
    }
  } else {
    // OpenCV's other decoders print their own errors on stderr (PNM, JPEG 2000, ...); TIFF's
    // and WebP's do not: OpenCV silences libtiff, and libwebp says nothing.
    const bool tiff =
        starts_with(bytes, {'I', 'I', 42, 0}) || starts_with(bytes, {'M', 'M', 0, 42});
    const bool webp = bytes.size() >= 12 && starts_with(bytes, {'R', 'I', 'F', 'F'}) &&
                      std::equal(bytes.begin() + 8, bytes.begin() + 12, "WEBP");
    if (!tiff && !webp) {
      throw FormatError(fmt::format(
          "{}: not a readable image (not a PNG, JPEG, BMP, TIFF or WebP file)", path.string()));
    }
  }
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    throw FormatError(
        fmt::format("{}: not a readable image ({})", path.string(), *opencv_error_text(e)));
  }
  if (decoded.empty()) {
    throw FormatError(
        fmt::format("{}: not a readable image (unknown or corrupt format)", path.string()));
  }
  return from_mat(decoded);
}

std::optional<std::string> opencv_error_text(const std::exception& e) {
  const auto* cv_error = dynamic_cast<const cv::Exception*>(&e);
  if (cv_error == nullptr) return std::nullopt;
  // The one limit a user meets in practice, in its own words.
  if (cv_error->err.find("CV_IO_MAX_IMAGE_PIXELS") != std::string::npos) return kTooManyPixels;
  return fmt::format("image processing failed in OpenCV's {}: {}",
                     cv_error->func.empty() ? std::string("code") : cv_error->func, cv_error->err);
}

void write_png(const std::filesystem::path& path, const GrayImage& image) {
  write_image_atomically(path, as_mat(image));
}

namespace {
bool is_image_name(const std::filesystem::path& p) {
  std::string ext = p.extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return ext == ".png" || ext == ".jpg" || ext == ".jpeg" || ext == ".bmp" || ext == ".tif" ||
         ext == ".tiff";
}
}  // namespace

std::vector<std::filesystem::path> list_frames(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) {
    throw FormatError(fmt::format("{}: not a directory of frames", dir.string()));
  }
  std::vector<std::filesystem::path> frames;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.is_regular_file() && is_image_name(entry.path())) frames.push_back(entry.path());
  }
  if (frames.empty()) {
    throw FormatError(fmt::format(
        "{}: no image files (.png .jpg .jpeg .bmp .tif) in this directory", dir.string()));
  }
  std::sort(frames.begin(), frames.end());
  return frames;
}

std::vector<GrayImage> read_frames(const std::filesystem::path& dir) {
  const auto paths = list_frames(dir);
  std::vector<GrayImage> frames;
  frames.reserve(paths.size());
  for (const auto& path : paths) {
    GrayImage image = read_image(path);
    if (!frames.empty() && (image.width_px != frames.front().width_px ||
                            image.height_px != frames.front().height_px)) {
      throw FormatError(fmt::format(
          "{}: frame is {}x{} px but {} is {}x{} px; all frames of a "
          "sequence must have the same size",
          path.string(), image.width_px, image.height_px, paths.front().filename().string(),
          frames.front().width_px, frames.front().height_px));
    }
    frames.push_back(std::move(image));
  }
  return frames;
}

std::string frame_file_name(std::size_t i) {
  return fmt::format("frame_{:03d}.png", i);
}

std::string frame_files_text(std::size_t count) {
  return frame_file_name(0) + " .. " + frame_file_name(count == 0 ? 0 : count - 1);
}

void write_frames(const std::filesystem::path& dir, const std::vector<GrayImage>& frames) {
  std::filesystem::create_directories(dir);
  for (std::size_t i = 0; i < frames.size(); ++i) write_png(dir / frame_file_name(i), frames[i]);
}

}  // namespace tactile::capture
