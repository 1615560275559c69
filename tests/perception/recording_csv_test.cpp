// BioTac-style CSV recordings: round trip, the real files' quirks, and malformed input.

#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "../common/temp_dir.hpp"
#include "tactile/common/error.hpp"
#include "tactile/perception/recording_csv.hpp"

namespace perception = tactile::perception;

namespace {

std::string header() {
  std::ostringstream h;
  h << "timestamp,tdc,tac,pdc";
  for (int i = 1; i <= 22; ++i) h << ",pac" << i;
  for (int i = 1; i <= 19; ++i) h << ",ele" << i;
  return h.str();
}

// Row with pressure p, pac k = 100 + k, ele e = 1000 + e; optional trailing comma.
std::string row(double t, double p, bool trailing_comma = true) {
  std::ostringstream r;
  r.precision(15);
  r << t << ",2,113," << p;
  for (int k = 1; k <= 22; ++k) r << ',' << 100 + k;
  for (int e = 1; e <= 19; ++e) r << ',' << 1000 + e;
  if (trailing_comma) r << ',';
  return r.str();
}

// `text` with the first `from` replaced by `to` (built by concatenation: GCC 12's -Wrestrict
// misfires on std::string::replace).
std::string with(const std::string& text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  return text.substr(0, at) + to + text.substr(at + from.size());
}

std::string message_of(const std::string& text) {
  std::istringstream in(text);
  try {
    perception::read_sensor_csv(in, "rec.csv");
  } catch (const tactile::FormatError& e) {
    return e.what();
  }
  return "no error";
}

}  // namespace

TEST(SensorCsv, ReadsRowsWithTrailingCommaAndDeinterleavesVibration) {
  std::istringstream in(header() + "\n" + row(1581234207.12, 51) + "\n" + row(1581234207.13, 53) +
                        "\n");
  const auto r = perception::read_sensor_csv(in, "rec.csv");
  ASSERT_EQ(r.rows(), 2u);
  EXPECT_DOUBLE_EQ(r.pressure[1], 53);
  ASSERT_EQ(r.vibration.size(), 44u);
  EXPECT_DOUBLE_EQ(r.vibration[0], 101);   // pac1 of row 1
  EXPECT_DOUBLE_EQ(r.vibration[21], 122);  // pac22 of row 1
  EXPECT_DOUBLE_EQ(r.vibration[22], 101);  // pac1 of row 2
  EXPECT_DOUBLE_EQ(r.electrodes[18][0], 1019);
}

TEST(SensorCsv, RoundTripThroughAFile) {
  perception::SensorRecording r;
  for (int i = 0; i < 3; ++i) {
    r.t_s.push_back(0.01 * i);
    r.temperature_dc.push_back(2);
    r.temperature_ac.push_back(0);
    r.pressure.push_back(2000.5 + i);
    for (int k = 0; k < 22; ++k) r.vibration.push_back(2048 + k * 0.25 - i);
    for (int e = 0; e < 19; ++e) r.electrodes[e].push_back(3000 + e + 0.125 * i);
  }
  const tactile::test::TempDir dir;
  const auto path = dir / "sensor.csv";
  perception::write_sensor_csv(path, r);
  const auto back = perception::read_sensor_csv(path);
  ASSERT_EQ(back.rows(), 3u);
  EXPECT_EQ(back.pressure, r.pressure);
  EXPECT_EQ(back.vibration, r.vibration);
  EXPECT_EQ(back.electrodes[7], r.electrodes[7]);
}

