// The contact map: cells of skin showing ridges are in contact, even cells are not, whatever the
// exposure; the map's grid covers the image.

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <random>
#include <stdexcept>
#include <vector>

#include "tactile/capture/contact_map.hpp"

namespace tactile::capture {
namespace {

constexpr double kPxPerMm = 20;

// Ridges of period 0.45 mm (9 px at 20 px/mm, or `period_px`) and amplitude `ridge_grey` where
// `touching(x, y)`, the even brightness of the valleys (200) elsewhere, with camera noise of 2
// grey levels.
template <typename Touching>
GrayImage skin(int width, int height, double ridge_grey, Touching touching, unsigned seed,
               double period_px = 9) {
  GrayImage g;
  g.width_px = width;
  g.height_px = height;
  g.pixels.resize(static_cast<std::size_t>(width * height));
  std::mt19937 rng(seed);
  std::normal_distribution<double> noise(0, 2);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) {
      const double ridge =
          touching(x, y) ? ridge_grey * std::sin(2 * M_PI * (x + 0.3 * y) / period_px) : 0.0;
      const double grey = std::clamp(200 - ridge_grey + ridge + noise(rng), 0.0, 255.0);
      g.pixels[static_cast<std::size_t>(y * width + x)] = static_cast<std::uint8_t>(grey);
    }
  }
  return g;
}

TEST(ContactMap, TheGridCoversTheImageInCellsOfAboutAMillimetre) {
  // 47 px/mm: cells of 47 px, 640 / 47 = 13.6 -> 14 columns, 484 / 47 = 10.3 -> 11 rows.
  const ContactGrid g = contact_grid(640, 484, 47);
  EXPECT_EQ(g.cell_px, 47);
  EXPECT_EQ(g.columns, 14);
  EXPECT_EQ(g.rows, 11);
  // Never below 8 px or above 256 px a cell.
  EXPECT_EQ(contact_grid(64, 48, 2).cell_px, 8);
  EXPECT_EQ(contact_grid(4000, 3000, 900).cell_px, 256);
  EXPECT_THROW(contact_grid(0, 10, 20), std::invalid_argument);
  EXPECT_THROW(contact_grid(10, 10, std::nan("")), std::invalid_argument);
}

TEST(ContactMap, CellsShowingRidgesAreInContactAndEvenCellsAreNot) {
  // Cells of 20 px: the left 100 px (5 columns) touch, the right 60 px (3 columns) do not.
  const auto left = [](int x, int) { return x < 100; };
  const GrayImage frame = skin(160, 80, 40, left, 1);
  const ContactMap map = measure_contact({frame}, kPxPerMm);
  ASSERT_EQ(map.grid.columns, 8);
  ASSERT_EQ(map.grid.rows, 4);
  ASSERT_EQ(map.frame_count(), 1);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 8; ++c) {
      const auto i = static_cast<std::size_t>(r * 8 + c);
      EXPECT_EQ(map.in_contact[i], c < 5 ? 1 : 0) << "row " << r << " column " << c;
      EXPECT_EQ(map.in_contact[i] == 1, map.ridge_contrast[i] >= map.threshold);
    }
  }
  // A sine of amplitude 40 has an RMS of 40 / sqrt(2) = 28: the contrast of skin in contact,
  // less what the box mean of a period leaves of it; noise alone stays near 2.
  EXPECT_GT(map.ridge_contrast[0], 20);
  EXPECT_LT(map.ridge_contrast[7], 4);
  EXPECT_NEAR(contact_fraction(map, 0), 5.0 / 8.0, 1e-12);
  EXPECT_EQ(contact_fraction(map, 1), 0);
}

