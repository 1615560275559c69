#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <fstream>

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