TEST(SensorCsv, MalformedFilesNameTheProblem) {
  const std::string h = header() + "\n";
  EXPECT_NE(message_of("").find("empty file"), std::string::npos);
  EXPECT_NE(message_of(h).find("no data rows"), std::string::npos);
  EXPECT_NE(message_of("timestamp,pdc\n1,2\n").find("header has 2 columns"), std::string::npos);
  const std::string wrong = with(header(), "pdc", "pxx");
  EXPECT_NE(message_of(wrong + "\n").find("'pxx', expected 'pdc'"), std::string::npos);
  // A truncated last row (the recorder stopped mid-line).
  const std::string full = row(1.0, 51);
  EXPECT_NE(message_of(h + full + "\n" + full.substr(0, 40) + "\n").find("line 3"),
            std::string::npos);
  EXPECT_NE(message_of(h + full.substr(0, 40)).find("expected 45 (truncated row?)"),
            std::string::npos);
  const std::string bad = with(full, ",51", ",5x");
  EXPECT_NE(message_of(h + bad + "\n").find("column 'pdc': '5x' is not a number"),
            std::string::npos);
  const std::string nan = with(full, ",51", ",nan");
  EXPECT_NE(message_of(h + nan + "\n").find("not a number"), std::string::npos);
  EXPECT_NE(message_of(h + row(2.0, 51) + "\n" + row(1.0, 51) + "\n").find("goes back in time"),
            std::string::npos);
  EXPECT_THROW(perception::read_sensor_csv(std::filesystem::path("/nonexistent/x.csv")),
               std::runtime_error);
}

TEST(SensorCsv, TakesCrLfLineEndsAndAByteOrderMark) {
  std::istringstream in("\xEF\xBB\xBF" + header() + "\r\n" + row(1.0, 51) + "\r\n" + row(1.01, 53) +
                        "\r\n");
  const auto r = perception::read_sensor_csv(in, "rec.csv");
  ASSERT_EQ(r.rows(), 2u);
  EXPECT_DOUBLE_EQ(r.pressure[1], 53);
  EXPECT_DOUBLE_EQ(r.electrodes[18][1], 1019);
}

TEST(SensorCsv, RefusesValuesNoSensorGivesAndASensorThatMeasuredNothing) {
  const std::string h = header() + "\n";
  EXPECT_NE(message_of(h + row(1.0, 51) + "\n" + row(1.01, 1e9) + "\n")
                .find("line 3: column 'pdc': 1000000000 is out of range: a sensor's counts lie "
                      "within -100000 to 100000"),
            std::string::npos);
  const std::string ele = with(row(1.0, 51), ",1019", ",-3e7");
  EXPECT_NE(message_of(h + ele + "\n").find("line 2: column 'ele19': -3e7 is out of range"),
            std::string::npos);
  // One row repeated (its 22 vibration samples differ, but each repeats every 10 ms): nothing
  // changed anywhere.
  EXPECT_NE(message_of(h + row(1.0, 51) + "\n" + row(1.01, 51) + "\n" + row(1.02, 51) + "\n")
                .find("all 19 electrodes hold one value each over all 3 rows: the sensor "
                      "measured nothing"),
            std::string::npos);
  // One changing signal is a measurement.
  EXPECT_EQ(message_of(h + row(1.0, 51) + "\n" + row(1.01, 52) + "\n"), "no error");
  EXPECT_EQ(message_of(h + row(1.0, 51) + "\n" + with(row(1.01, 51), ",1019", ",1018") + "\n"),
            "no error");
  EXPECT_EQ(message_of(h + row(1.0, 51) + "\n" + with(row(1.01, 51), ",122,", ",121,") + "\n"),
            "no error");
}

TEST(SensorCsv, ReadsEveryRealRecording) {
  const std::filesystem::path dir = std::filesystem::path(TACTILE_TEST_DATA_DIR) / "biotac-slide";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    if (entry.path().filename().string().find("_bio.csv") == std::string::npos) continue;
    const auto r = perception::read_sensor_csv(entry.path());
    ++files;
    // The README: one row per 10 ms, 22 vibration samples per row.
    ASSERT_GT(r.rows(), 100u) << entry.path();
    EXPECT_EQ(r.vibration.size(), 22 * r.rows());
    const double span_s = r.t_s.back() - r.t_s.front();
    EXPECT_NEAR(span_s / static_cast<double>(r.rows() - 1), 0.01, 0.002) << entry.path();
  }
  EXPECT_EQ(files, 9);
}