// Cells under 16 px are measured at the image's own resolution (larger ones at half of it): at
// 12 px/mm, cells of 12 px and ridges of 5.4 px, the same rule holds.
TEST(ContactMap, SmallCellsAreMeasuredAtFullResolutionByTheSameRule) {
  const auto left = [](int x, int) { return x < 60; };
  const ContactMap map = measure_contact({skin(96, 48, 40, left, 5, 5.4)}, 12);
  ASSERT_EQ(map.grid.cell_px, 12);
  ASSERT_EQ(map.grid.columns, 8);
  ASSERT_EQ(map.grid.rows, 4);
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 8; ++c) {
      EXPECT_EQ(map.in_contact[static_cast<std::size_t>(r * 8 + c)], c < 5 ? 1 : 0)
          << "row " << r << " column " << c;
    }
  }
}

TEST(ContactMap, TheThresholdFollowsTheSequenceNotAFixedGreyLevel) {
  // A faint print (ridges of 12 grey levels, an RMS of 8.5) lifting off in its second frame: the
  // faint ridges are still contact, and the lifted cells are not.
  const auto all = [](int, int) { return true; };
  const auto lower_half = [](int, int y) { return y >= 40; };
  const ContactMap map =
      measure_contact({skin(160, 80, 12, all, 2), skin(160, 80, 12, lower_half, 3)}, kPxPerMm);
  ASSERT_EQ(map.frame_count(), 2);
  EXPECT_EQ(contact_fraction(map, 0), 1.0);
  EXPECT_NEAR(contact_fraction(map, 1), 0.5, 1e-12);
  // An even sequence (nothing touches) is out of contact everywhere: the floor holds.
  const auto none = [](int, int) { return false; };
  const ContactMap even = measure_contact({skin(160, 80, 12, none, 4)}, kPxPerMm);
  EXPECT_EQ(contact_fraction(even, 0), 0.0);
  EXPECT_GE(even.threshold, kContactFloorGrey);
}

// Frame by frame: the scale is the contact seen so far, so a faint print is in contact from its
// first frame, and a frame lifting off half its skin afterwards is cut at the same threshold as
// the whole sequence's map would cut it.
TEST(ContactMap, FrameByFrameTheThresholdIsTheContactSeenSoFar) {
  const auto all = [](int, int) { return true; };
  const auto lower_half = [](int, int y) { return y >= 40; };
  const ContactGrid g = contact_grid(160, 80, kPxPerMm);
  const auto fraction = [](const std::vector<std::uint8_t>& c) {
    return static_cast<double>(std::count(c.begin(), c.end(), std::uint8_t{1})) /
           static_cast<double>(c.size());
  };
  RunningContact running;
  EXPECT_EQ(fraction(contact_of_frame(running,
                                      cell_ridge_contrast(skin(160, 80, 12, all, 2), g, kPxPerMm))),
            1.0);
  const double scale = running.contact_contrast_grey;
  EXPECT_GT(scale, kContactFloorGrey);
  EXPECT_NEAR(fraction(contact_of_frame(
                  running, cell_ridge_contrast(skin(160, 80, 12, lower_half, 3), g, kPxPerMm))),
              0.5, 1e-12);
  // A frame mostly out of contact does not lower the scale.
  EXPECT_EQ(running.contact_contrast_grey, scale);
  // Before any skin in contact, the floor: an even frame is out of contact everywhere.
  RunningContact fresh;
  const auto none = [](int, int) { return false; };
  EXPECT_EQ(fraction(contact_of_frame(
                fresh, cell_ridge_contrast(skin(160, 80, 12, none, 4), g, kPxPerMm))),
            0.0);
}

TEST(ContactMap, AFrameOfAnotherSizeOrContrastsOfNoWholeFrameAreRefused) {
  const ContactGrid g = contact_grid(160, 80, kPxPerMm);
  GrayImage other;
  other.width_px = 200;
  other.height_px = 80;
  other.pixels.assign(200 * 80, 100);
  EXPECT_THROW(cell_ridge_contrast(other, g, kPxPerMm), std::invalid_argument);
  EXPECT_THROW(contact_map(g, std::vector<double>(33, 1.0)), std::invalid_argument);
  EXPECT_FALSE(measure_contact({}, kPxPerMm).measured());
}

}  // namespace
}  // namespace tactile::capture
