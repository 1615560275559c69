#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <stdexcept>

#include "../common/error_of.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/common/error.hpp"
#include "test_util.hpp"

using tactile::test::error_of;

namespace tactile::capture {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

GrayImage gradient(int w, int h) {
  GrayImage img{w, h, std::vector<std::uint8_t>(static_cast<std::size_t>(w * h))};
  for (int y = 0; y < h; ++y) {
    for (int x = 0; x < w; ++x) {
      img.pixels[static_cast<std::size_t>(y * w + x)] =
          static_cast<std::uint8_t>((x * 7 + y) % 256);
    }
  }
  return img;
}

TEST(Image, PngRoundTripIsLossless) {
  TempDir dir;
  const GrayImage img = gradient(37, 21);
  write_png(dir.path() / "a.png", img);
  const GrayImage back = read_image(dir.path() / "a.png");
  EXPECT_EQ(back.width_px, 37);
  EXPECT_EQ(back.height_px, 21);
  EXPECT_EQ(back.pixels, img.pixels);
}

TEST(Image, MissingEmptyAndNonImageFilesAreFormatErrorsNamingTheFile) {
  TempDir dir;
  EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "nope.png"); }),
              HasSubstr("nope.png: no such image file"));
  std::ofstream(dir.path() / "empty.png").close();
  EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "empty.png"); }),
              HasSubstr("empty.png: image file is empty"));
  std::ofstream(dir.path() / "text.png") << "this is not a PNG\n";
  EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "text.png"); }),
              HasSubstr("text.png: not a readable image"));
}

TEST(Image, TruncatedPngIsAFormatError) {
  TempDir dir;
  write_png(dir.path() / "full.png", gradient(64, 64));
  std::ifstream in(dir.path() / "full.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::ofstream(dir.path() / "cut.png", std::ios::binary) << bytes.substr(0, 40);
  EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "cut.png"); }),
              HasSubstr("cut.png: not a readable image"));
}

// The PNG chunk checksum (CRC-32 of ISO 3309, as the PNG specification gives it).
std::uint32_t png_crc(const std::string& bytes) {
  std::uint32_t c = 0xFFFFFFFFU;
  for (const char b : bytes) {
    c ^= static_cast<std::uint8_t>(b);
    for (int k = 0; k < 8; ++k) c = (c & 1U) ? 0xEDB88320U ^ (c >> 1) : c >> 1;
  }
  return c ^ 0xFFFFFFFFU;
}

// A valid PNG whose header declares 60000 x 60000 px (its checksum corrected): OpenCV refuses
// it with an assertion; the reader says so in words, naming the file, without OpenCV's text.
TEST(Image, PngDeclaringTooManyPixelsIsRefusedInWords) {
  TempDir dir;
  write_png(dir.path() / "small.png", gradient(64, 64));
  std::ifstream in(dir.path() / "small.png", std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ASSERT_EQ(bytes.substr(12, 4), "IHDR");
  for (const int at : {16, 20}) {  // width, height: big-endian 60000
    bytes[at] = 0;
    bytes[at + 1] = 0;
    bytes[at + 2] = static_cast<char>(60000 >> 8);
    bytes[at + 3] = static_cast<char>(60000 & 0xFF);
  }
  const std::uint32_t crc = png_crc(bytes.substr(12, 17));
  for (int i = 0; i < 4; ++i) bytes[29 + i] = static_cast<char>(crc >> (24 - 8 * i));
  std::ofstream(dir.path() / "huge.png", std::ios::binary) << bytes;
  const std::string e = error_of<FormatError>([&] { read_image(dir.path() / "huge.png"); });
  EXPECT_THAT(e, HasSubstr("huge.png: not a readable image (the image has more pixels than "
                           "OpenCV decodes (2^30))"));
  EXPECT_THAT(e, ::testing::Not(HasSubstr("OpenCV(")));
}

cv::Mat to_mat(const GrayImage& image) {
  return cv::Mat(image.height_px, image.width_px, CV_8U,
                 const_cast<std::uint8_t*>(image.pixels.data()))
      .clone();
}

std::string file_bytes(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  return {(std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>()};
}

// PNG and JPEG are decoded by our own calls to libpng and libjpeg (for their messages), BMP
// checked first: the pixels must still be OpenCV's own grey decoding, for every kind of image.
TEST(Image, EveryFormatReadDecodesToTheGreyOpencvGives) {
  TempDir dir;
  cv::Mat bgr(23, 31, CV_8UC3), bgra(23, 31, CV_8UC4), gray16(23, 31, CV_16UC1);
  cv::randu(bgr, 0, 256);
  cv::randu(bgra, 0, 256);
  cv::randu(gray16, 0, 65536);
  const cv::Mat gray8 = to_mat(gradient(31, 23));
  const std::vector<std::pair<std::string, cv::Mat>> images = {
      {"gray8.png", gray8}, {"gray16.png", gray16}, {"bgr.png", bgr}, {"bgra.png", bgra},
      {"bgr.jpg", bgr},     {"gray8.jpg", gray8},   {"bgr.bmp", bgr}, {"gray8.bmp", gray8},
      {"bgr.tif", bgr},     {"bgr.webp", bgr}};
  for (const auto& [name, mat] : images) {
    const auto path = dir.path() / name;
    ASSERT_TRUE(cv::imwrite(path.string(), mat)) << name;
    const cv::Mat expected = cv::imread(path.string(), cv::IMREAD_GRAYSCALE);
    const GrayImage got = read_image(path);
    ASSERT_EQ(got.width_px, expected.cols) << name;
    ASSERT_EQ(got.height_px, expected.rows) << name;
    EXPECT_EQ(cv::norm(to_mat(got), expected, cv::NORM_INF), 0) << name;
  }
}

// A damaged PNG or JPEG is refused in our words, naming the file and what is wrong (libpng and
// libjpeg would print their own lines on stderr; tests/e2e checks the real program's stderr).
TEST(Image, DamagedPngAndJpegAreFormatErrorsSayingWhatIsWrong) {
  TempDir dir;
  write_png(dir.path() / "good.png", gradient(64, 48));
  const std::string png = file_bytes(dir.path() / "good.png");
  std::ofstream(dir.path() / "half.png", std::ios::binary) << png.substr(0, png.size() / 2);
  std::string bad_crc = png;
  bad_crc[29] = static_cast<char>(bad_crc[29] ^ 0xFF);  // the IHDR chunk's checksum
  std::ofstream(dir.path() / "crc.png", std::ios::binary) << bad_crc;
  EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "half.png"); }),
              HasSubstr("half.png: not a readable image (the file ends early (truncated))"));
  EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "crc.png"); }),
              HasSubstr("crc.png: not a readable image (IHDR: CRC error)"));

  ASSERT_TRUE(cv::imwrite((dir.path() / "good.jpg").string(), to_mat(gradient(64, 48))));
  const std::string jpg = file_bytes(dir.path() / "good.jpg");
  std::ofstream(dir.path() / "half.jpg", std::ios::binary) << jpg.substr(0, jpg.size() * 2 / 3);
  EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "half.jpg"); }),
              HasSubstr("half.jpg: not a readable image (Premature end of JPEG file)"));

  // OpenCV's BMP decoder prints "imdecode_(''): can't read data" for a truncated file.
  for (const char* name : {"gray8.bmp", "bgr.bmp"}) {
    const cv::Mat mat = std::string(name) == "bgr.bmp"
                            ? cv::Mat(48, 64, CV_8UC3, cv::Scalar(1, 2, 3))
                            : to_mat(gradient(64, 48));
    ASSERT_TRUE(cv::imwrite((dir.path() / name).string(), mat));
    const std::string bmp = file_bytes(dir.path() / name);
    std::ofstream(dir.path() / "cut.bmp", std::ios::binary) << bmp.substr(0, bmp.size() - 100);
    EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "cut.bmp"); }),
                HasSubstr("cut.bmp: not a readable image (the file ends early (truncated))"))
        << name;
  }
}

