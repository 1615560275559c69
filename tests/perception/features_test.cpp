// Signal analysis: contact at 0.2 % of baseline, the windows, and the 76 inputs of Table 1, on
// hand-made recordings with a known answer and on the simulated sensor.

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "tactile/perception/eval.hpp"
#include "tactile/perception/features.hpp"
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
