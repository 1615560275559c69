// Signal analysis: contact at 0.2 % of baseline, the windows, and the 76 inputs of Table 1, on
// hand-made recordings with a known answer and on the simulated sensor.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tactile/perception/cascade.hpp"
#include "tactile/perception/contact_inputs.hpp"
#include "tactile/perception/recording_csv.hpp"
#include "tactile/perception/sensor_model.hpp"

namespace perception = tactile::perception;

namespace {

// 3 s at 100 Hz: baseline 1000, contact rows [50, 250) with pressure 1000 + 50 and electrode
// cluster c raised by 10 (c + 1); vibration a 200 Hz tone during contact.
perception::SensorRecording box_recording() {
  perception::SensorRecording r;
  r.source = "box";
  for (int i = 0; i < 300; ++i) {
    const bool in = i >= 50 && i < 250;
    r.t_s.push_back(0.01 * i);
    r.temperature_dc.push_back(0);
    r.temperature_ac.push_back(0);
    r.pressure.push_back(1000 + (in ? 50 : 0));
    for (int e = 0; e < perception::kElectrodeCount; ++e)
      r.electrodes[e].push_back(500 + (in ? 10.0 * (perception::kElectrodeCluster[e] + 1) : 0));
    for (int k = 0; k < 22; ++k) {
      const double t = (22.0 * i + k) / 2200.0;
      r.vibration.push_back(in ? std::sin(2 * std::numbers::pi * 200 * t) : 0.0);
    }
  }
  return r;
}

}  // namespace

TEST(PerceptionFeatures, ContactAtPointTwoPercentOfBaseline) {
  auto r = box_recording();
  // 1000 * 0.2 % = 2: a rise of 1.5 is not contact, a rise of 2.5 is.
  r.pressure[20] = 1001.5;
  r.pressure[30] = 1002.5;
  const auto c = perception::find_contact(r);
  EXPECT_DOUBLE_EQ(c.baseline_pressure, 1000);
  EXPECT_DOUBLE_EQ(c.threshold, 2.0);
  EXPECT_EQ(c.begin, 30u);
  EXPECT_EQ(c.end, 250u);
  EXPECT_FALSE(c.starts_in_contact);
}

TEST(PerceptionFeatures, NoContactIsAClearError) {
  auto r = box_recording();
  for (double& p : r.pressure) p = 1000;
  try {
    perception::find_contact(r);
    FAIL();
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("box: no contact"), std::string::npos);
  }
}

TEST(PerceptionFeatures, WindowMeansRatesAndVibrationOfABox) {
  const auto r = box_recording();
  perception::ContactOptions whole;
  whole.feature_from_kinematics = false;  // the whole contact is the feature contact
  const auto in = perception::procedure_inputs(r, perception::Procedure::distal_proximal, whole);
  const auto names = perception::procedure_input_names(perception::Procedure::distal_proximal);
  ASSERT_EQ(in.size(), 23u);
  ASSERT_EQ(names.size(), 23u);
  EXPECT_EQ(names[0], "dp.w1.pressure");
  EXPECT_DOUBLE_EQ(in[0], 50);      // window 1 pressure mean, relative to baseline
  EXPECT_DOUBLE_EQ(in[7 + 4], 40);  // window 2 (from 7: pressure, clusters 0..5), cluster 3
  EXPECT_DOUBLE_EQ(in[14], 0);      // flat top: no initial rate
  EXPECT_NEAR(in[21], 200, 4);      // mean IF of IMF1 in the first 250 ms
  EXPECT_NEAR(in[22], 200, 4);
  const auto s = perception::procedure_inputs(r, perception::Procedure::static_contact, whole);
  ASSERT_EQ(s.size(), 7u);
  EXPECT_DOUBLE_EQ(s[6], 60);
}

TEST(PerceptionFeatures, InitialRateIsTheSlopeOfARamp) {
  auto r = box_recording();
  for (int i = 50; i < 250; ++i) r.pressure[i] = 1000 + 3 + 2.0 * (i - 50);  // 200 counts/s
  perception::ContactOptions whole;
  whole.feature_from_kinematics = false;
  const auto in = perception::procedure_inputs(r, perception::Procedure::roll, whole);
  EXPECT_NEAR(in[14], 200.0, 1e-6);
}

TEST(PerceptionFeatures, SeventySixInputsFromTheSimulatedSensor) {
  const auto names = perception::perception_input_names();
  EXPECT_EQ(names.size(), 76u);
  const perception::SurfaceFeature f{perception::Curvature::planar, 5, 2.5};
  std::size_t total = 0;
  for (auto p : {perception::Procedure::static_contact, perception::Procedure::distal_proximal,
                 perception::Procedure::radial_ulnar, perception::Procedure::roll}) {
    const auto r = perception::simulate_trial(f, p, 2);
    const auto c = perception::find_contact(r);
    // Contact starts in the first third of the 0.3 s press ramp (after 0.5 s of free air).
    const double begin_s = static_cast<double>(c.begin) / r.rate_hz;
    EXPECT_GT(begin_s, 0.5) << perception::procedure_name(p);
    EXPECT_LT(begin_s, 0.6) << perception::procedure_name(p);
    const auto in = perception::procedure_inputs(r, p);
    total += in.size();
    for (double v : in) EXPECT_TRUE(std::isfinite(v));
  }
  EXPECT_EQ(total, 76u);
}

