#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <opencv2/core.hpp>
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
