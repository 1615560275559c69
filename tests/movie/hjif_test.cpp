// MPEG-I Haptics interchange files: the written file follows the format's rules (checked here
// independently of the writer, from the rules the format's reference loader applies), a movie
// survives export -> import, and every file the importer cannot represent is refused by field.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <nlohmann/json.hpp>
#include <set>
#include <string>

#include "tactile/common/error.hpp"
#include "tactile/movie/hjif.hpp"
#include "test_movies.hpp"

namespace tactile::movie {
namespace {

using nlohmann::json;
using ::testing::HasSubstr;

Layout grid_layout(std::int32_t rows, std::int32_t cols) {
  Layout l = stress_layout();
  l.name = "grid";
  l.rows = rows;
  l.cols = cols;
  return l;
}

TactileMovie movie_on(const Layout& l, std::int32_t frames, double rate_hz = 0) {
  const double rate = rate_hz > 0 ? rate_hz : l.max_rate_hz;
  return testing::sine_movie(l, rate, frames, 0.8 * l.deflection_max_um, 7);
}

// The rules of the format as its reference loader and bitstream check them, applied to the
// text alone: the writer's constants are not used, so a wrong constant there fails here.
void expect_conformant(const std::string& text, const TactileMovie& m) {
  const json d = json::parse(text);
  for (const char* key : {"version", "profile", "level", "date", "description", "timescale",
                          "perceptions", "avatars", "syncs"}) {
    ASSERT_TRUE(d.contains(key)) << key;
  }
  // "20YY" or "20YY-N" (N 1-9), checked by hand: GCC 12's <regex> does not build warning-free
  // under the sanitizers.
  const std::string version = d["version"].get<std::string>();
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  EXPECT_TRUE((version.size() == 4 || (version.size() == 6 && version[4] == '-' &&
                                       version[5] >= '1' && version[5] <= '9')) &&
              version.compare(0, 2, "20") == 0 && version[2] >= '2' && digit(version[2]) &&
              digit(version[3]))
      << version;
  EXPECT_GE(std::stoi(d["version"].get<std::string>().substr(0, 4)), 2023);
  EXPECT_EQ(d["profile"], "Main");
  const int channels = m.layout.rows * m.layout.cols;
  EXPECT_EQ(d["level"], channels > 127 ? 2 : 1);  // level 1: at most 127 channels
  const auto timescale = d["timescale"].get<std::int64_t>();
  EXPECT_LE(timescale, 48000);
  EXPECT_LE(d["description"].get<std::string>().size(), 255U);
  ASSERT_EQ(d["perceptions"].size(), 1U);
  const json& p = d["perceptions"][0];
  for (const char* key :
       {"id", "avatar_id", "description", "perception_modality", "channels", "effect_library"}) {
    ASSERT_TRUE(p.contains(key)) << key;
  }
  EXPECT_EQ(p["perception_modality"], "Position");
  EXPECT_LE(p["description"].get<std::string>().size(), 255U);
  ASSERT_EQ(p["reference_devices"].size(), 1U);
  const json& dev = p["reference_devices"][0];
  EXPECT_TRUE(
      (std::set<std::string>{"Unknown", "LRA", "VCA", "ERM", "Piezo"}.contains(dev["type"])));
  EXPECT_GE(dev["maximum_frequency"].get<double>(), dev["minimum_frequency"].get<double>());
  EXPECT_GE(dev["maximum_displacement"].get<double>(), 50.0 * 0.8);
  const double to_um = std::pow(10.0, p["perception_unit_exponent"].get<int>() + 6);

  const json& chans = p["channels"];
  ASSERT_EQ(static_cast<int>(chans.size()), channels);
  std::set<int> ids;
  std::set<std::pair<int, int>> targets;
  const std::set<std::string> body_parts = {"Finger", "Third Phalanx", "Index", "Hand"};
  for (const json& c : chans) {
    for (const char* key : {"id", "description", "gain", "mixing_coefficient", "body_part_mask",
                            "bands", "actuator_resolution", "actuator_target", "direction",
                            "frequency_sampling", "sample_count"}) {
      ASSERT_TRUE(c.contains(key)) << key;
    }
    EXPECT_TRUE(ids.insert(c["id"].get<int>()).second);
    EXPECT_LE(c["description"].get<std::string>().size(), 255U);
    // The fingers of the right and of the left hand in the reference software's body table
    // (OHMData::Body: RIGHT_HAND_FINGERS 0x00100000, LEFT_HAND_FINGERS 0x00200000), which it
    // copies unchanged into a channel's body_part_mask; no other part.
    EXPECT_EQ(c["body_part_mask"].get<std::uint32_t>(), 0x00100000U | 0x00200000U);
    for (const auto& part : c["body_part_target"]) EXPECT_TRUE(body_parts.contains(part));
    const json& res = c["actuator_resolution"];
    EXPECT_EQ(res["X"], m.layout.cols);
    EXPECT_EQ(res["Y"], m.layout.rows);
    EXPECT_LE(res["X"].get<int>(), 127);
    EXPECT_LE(res["Y"].get<int>(), 127);
    ASSERT_EQ(c["actuator_target"].size(), 1U);
    const json& t = c["actuator_target"][0];
    EXPECT_GE(t["X"].get<int>(), 0);
    EXPECT_LT(t["X"].get<int>(), res["X"].get<int>());
    EXPECT_GE(t["Y"].get<int>(), 0);
    EXPECT_LT(t["Y"].get<int>(), res["Y"].get<int>());
    EXPECT_TRUE(targets.insert({t["X"].get<int>(), t["Y"].get<int>()}).second);
    const json& dir = c["direction"];
    const double norm =
        std::hypot(dir["X"].get<double>(), dir["Y"].get<double>(), dir["Z"].get<double>()) / 127;
    EXPECT_NEAR(norm, 1.0, 0.01);
    EXPECT_EQ(dir[m.layout.axis == DeflectionAxis::x ? "X" : "Y"], 127);
    const auto rate = c["frequency_sampling"].get<std::int64_t>();
    EXPECT_EQ(rate, static_cast<std::int64_t>(m.rate_hz));
    EXPECT_EQ(c["sample_count"], m.frame_count);
    EXPECT_EQ(timescale % rate, 0) << "samples must fall on whole ticks";
    const std::int64_t ticks_per_sample = timescale / rate;
    ASSERT_LE(c["bands"].size(), 7U);
    ASSERT_EQ(c["bands"].size(), 1U);
    const json& band = c["bands"][0];
    EXPECT_EQ(band["band_type"], "Curve");
    EXPECT_EQ(band["curve_type"], "Linear");
    EXPECT_LE(band["lower_frequency_limit"].get<int>(), band["upper_frequency_limit"].get<int>());
    const int k = t["Y"].get<int>() * m.layout.cols + t["X"].get<int>();
    const double gain = c["gain"].get<double>();
    EXPECT_GT(gain, 0.1);
    EXPECT_LE(gain, 1.0);
    ASSERT_FALSE(band["effects"].empty());
    EXPECT_EQ(band["effects"][0]["position"], 0);  // the reference synthesiser renders it
    std::int64_t next_sample = 0;
    for (const json& e : band["effects"]) {
      EXPECT_EQ(e["effect_type"], "Basis");
      const auto& kfs = e["keyframes"];
      EXPECT_NE(kfs.size(), 2U) << "an effect of two keyframes renders silent";
      EXPECT_LE(kfs.size(), 65535U);
      const auto position = e["position"].get<std::int64_t>();
      EXPECT_LT(position, 1 << 25);
      for (const json& kf : kfs) {
        const auto rel = kf["relative_position"].get<std::int64_t>();
        EXPECT_LE(rel, 65535);
        const double a = kf["amplitude_modulation"].get<double>();
        EXPECT_LE(std::abs(a), 1.0);
        const std::int64_t tick = position + rel;
        if (tick % ticks_per_sample != 0) continue;  // a point between samples (one frame)
        const std::int64_t s = tick / ticks_per_sample;
        if (s == m.frame_count) {
          // The closing keyframe: the last frame held for one period, at the very end.
          EXPECT_EQ(&e, &band["effects"].back());
          EXPECT_EQ(&kf, &kfs.back());
          EXPECT_NEAR(a * gain * to_um, m.frame(m.frame_count - 1)[k], 1e-4);
          continue;
        }
        EXPECT_EQ(s, next_sample);
        ++next_sample;
        ASSERT_LT(s, m.frame_count);
        EXPECT_NEAR(a * gain * to_um, m.frame(static_cast<std::int32_t>(s))[k], 1e-4);
      }
    }
    EXPECT_EQ(next_sample, m.frame_count) << "one keyframe per sample";
  }
}

TEST(Hjif, BuiltInLayoutsFollowTheFormatsRules) {
  for (const Layout& l : {stress_layout(), stress2_layout(), latero_layout()}) {
    SCOPED_TRACE(l.name);
    const TactileMovie m = movie_on(l, 300);
    HjifSummary s;
    const std::string text = hjif_text(m, {}, &s);
    expect_conformant(text, m);
    EXPECT_EQ(s.channels, l.rows * l.cols);
    EXPECT_EQ(s.effects_per_channel, 1);
  }
}

TEST(Hjif, MoreThan127ChannelsIsLevel2) {
  const TactileMovie m = movie_on(grid_layout(12, 12), 20);
  HjifSummary s;
  const std::string text = hjif_text(m, {}, &s);
  EXPECT_EQ(s.level, 2);
  expect_conformant(text, m);
  EXPECT_EQ(json::parse(hjif_text(movie_on(grid_layout(127, 1), 5)))["level"], 1);
  EXPECT_EQ(json::parse(hjif_text(movie_on(grid_layout(64, 2), 5)))["level"], 2);
}

void expect_same_movie(const TactileMovie& a, const TactileMovie& b, double tolerance_um) {
  EXPECT_EQ(a.layout.name, b.layout.name);
  EXPECT_EQ(a.layout.rows, b.layout.rows);
  EXPECT_EQ(a.layout.cols, b.layout.cols);
  EXPECT_EQ(a.layout.axis, b.layout.axis);
  EXPECT_DOUBLE_EQ(a.layout.pitch_x_mm, b.layout.pitch_x_mm);
  EXPECT_DOUBLE_EQ(a.layout.pitch_y_mm, b.layout.pitch_y_mm);
  EXPECT_DOUBLE_EQ(a.layout.contactor_width_mm, b.layout.contactor_width_mm);
  EXPECT_DOUBLE_EQ(a.layout.deflection_min_um, b.layout.deflection_min_um);
  EXPECT_DOUBLE_EQ(a.layout.deflection_max_um, b.layout.deflection_max_um);
  EXPECT_DOUBLE_EQ(a.layout.max_rate_hz, b.layout.max_rate_hz);
  EXPECT_DOUBLE_EQ(a.rate_hz, b.rate_hz);
  ASSERT_EQ(a.frame_count, b.frame_count);
  ASSERT_EQ(a.deflection_um.size(), b.deflection_um.size());
  double worst = 0;
  for (std::size_t i = 0; i < a.deflection_um.size(); ++i) {
    worst = std::max(worst, std::abs(double(a.deflection_um[i]) - b.deflection_um[i]));
  }
  EXPECT_LE(worst, tolerance_um);
  EXPECT_EQ(a.provenance.program_version, b.provenance.program_version);
  EXPECT_EQ(a.provenance.created_utc, b.provenance.created_utc);
  EXPECT_EQ(a.provenance.input, b.provenance.input);
  EXPECT_EQ(a.provenance.command_line, b.provenance.command_line);
  EXPECT_EQ(a.provenance.method, b.provenance.method);
  EXPECT_EQ(a.provenance.parameters_json, b.provenance.parameters_json);
}

TEST(Hjif, RoundTripKeepsLayoutRateProvenanceAndDeflections) {
  for (const Layout& l : {stress_layout(), stress2_layout(), latero_layout()}) {
    SCOPED_TRACE(l.name);
    TactileMovie m = movie_on(l, 257);
    m.provenance.created_utc = "2026-01-02T03:04:05Z";
    // Longer than one description may hold: it travels in pieces over the channels.
    m.provenance.parameters_json = json{{"note", std::string(700, 'x') + "é"}}.dump();
    const TactileMovie back = parse_hjif(hjif_text(m), "test");
    // Amplitudes are written in steps of 1e-6 of the full scale (100 um at most here).
    expect_same_movie(m, back, 1e-4);
  }
}

TEST(Hjif, LongMoviesAreSplitIntoEffectsNoneOfTwoKeyframes) {
  HjifOptions o;
  o.max_effect_ticks = 9;  // 9 samples per effect, 10 keyframes in the last
  for (std::int32_t frames : {45, 46, 47, 50}) {
    SCOPED_TRACE(frames);
    const TactileMovie m = movie_on(grid_layout(2, 3), frames, 700);
    HjifSummary s;
    const std::string text = hjif_text(m, o, &s);
    EXPECT_EQ(s.effects_per_channel, (frames + 8) / 9);
    expect_conformant(text, m);
    // Held in a variable: a range-for over a part of a temporary would outlive the temporary.
    const json doc = json::parse(text);
    for (const json& e : doc["perceptions"][0]["channels"][0]["bands"][0]["effects"]) {
      EXPECT_LE(e["keyframes"].back()["relative_position"].get<int>(), 9);
      EXPECT_GE(e["keyframes"].size(), 3U);
    }
    expect_same_movie(m, parse_hjif(text, "test"), 1e-4);
  }
}

TEST(Hjif, TicksPerSampleScaleTheTimescale) {
  HjifOptions o;
  o.ticks_per_sample = 10;
  const TactileMovie m = movie_on(stress_layout(), 40);
  const std::string text = hjif_text(m, o);
  EXPECT_EQ(json::parse(text)["timescale"], 7000);
  expect_conformant(text, m);
  expect_same_movie(m, parse_hjif(text, "test"), 1e-4);
}

TEST(Hjif, OneFrameGetsAThirdKeyframeHalfWay) {
  const TactileMovie m = movie_on(stress_layout(), 1);
  const std::string text = hjif_text(m);
  const json d = json::parse(text);
  EXPECT_EQ(d["timescale"], 1400);
  EXPECT_EQ(d["perceptions"][0]["channels"][0]["bands"][0]["effects"][0]["keyframes"].size(), 3U);
  expect_conformant(text, m);
  expect_same_movie(m, parse_hjif(text, "test"), 1e-4);
}

TEST(Hjif, RefusesMoviesBeyondTheFormat) {
  EXPECT_THAT([] { hjif_text(movie_on(stress_layout(), 10, 699.5)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("whole number of hertz")));
  EXPECT_THAT(
      [] { hjif_text(movie_on(stress_layout(), 10, 50000)); },
      ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("must be from 1 to 48000")));
  EXPECT_THAT([] { hjif_text(movie_on(grid_layout(128, 1), 3)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("at most 127 per side")));
  EXPECT_THAT([] { hjif_text(movie_on(stress_layout(), 0)); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("no frames")));
}

// A file written by hand, as another tool would: keyframes every 5 samples, no layout inside.
const char* kForeign = R"({
  "version": "2023", "profile": "Main", "level": 1, "date": "2024-05-01",
  "description": "hand made", "timescale": 1000, "avatars": [], "syncs": [],
  "perceptions": [{
    "id": 0, "avatar_id": 0, "description": "ramp", "perception_modality": "Position",
    "perception_unit_exponent": -5, "effect_library": [],
    "channels": [
      {"id": 0, "description": "a", "gain": 0.5, "mixing_coefficient": 1, "body_part_mask": 0,
       "frequency_sampling": 100, "sample_count": 12,
       "actuator_resolution": {"X": 2, "Y": 1, "Z": 1}, "actuator_target": [{"X": 1, "Y": 0, "Z": 0}],
       "bands": [{"band_type": "Curve", "curve_type": "Linear", "lower_frequency_limit": 0,
                  "upper_frequency_limit": 50, "effects": [{"effect_type": "Basis", "position": 0,
                  "keyframes": [{"relative_position": 0, "amplitude_modulation": 0},
                                {"relative_position": 50, "amplitude_modulation": 1},
                                {"relative_position": 100, "amplitude_modulation": 0}]}]}]},
      {"id": 1, "description": "b", "gain": 1, "mixing_coefficient": 1, "body_part_mask": 0,
       "frequency_sampling": 100, "sample_count": 12,
       "actuator_resolution": {"X": 2, "Y": 1, "Z": 1}, "actuator_target": [{"X": 0, "Y": 0, "Z": 0}],
       "bands": [{"band_type": "Curve", "curve_type": "Linear", "lower_frequency_limit": 0,
                  "upper_frequency_limit": 50, "effects": [{"effect_type": "Basis", "position": 20,
                  "keyframes": [{"relative_position": 0, "amplitude_modulation": -0.5},
                                {"relative_position": 30, "amplitude_modulation": -0.5}]}]}]}
    ]}]})";

TEST(Hjif, ImportsAFileFromAnotherToolThroughItsTargets) {
  HjifImportOptions o;
  o.layout = grid_layout(1, 2);
  const TactileMovie m = parse_hjif(kForeign, "foreign.hjif", o);
  EXPECT_EQ(m.frame_count, 12);
  EXPECT_DOUBLE_EQ(m.rate_hz, 100);
  // Channel 0 targets column 1: amplitude 1 = 0.5 x 10^-5 m = 5 um, a triangle over samples 0..10
  // (10 ms per sample, 10 ticks per sample).
  const double triangle[12] = {0, 1, 2, 3, 4, 5, 4, 3, 2, 1, 0, 0};
  // Channel 1 targets column 0: amplitude 1 = 10 um, -5 um from tick 20 to 50 (samples 2..5).
  const double step[12] = {0, 0, -5, -5, -5, -5, 0, 0, 0, 0, 0, 0};
  for (int f = 0; f < 12; ++f) {
    EXPECT_NEAR(m.frame(f)[1], triangle[f], 1e-5) << f;
    EXPECT_NEAR(m.frame(f)[0], step[f], 1e-5) << f;
  }
  EXPECT_THAT([] { parse_hjif(kForeign, "foreign.hjif"); },
              ::testing::ThrowsMessage<FormatError>(HasSubstr("give the display's layout")));
  o.layout = grid_layout(2, 1);
  EXPECT_THAT([&] { parse_hjif(kForeign, "foreign.hjif", o); },
              ::testing::ThrowsMessage<FormatError>(HasSubstr("actuator_resolution is 1 x 2")));
}

// The written file with one edit, parsed: the message must name `expected`.
void expect_refused(const std::function<void(json&)>& edit, const std::string& expected) {
  json d = json::parse(hjif_text(movie_on(grid_layout(2, 2), 6)));
  edit(d);
  EXPECT_THAT([&] { parse_hjif(d.dump(), "bad.hjif"); },
              ::testing::ThrowsMessage<FormatError>(HasSubstr(expected)));
}

json& channel(json& d, int i) {
  return d["perceptions"][0]["channels"][i];
}
json& band(json& d, int i) {
  return channel(d, i)["bands"][0];
}

TEST(Hjif, RefusesWhatAMovieCannotRepresentNamingTheField) {
  expect_refused([](json& d) { d.erase("timescale"); }, "missing field 'timescale'");
  expect_refused([](json& d) { d["profile"] = "Advanced"; }, "'profile' is \"Advanced\"");
  expect_refused([](json& d) { d["level"] = 3; }, "level 3 is out of range");
  expect_refused([](json& d) { d["timescale"] = 96000; }, "timescale 96000 is out of range");
  expect_refused([](json& d) { d["perceptions"].push_back(d["perceptions"][0]); },
                 "holds 2 perceptions");
  expect_refused([](json& d) { d["perceptions"][0]["perception_modality"] = "Vibrotactile"; },
                 "perceptions[0].perception_modality' is \"Vibrotactile\"");
  expect_refused([](json& d) { band(d, 1)["band_type"] = "WaveletWave"; },
                 "perceptions[0].channels[1].bands[0].band_type' is \"WaveletWave\"");
  expect_refused([](json& d) { band(d, 0)["curve_type"] = "Cubic"; }, "curve_type' is \"Cubic\"");
  expect_refused([](json& d) { band(d, 0)["effects"][0]["effect_type"] = "Reference"; },
                 "effect_type' is \"Reference\"");
  expect_refused([](json& d) { channel(d, 3)["actuator_target"][0]["X"] = 2; },
                 "channels[3].actuator_target (2, 1, 0) is outside the actuator_resolution");
  expect_refused([](json& d) { channel(d, 3)["actuator_target"][0]["Y"] = -1; },
                 "outside the actuator_resolution");
  expect_refused(
      [](json& d) { channel(d, 3)["actuator_target"] = channel(d, 0)["actuator_target"]; },
      "is also the target of channel 0");
  expect_refused([](json& d) { channel(d, 2).erase("gain"); }, "channels[2]: missing field 'gain'");
  expect_refused([](json& d) { channel(d, 2)["gain"] = "loud"; },
                 "channels[2].gain' must be a number");
  expect_refused(
      [](json& d) {
        channel(d, 1)["direction"] = {{"X", 90}, {"Y", 90}, {"Z", 0}};
      },
      "channels[1].direction (90, 90, 0)");
  expect_refused(
      [](json& d) { band(d, 0)["effects"][0]["keyframes"][1]["amplitude_modulation"] = 2; },
      "keyframes[1].amplitude_modulation 2 is out of range");
  expect_refused([](json& d) { band(d, 0)["effects"][0]["keyframes"][2]["relative_position"] = 1; },
                 "keyframes[2].relative_position 1 does not increase");
  expect_refused([](json& d) { d["perceptions"][0]["channels"].erase(3); },
                 "holds 3 channels but the actuator_resolution 2 x 2 has 4");
  expect_refused(
      [](json& d) {
        for (int i = 0; i < 4; ++i) channel(d, i)["sample_count"] = 2000000000;
      },
      "more than the limit");
  // The 6-frame movie's keyframes reach sample 6 (the closing one): with 3 samples declared,
  // those past sample 3 have nowhere to go.
  expect_refused(
      [](json& d) {
        for (int i = 0; i < 4; ++i) channel(d, i)["sample_count"] = 3;
      },
      "past the movie's end (sample_count 3)");
  expect_refused([](json& d) { channel(d, 1)["frequency_sampling"] = 500; },
                 "must be those of channel 0");
  expect_refused([](json& d) { d["perceptions"][0]["description"] = "tactile-movie layout {"; },
                 "not valid JSON");
  expect_refused([](json& d) { channel(d, 0)["description"] = "r0 c0\t{\"source\": 3"; },
                 "provenance in the channel descriptions: not valid JSON");
}

TEST(Hjif, RefusesFilesThatAreNotHjif) {
  for (const char* text : {"", "{", "[1, 2]", "{\"version\": \"2023\"}", "null"}) {
    EXPECT_THROW(parse_hjif(text, "junk.hjif"), FormatError) << text;
  }
  EXPECT_THAT([] { read_hjif("/nonexistent/x.hjif"); },
              ::testing::ThrowsMessage<FormatError>(HasSubstr("/nonexistent/x.hjif: cannot open")));
}

}  // namespace
}  // namespace tactile::movie