TEST(PerceptionFeatures, RealRecordingsBeginInContact) {
  // biotac-slide: trials start in contact and end released; baseline from the end.
  const auto path =
      std::filesystem::path(TACTILE_TEST_DATA_DIR) / "biotac-slide" / "mat14_2_bio.csv";
  const auto r = perception::read_sensor_csv(path);
  perception::ContactOptions o;
  o.baseline_at = perception::ContactOptions::BaselineAt::end;
  o.feature_from_kinematics = false;
  const auto c = perception::find_contact(r, o);
  EXPECT_TRUE(c.starts_in_contact);
  EXPECT_LT(c.end, r.rows());
  EXPECT_EQ(perception::procedure_inputs(r, perception::Procedure::distal_proximal, o).size(), 23u);
}

namespace {

// A tared slide, as the real files are (signals near 0 off contact): 3 s at 100 Hz, contact
// rows [50, 250); pressure rises over [50, 90) to 80, holds until 210 and falls to 0 at 250
// (press, slide, lift); electrode e reads 2e + 1 in the first half of the contact and 5e + 3 in
// the second; vibration a 200 Hz tone during contact.
perception::SensorRecording tared_slide() {
  perception::SensorRecording r;
  r.source = "slide";
  for (int i = 0; i < 300; ++i) {
    const bool in = i >= 50 && i < 250;
    double p = 0;
    if (i >= 50 && i < 90) p = 2.0 * (i - 50 + 1);
    if (i >= 90 && i < 210) p = 80;
    if (i >= 210 && i < 250) p = 2.0 * (250 - i);
    r.t_s.push_back(0.01 * i);
    r.temperature_dc.push_back(0);
    r.temperature_ac.push_back(0);
    r.pressure.push_back(p);
    for (int e = 0; e < perception::kElectrodeCount; ++e)
      r.electrodes[e].push_back(!in ? 0.0 : i < 150 ? 2.0 * e + 1 : 5.0 * e + 3);
    for (int k = 0; k < 22; ++k) {
      const double t = (22.0 * i + k) / 2200.0;
      r.vibration.push_back(in ? std::sin(2 * std::numbers::pi * 200 * t) : 0.0);
    }
  }
  return r;
}

double column_mean(const std::vector<double>& v, std::size_t begin, std::size_t end) {
  double s = 0;
  for (std::size_t i = begin; i < end; ++i) s += v[i];
  return s / static_cast<double>(end - begin);
}

perception::ContactOptions slide_options() {
  perception::ContactOptions o;
  o.baseline_at = perception::ContactOptions::BaselineAt::none;
  o.feature_from_kinematics = false;
  return o;
}

}  // namespace

// Tared files need no baseline: contact is where pressure exceeds 0 by the 1-count floor, and the
// window means are of the signals as recorded.
TEST(PerceptionFeatures, NoBaselineTakesTheSignalsAsRecorded) {
  const auto r = tared_slide();
  const auto o = slide_options();
  const auto c = perception::find_contact(r, o);
  EXPECT_DOUBLE_EQ(c.baseline_pressure, 0);
  EXPECT_EQ(c.begin, 50u);  // pressure 2 > 1 from the first contact row
  EXPECT_EQ(c.end, 250u);   // the last row of the lift is 2
  const auto in = perception::procedure_inputs(r, perception::Procedure::distal_proximal, o);
  EXPECT_DOUBLE_EQ(in[0], column_mean(r.pressure, 50, 150));
  // With the baseline at the end, the same file loses nothing here (its end is 0) ...
  auto end = o;
  end.baseline_at = perception::ContactOptions::BaselineAt::end;
  EXPECT_DOUBLE_EQ(perception::procedure_inputs(r, perception::Procedure::distal_proximal, end)[0],
                   in[0]);
  // ... but a file that ends still in contact (here at 30 from row 250) has that level taken
  // off: contact becomes pressure above 31, rows [65, 235) of the ramps, halves split at 150.
  auto held = r;
  for (std::size_t i = 250; i < 300; ++i) held.pressure[i] = 30;
  EXPECT_DOUBLE_EQ(
      perception::procedure_inputs(held, perception::Procedure::distal_proximal, end)[0],
      column_mean(held.pressure, 65, 150) - 30);
  // Without a baseline, contact runs to the end, rows [50, 300), halves split at 175.
  EXPECT_DOUBLE_EQ(perception::procedure_inputs(held, perception::Procedure::distal_proximal, o)[0],
                   column_mean(held.pressure, 50, 175));
}