// Other formats OpenCV decodes print their own errors when damaged: they are refused by name.
TEST(Image, OtherFormatsAreRefusedNamingTheFormatsRead) {
  TempDir dir;
  ASSERT_TRUE(cv::imwrite((dir.path() / "a.pgm").string(), to_mat(gradient(8, 8))));
  EXPECT_THAT(error_of<FormatError>([&] { read_image(dir.path() / "a.pgm"); }),
              HasSubstr("a.pgm: not a readable image (not a PNG, JPEG, BMP, TIFF or WebP file)"));
}

TEST(Image, OpencvErrorsAreSaidInWords) {
  const cv::Exception e(cv::Error::StsBadArg, "ssize.area() > 0", "resize", "resize.cpp", 4052);
  EXPECT_EQ(opencv_error_text(e), "image processing failed in OpenCV's resize: ssize.area() > 0");
  EXPECT_EQ(opencv_error_text(std::runtime_error("not OpenCV's")), std::nullopt);
}

TEST(Image, ListFramesSortsByNameAndSkipsOtherFiles) {
  TempDir dir;
  for (const char* name : {"f_002.png", "f_000.PNG", "f_001.jpg", "notes.txt"}) {
    if (std::string(name) == "notes.txt") {
      std::ofstream(dir.path() / name) << "x";
    } else {
      write_png(dir.path() / name, gradient(8, 8));
    }
  }
  const auto frames = list_frames(dir.path());
  ASSERT_EQ(frames.size(), 3u);
  EXPECT_EQ(frames[0].filename(), "f_000.PNG");
  EXPECT_EQ(frames[1].filename(), "f_001.jpg");
  EXPECT_EQ(frames[2].filename(), "f_002.png");
}

TEST(Image, EmptyOrMissingDirectoryIsAFormatError) {
  TempDir dir;
  EXPECT_THAT(error_of<FormatError>([&] { list_frames(dir.path()); }), HasSubstr("no image files"));
  EXPECT_THAT(error_of<FormatError>([&] { read_frames(dir.path() / "missing"); }),
              HasSubstr("not a directory"));
}

TEST(Image, MixedFrameSizesNameTheOddFile) {
  TempDir dir;
  write_png(dir.path() / "a.png", gradient(16, 16));
  write_png(dir.path() / "b.png", gradient(16, 16));
  write_png(dir.path() / "c.png", gradient(17, 16));
  const std::string msg = error_of<FormatError>([&] { read_frames(dir.path()); });
  EXPECT_THAT(msg, HasSubstr("c.png"));
  EXPECT_THAT(msg, HasSubstr("17x16"));
}

TEST(Image, NonImageAmongFramesIsAFormatError) {
  TempDir dir;
  write_png(dir.path() / "a.png", gradient(16, 16));
  std::ofstream(dir.path() / "b.png") << "garbage";
  EXPECT_THAT(error_of<FormatError>([&] { read_frames(dir.path()); }), HasSubstr("b.png"));
}

}  // namespace
}  // namespace tactile::capture