// With each electrode, the window means are the electrodes' own column means over each half of
// the contact, named e1..e19 after pressure; the rates and vibration follow as before.
TEST(PerceptionFeatures, EachElectrodeMeansAreTheColumnMeansOfTheWindows) {
  const auto r = tared_slide();
  auto o = slide_options();
  o.electrodes = perception::ContactOptions::Electrodes::each;
  const auto p = perception::Procedure::distal_proximal;
  const auto in = perception::procedure_inputs(r, p, o);
  const auto names = perception::procedure_input_names(p, o);
  ASSERT_EQ(in.size(), 3u * 20u + 2u);
  ASSERT_EQ(names.size(), in.size());
  EXPECT_EQ(perception::procedure_input_count(p, o), in.size());
  EXPECT_EQ(names[1], "dp.w1.e1");
  EXPECT_EQ(names[20 + 19], "dp.w2.e19");
  for (int e = 0; e < perception::kElectrodeCount; ++e) {
    EXPECT_DOUBLE_EQ(in[1 + e], column_mean(r.electrodes[e], 50, 150)) << e;
    EXPECT_DOUBLE_EQ(in[20 + 1 + e], column_mean(r.electrodes[e], 150, 250)) << e;
    EXPECT_DOUBLE_EQ(in[20 + 1 + e], 5.0 * e + 3) << e;  // the hand-built level
  }
  // The paper's clusters are still the default, and average their members.
  const auto clusters = perception::procedure_inputs(r, p, slide_options());
  ASSERT_EQ(clusters.size(), 23u);
  for (int c = 0; c < perception::kElectrodeClusterCount; ++c) {
    double sum = 0;
    int members = 0;
    for (int e = 0; e < perception::kElectrodeCount; ++e)
      if (perception::kElectrodeCluster[e] == c) {
        sum += in[1 + e];
        ++members;
      }
    EXPECT_NEAR(clusters[1 + c], sum / members, 1e-12) << c;
  }
}

// Trimming 20 % of a 200-row contact at each end leaves rows [90, 210): exactly the plateau
// between the press and the lift, so the window means are the plateau's level and the initial
// rate is flat.
TEST(PerceptionFeatures, TrimLeavesOutThePressAndTheLift) {
  const auto r = tared_slide();
  auto o = slide_options();
  o.trim_fraction = 0.2;
  const auto p = perception::Procedure::distal_proximal;
  const auto c = perception::find_contact(r, o);
  const auto f = perception::find_feature_contact(r, p, c, o);
  EXPECT_EQ(f.begin, 90u);
  EXPECT_EQ(f.end, 210u);
  const auto in = perception::procedure_inputs(r, p, o);
  EXPECT_DOUBLE_EQ(in[0], 80);
  EXPECT_DOUBLE_EQ(in[7], 80);
  EXPECT_NEAR(in[14], 0, 1e-9);
  // Untrimmed, the press and the lift are in the windows.
  const auto whole = perception::procedure_inputs(r, p, slide_options());
  EXPECT_LT(whole[0], 80);
  EXPECT_GT(whole[14], 100);  // the press: 2 counts a row = 200 counts/s
  // Static contact keeps the paper's middle 30 %, whatever the trim.
  EXPECT_EQ(
      perception::procedure_inputs(r, perception::Procedure::static_contact, o),
      perception::procedure_inputs(r, perception::Procedure::static_contact, slide_options()));
}

TEST(PerceptionFeatures, BadTrimAndNamesAreClearErrors) {
  const auto message = [](auto&& f) {
    try {
      f();
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("(no error)");
  };
  const auto r = tared_slide();
  auto o = slide_options();
  o.trim_fraction = 0.5;
  const auto c = perception::find_contact(r, o);
  const auto half = message(
      [&] { perception::find_feature_contact(r, perception::Procedure::distal_proximal, c, o); });
  EXPECT_NE(half.find("trim fraction 0.5 is outside [0, 0.5)"), std::string::npos) << half;
  const auto negative = message([] { perception::check_trim_fraction(-0.1); });
  EXPECT_NE(negative.find("-0.1"), std::string::npos) << negative;
  EXPECT_EQ(message([] { perception::check_trim_fraction(0.0); }), "(no error)");
  const auto electrodes = message([] { perception::parse_electrodes("all"); });
  EXPECT_NE(electrodes.find("'all' (known: clusters, each)"), std::string::npos) << electrodes;
  const auto baseline = message([] { perception::parse_baseline_at("middle"); });
  EXPECT_NE(baseline.find("'middle' (known: start, end, none)"), std::string::npos) << baseline;
  for (const auto& [value, name] : perception::kElectrodesNames)
    EXPECT_EQ(perception::parse_electrodes(perception::to_string(value)), value) << name;
  for (const auto& [value, name] : perception::kBaselineAtNames)
    EXPECT_EQ(perception::parse_baseline_at(perception::to_string(value)), value) << name;
}
