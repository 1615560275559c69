// MPEG-I Haptics interchange files (HJIF): writer and strict reader. The rules follow the
// format's limits as its reference software checks them; the mapping is in docs/formats.md.

#include "tactile/movie/hjif.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <functional>
#include <limits>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "tactile/common/atomic_write.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/json.hpp"
#include "tactile/common/value_checks.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::movie {
namespace {

using nlohmann::json;

// The perception's description starts with this, then the layout as compact JSON; channel
// descriptions carry the provenance in pieces after a tab (see docs/formats.md).
constexpr const char* kLayoutPrefix = "tactile-movie layout ";
constexpr std::size_t kProvenancePieceBytes = 200;
constexpr std::int32_t kVectorRange = 127;  // a unit vector's component
// body_part_target of every channel: the distal phalanx of a finger (the display is felt with a
// fingertip; which finger is not known).
const std::vector<std::string> kFingertip = {"Finger", "Third Phalanx"};
// body_part_mask of every channel: the fingers of either hand (which hand is not known), in the
// bit table of the format's reference software (docs/formats.md): right-hand fingers bit 20,
// left-hand fingers bit 21.
constexpr std::uint32_t kFingersOfEitherHand = (1U << 20) | (1U << 21);

// `text` cut into pieces of at most `bytes`, never inside a UTF-8 sequence.
std::vector<std::string> pieces(const std::string& text, std::size_t bytes) {
  std::vector<std::string> out;
  std::size_t at = 0;
  while (at < text.size()) {
    std::size_t end = std::min(text.size(), at + bytes);
    while (end < text.size() && end > at + 1 &&
           (static_cast<unsigned char>(text[end]) & 0xC0U) == 0x80U) {
      --end;
    }
    out.push_back(text.substr(at, end - at));
    at = end;
  }
  return out;
}

// Gain and perception_unit_exponent such that gain * 10^exponent metres is the full scale, with
// 0.1 < gain <= 1: a renderer that ignores the exponent still never drives beyond amplitude 1.
std::pair<double, int> gain_and_exponent(double full_scale_um) {
  const int k = static_cast<int>(std::ceil(std::log10(full_scale_um)));
  return {full_scale_um / std::pow(10.0, k), k - 6};
}

std::string amplitude_text(double a) {
  const double q = std::round(a / kHjifAmplitudeStep) * kHjifAmplitudeStep;
  return q == 0 ? std::string("0") : fmt::format("{}", q);
}

// The JSON text of `j` without its closing brace, so that a member can be appended.
std::string open_object(const json& j) {
  std::string s = j.dump();
  s.pop_back();
  return s;
}

// First sample of each effect: the movie split into effects of at most `per_effect` samples.
// The last effect ends with one more keyframe (the last frame held for its frame period), so
// it gets at least two samples: then no effect has exactly two keyframes, which the reference
// synthesiser renders silent.
std::vector<std::int32_t> effect_starts(std::int32_t frames, std::int64_t per_effect) {
  std::vector<std::int32_t> starts;
  for (std::int64_t s = 0; s < frames; s += per_effect) {
    starts.push_back(static_cast<std::int32_t>(s));
  }
  if (starts.size() >= 2 && frames - starts.back() == 1) --starts.back();
  return starts;
}

}  // namespace

double full_scale_um(const TactileMovie& movie) {
  double peak =
      std::max(std::abs(movie.layout.deflection_min_um), std::abs(movie.layout.deflection_max_um));
  for (const float v : movie.deflection_um) peak = std::max(peak, std::abs(static_cast<double>(v)));
  return peak;
}

namespace {

// The HJIF text handed to `sink` a channel at a time, so that a long movie never sits in memory
// as text whole.
HjifSummary write_hjif_to(const TactileMovie& movie, const HjifOptions& options,
                          const std::function<void(const std::string&)>& sink) {
  validate_movie(movie);
  const Layout& l = movie.layout;
  if (movie.frame_count < 1) {
    throw std::invalid_argument("HJIF: the movie has no frames; an HJIF channel needs a keyframe");
  }
  if (movie.rate_hz != std::round(movie.rate_hz)) {
    throw std::invalid_argument(fmt::format(
        "HJIF: rate {:g} Hz is not a whole number of hertz (frequency_sampling is an integer)",
        movie.rate_hz));
  }
  if (options.ticks_per_sample < 1 || options.ticks_per_sample > kHjifMaxTimescale) {
    throw std::invalid_argument(
        fmt::format("HJIF: ticks per sample {} is out of range: must be from 1 to {}",
                    options.ticks_per_sample, kHjifMaxTimescale));
  }
  std::int32_t tps = options.ticks_per_sample;
  // One frame and its closing keyframe make an effect of two keyframes, which the reference
  // synthesiser renders silent: a third keyframe half way needs an even tick count.
  if (movie.frame_count == 1 && tps % 2 != 0) tps *= 2;
  const auto rate = static_cast<std::int64_t>(movie.rate_hz);
  if (tps < 1 || rate * tps > kHjifMaxTimescale) {
    throw std::invalid_argument(fmt::format(
        "HJIF: timescale {} Hz x {} ticks per sample = {} is out of range: must be from 1 to {} "
        "(profile Main)",
        rate, tps, rate * tps, kHjifMaxTimescale));
  }
  if (l.rows > kHjifMaxGridSide || l.cols > kHjifMaxGridSide) {
    throw std::invalid_argument(fmt::format(
        "HJIF: layout {} x {} is out of range: actuator_resolution allows at most {} per side",
        l.rows, l.cols, kHjifMaxGridSide));
  }
  const std::int32_t channels = l.contactor_count();
  if (channels > kHjifLevel2MaxChannels) {
    throw std::invalid_argument(fmt::format("HJIF: {} contactors is out of range: must be <= {}",
                                            channels, kHjifLevel2MaxChannels));
  }
  // Samples per effect, with room for the closing keyframe of the last one.
  const std::int64_t per_effect = std::min(options.max_effect_ticks / tps, kHjifMaxKeyframes - 1);
  if (per_effect < 4) {
    throw std::invalid_argument(
        fmt::format("HJIF: max_effect_ticks {} holds fewer than 4 samples at {} ticks per sample",
                    options.max_effect_ticks, tps));
  }

  if (static_cast<std::int64_t>(movie.frame_count) * tps > kHjifMaxEffectPosition) {
    throw std::invalid_argument(fmt::format(
        "HJIF: {} frames at {} ticks per sample is out of range: effect positions reach at most "
        "tick {}",
        movie.frame_count, tps, kHjifMaxEffectPosition));
  }
  const double scale_um = full_scale_um(movie);
  const auto [gain, exponent] = gain_and_exponent(scale_um);
  const std::int32_t level = channels > kHjifLevel1MaxChannels ? 2 : 1;
  const std::string layout_text = kLayoutPrefix + json::parse(layout_to_json(l)).dump();
  if (layout_text.size() > kHjifMaxDescriptionBytes) {
    throw std::invalid_argument(
        fmt::format("HJIF: the layout takes {} bytes in the perception description, more than "
                    "the {} a description may hold (shorten the layout name)",
                    layout_text.size(), kHjifMaxDescriptionBytes));
  }
  const std::string summary_text =
      fmt::format("tactile movie: {} x {} contactors ({}), {} deflection, {:g} Hz, {} frames",
                  l.rows, l.cols, l.name, to_string(l.axis), movie.rate_hz, movie.frame_count);
  const std::string created = movie.provenance.created_utc;
  const std::string date = created.size() >= 10 ? created.substr(0, 10) : "2023-01-01";

  json head = {{"version", "2023"},
               {"profile", "Main"},
               {"level", level},
               {"date", date},
               {"description", pieces(summary_text, kHjifMaxDescriptionBytes).front()},
               {"timescale", rate * tps},
               {"avatars", json::array()},
               {"syncs", json::array()}};
  json device = {{"id", 0},
                 {"name", fmt::format("{} lateral skin-stretch display",
                                      pieces(l.name, kHjifMaxDescriptionBytes - 40).front())},
                 {"type", "Piezo"},
                 {"maximum_displacement", scale_um},
                 {"minimum_frequency", 0.0},
                 {"maximum_frequency", l.max_rate_hz / 2}};
  json perception = {{"id", 0},
                     {"avatar_id", 0},
                     {"description", layout_text},
                     {"perception_modality", "Position"},
                     {"unit_exponent", -6},
                     {"perception_unit_exponent", exponent},
                     {"reference_devices", json::array({device})},
                     {"effect_library", json::array()}};
  const json direction = l.axis == DeflectionAxis::x
                             ? json{{"X", kVectorRange}, {"Y", 0}, {"Z", 0}}
                             : json{{"X", 0}, {"Y", kVectorRange}, {"Z", 0}};
  const json band = {{"band_type", "Curve"},
                     {"curve_type", "Linear"},
                     {"lower_frequency_limit", 0},
                     {"upper_frequency_limit", rate / 2}};
  const std::vector<std::string> provenance =
      pieces(provenance_json(movie.provenance).dump(), kProvenancePieceBytes);
  const std::vector<std::int32_t> starts = effect_starts(movie.frame_count, per_effect);

  std::string out = open_object(head);
  out += ",\"perceptions\":[" + open_object(perception) + ",\"channels\":[\n";
  for (std::int32_t k = 0; k < channels; ++k) {
    const std::int32_t r = k / l.cols, c = k % l.cols;
    std::string description = fmt::format("r{} c{}", r, c);
    if (static_cast<std::size_t>(k) < provenance.size()) {
      // A layout with fewer contactors than pieces keeps the rest in its last channel.
      description += '\t';
      for (std::size_t p = k; p < provenance.size(); ++p) {
        description += provenance[p];
        if (k + 1 < channels) break;
      }
    }
    const json channel = {{"id", k},
                          {"description", description},
                          {"gain", gain},
                          {"mixing_coefficient", 1.0},
                          {"body_part_mask", kFingersOfEitherHand},
                          {"body_part_target", kFingertip},
                          {"reference_device_id", 0},
                          {"frequency_sampling", rate},
                          {"sample_count", movie.frame_count},
                          {"direction", direction},
                          {"actuator_resolution", {{"X", l.cols}, {"Y", l.rows}, {"Z", 1}}},
                          {"actuator_target", json::array({{{"X", c}, {"Y", r}, {"Z", 0}}})}};
    if (out.size() >= (1U << 20)) {
      sink(out);
      out.clear();
    }
    out += k ? ",\n" : "";
    out += open_object(channel) + ",\"bands\":[" + open_object(band) + ",\"effects\":[";
    for (std::size_t e = 0; e < starts.size(); ++e) {
      const std::int32_t s0 = starts[e];
      const std::int32_t s1 = e + 1 < starts.size() ? starts[e + 1] : movie.frame_count;
      out +=
          fmt::format("{}\n{{\"id\":{},\"effect_type\":\"Basis\",\"position\":{},\"keyframes\":[",
                      e ? "," : "", e, static_cast<std::int64_t>(s0) * tps);
      const bool last = e + 1 == starts.size();
      // The last frame lasts one frame period: a closing keyframe holds it until the movie's
      // end (the reference synthesiser also drops an effect's last keyframe).
      for (std::int32_t s = s0; s < s1 + (last ? 1 : 0); ++s) {
        const double a = movie.frame(std::min(s, s1 - 1))[static_cast<std::size_t>(k)] / scale_um;
        out += fmt::format("{}{{\"relative_position\":{},\"amplitude_modulation\":{}}}",
                           s > s0 ? "," : "", static_cast<std::int64_t>(s - s0) * tps,
                           amplitude_text(a));
        if (movie.frame_count == 1 && s == 0) {
          out += fmt::format(",{{\"relative_position\":{},\"amplitude_modulation\":{}}}", tps / 2,
                             amplitude_text(a));
        }
      }
      out += "]}";
    }
    out += "]}]}";
  }
  out += "\n]}]}\n";
  sink(out);
  return {channels, level, rate * tps, static_cast<std::int32_t>(starts.size()), scale_um};
}

}  // namespace

std::string hjif_text(const TactileMovie& movie, const HjifOptions& options, HjifSummary* summary) {
  std::string text;
  const HjifSummary s =
      write_hjif_to(movie, options, [&text](const std::string& part) { text += part; });
  if (summary) *summary = s;
  return text;
}

HjifSummary write_hjif(const TactileMovie& movie, const std::filesystem::path& path,
                       const HjifOptions& options) {
  AtomicFile file(path);
  const HjifSummary s =
      write_hjif_to(movie, options, [&file](const std::string& part) { file.write(part); });
  file.commit();
  return s;
}

namespace {

// The reader: every field it uses is checked where it is read, and messages name the field by
// its path in the document, e.g. "perceptions[0].channels[3].actuator_target".
class Reader {
 public:
  explicit Reader(std::string where) : at_{std::move(where)} {}

  [[noreturn]] void fail(const std::string& what) const { at_.fail(what); }

  const json& need(const json& j, const char* key, const std::string& path) const {
    if (!j.is_object())
      fail(fmt::format("{} must be a JSON object", path.empty() ? "the file" : path));
    if (!j.contains(key)) {
      fail(path.empty() ? fmt::format("missing field '{}'", key)
                        : fmt::format("{}: missing field '{}'", path, key));
    }
    return j.at(key);
  }
  std::string field_path(const std::string& path, const char* key) const {
    return path.empty() ? std::string(key) : path + "." + key;
  }
  std::int64_t integer(const json& j, const char* key, const std::string& path) const {
    return json_integer(at_, need(j, key, path), field_path(path, key));
  }
  std::int64_t integer_in(const json& j, const char* key, const std::string& path, std::int64_t min,
                          std::int64_t max) const {
    return checks::int_in_range(integer(j, key, path), min, max, at_.origin, field_path(path, key));
  }
  double number(const json& j, const char* key, const std::string& path) const {
    return json_number(at_, need(j, key, path), field_path(path, key));
  }
  std::string string(const json& j, const char* key, const std::string& path) const {
    const json& v = need(j, key, path);
    if (!v.is_string()) {
      fail(fmt::format("'{}' must be a string, got {}", field_path(path, key), v.dump()));
    }
    return v.get<std::string>();
  }
  std::string one_of(const json& j, const char* key, const std::string& path,
                     const std::set<std::string>& allowed, const std::string& why) const {
    const std::string v = string(j, key, path);
    if (!allowed.contains(v)) {
      fail(fmt::format("'{}' is \"{}\": {}", field_path(path, key), v, why));
    }
    return v;
  }
  const json& array(const json& j, const char* key, const std::string& path) const {
    const json& v = need(j, key, path);
    if (!v.is_array()) {
      fail(fmt::format("'{}' must be an array", field_path(path, key)));
    }
    return v;
  }
  // A vector {"X": x, "Y": y, "Z": z} of signed 8-bit components.
  std::array<std::int64_t, 3> vector(const json& v, const std::string& path) const {
    std::array<std::int64_t, 3> out{};
    const char* names[3] = {"X", "Y", "Z"};
    for (int i = 0; i < 3; ++i) out[i] = integer_in(v, names[i], path, -128, 127);
    return out;
  }
  const std::string& where() const { return at_.origin; }

 private:
  JsonOrigin at_;
};

struct ChannelRead {
  std::int64_t row = 0, col = 0;
  double scale_um = 0;  // amplitude 1 in micrometres
  std::int64_t rate = 0;
  std::optional<std::int64_t> sample_count;
  std::optional<DeflectionAxis> axis;
  std::string description;
  const json* bands = nullptr;
  std::string path;
};

// One channel's curves sampled at the movie's rate: samples inside an effect get its linear
// curve, samples outside every effect stay 0, overlapping effects and bands add up (as the
// reference synthesiser renders them).
void sample_channel(const Reader& rd, const ChannelRead& ch, std::int64_t timescale,
                    std::int64_t rate, std::int64_t frames, std::int64_t contactors,
                    std::int64_t index, std::vector<double>& out) {
  for (std::size_t b = 0; b < ch.bands->size(); ++b) {
    const json& band = (*ch.bands)[b];
    const std::string bp = fmt::format("{}.bands[{}]", ch.path, b);
    rd.one_of(band, "band_type", bp, {"Curve"},
              "only Curve bands hold a deflection curve (wave and transient bands describe "
              "vibrations, which a tactile movie cannot represent)");
    rd.one_of(band, "curve_type", bp, {"Linear"},
              "only Linear curves are imported exactly (the samples are the keyframes)");
    const json& effects = rd.array(band, "effects", bp);
    for (std::size_t e = 0; e < effects.size(); ++e) {
      const json& effect = effects[e];
      const std::string ep = fmt::format("{}.effects[{}]", bp, e);
      rd.one_of(effect, "effect_type", ep, {"Basis"},
                "only Basis effects carry their own keyframes (library references and "
                "composites are not imported)");
      const std::int64_t position =
          rd.integer_in(effect, "position", ep, 0, std::numeric_limits<std::int32_t>::max());
      const json& keyframes = rd.array(effect, "keyframes", ep);
      std::int64_t prev_tick = -1;
      double prev_value = 0;
      for (std::size_t k = 0; k < keyframes.size(); ++k) {
        const std::string kp = fmt::format("{}.keyframes[{}]", ep, k);
        const std::int64_t rel = rd.integer_in(keyframes[k], "relative_position", kp, 0,
                                               std::numeric_limits<std::int32_t>::max());
        const double amplitude =
            checks::in_range(rd.number(keyframes[k], "amplitude_modulation", kp), -1, 1, rd.where(),
                             kp + ".amplitude_modulation");
        const double value = amplitude * ch.scale_um;
        const std::int64_t tick = position + rel;
        if (k > 0 && tick <= prev_tick) {
          rd.fail(fmt::format("{}.relative_position {} does not increase", kp, rel));
        }
        // The exporter's closing keyframe lies on the movie's end (sample sample_count); one
        // past it would be a sample the movie does not have, dropped without a word.
        if (tick * rate > frames * timescale) {
          rd.fail(fmt::format(
              "{}.relative_position {}: tick {} is sample {:g}, past the movie's end (sample_count "
              "{})",
              kp, rel, tick, static_cast<double>(tick * rate) / static_cast<double>(timescale),
              frames));
        }
        if (k == 0) {
          if ((tick * rate) % timescale == 0 && tick * rate / timescale < frames) {
            out[static_cast<std::size_t>(tick * rate / timescale * contactors + index)] += value;
          }
        } else {
          // The samples after the previous keyframe up to this one, on the line between them.
          const std::int64_t span = (tick - prev_tick) * rate;
          for (std::int64_t n = prev_tick * rate / timescale + 1;
               n < frames && n * timescale <= tick * rate; ++n) {
            const double t =
                static_cast<double>(n * timescale - prev_tick * rate) / static_cast<double>(span);
            out[static_cast<std::size_t>(n * contactors + index)] +=
                prev_value + t * (value - prev_value);
          }
        }
        prev_tick = tick;
        prev_value = value;
      }
    }
  }
}

}  // namespace

TactileMovie parse_hjif(const std::string& text, const std::string& where,
                        const HjifImportOptions& options) {
  const Reader rd(where);
  const json root = parse_json(JsonOrigin{where}, text);
  if (!root.is_object()) rd.fail("an HJIF file must be a JSON object");
  // Required at the top by the format, whether or not this reader uses them.
  rd.string(root, "version", "");
  rd.string(root, "date", "");
  rd.string(root, "description", "");
  rd.array(root, "avatars", "");
  rd.array(root, "syncs", "");
  rd.one_of(root, "profile", "", {"Main", "Simple Parametric"},
            "the format's profiles are \"Main\" and \"Simple "
            "Parametric\"");
  const std::int64_t level = rd.integer_in(root, "level", "", 1, 2);
  const std::int64_t timescale = rd.integer_in(root, "timescale", "", 1, kHjifMaxTimescale);
  const json& perceptions = rd.array(root, "perceptions", "");
  if (perceptions.size() != 1) {
    rd.fail(fmt::format("'perceptions' holds {} perceptions; a tactile movie is one",
                        perceptions.size()));
  }
  const json& p = perceptions[0];
  const std::string pp = "perceptions[0]";
  rd.one_of(p, "perception_modality", pp, {"Position"},
            "a tactile movie holds lateral displacements (Position)");
  const std::int64_t exponent = p.contains("perception_unit_exponent")
                                    ? rd.integer_in(p, "perception_unit_exponent", pp, -128, 127)
                                    : 0;
  const std::string perception_description = rd.string(p, "description", pp);
  const json& channels = rd.array(p, "channels", pp);
  const std::int64_t max_channels = level == 1 ? kHjifLevel1MaxChannels : kHjifLevel2MaxChannels;
  if (channels.empty() || static_cast<std::int64_t>(channels.size()) > max_channels) {
    rd.fail(fmt::format("{}.channels holds {} channels, out of range: level {} allows 1 to {}", pp,
                        channels.size(), level, max_channels));
  }

  std::vector<ChannelRead> read(channels.size());
  std::array<std::int64_t, 3> resolution{};
  for (std::size_t i = 0; i < channels.size(); ++i) {
    const json& c = channels[i];
    ChannelRead& ch = read[i];
    ch.path = fmt::format("{}.channels[{}]", pp, i);
    const double gain = rd.number(c, "gain", ch.path);
    ch.scale_um = gain * std::pow(10.0, static_cast<double>(exponent + 6));
    if (!std::isfinite(ch.scale_um) || std::abs(ch.scale_um) > 1e6) {
      rd.fail(fmt::format("{}.gain {} x 10^{} m is out of range: amplitude 1 must be at most 1 m",
                          ch.path, gain, exponent));
    }
    const auto res =
        rd.vector(rd.need(c, "actuator_resolution", ch.path), ch.path + ".actuator_resolution");
    if (res[0] < 1 || res[1] < 1 || res[2] > 1 || res[2] < 0) {
      rd.fail(
          fmt::format("{}.actuator_resolution ({}, {}, {}) is not a grid of contactors: X and Y "
                      "must be >= 1, Z 0 or 1",
                      ch.path, res[0], res[1], res[2]));
    }
    if (i == 0) resolution = res;
    if (res != resolution) {
      rd.fail(fmt::format(
          "{}.actuator_resolution ({}, {}, {}) differs from channel 0's ({}, {}, {})", ch.path,
          res[0], res[1], res[2], resolution[0], resolution[1], resolution[2]));
    }
    const json& targets = rd.array(c, "actuator_target", ch.path);
    if (targets.size() != 1) {
      rd.fail(fmt::format("{}.actuator_target holds {} targets; a contactor is one", ch.path,
                          targets.size()));
    }
    const auto t = rd.vector(targets[0], ch.path + ".actuator_target[0]");
    if (t[0] < 0 || t[0] >= res[0] || t[1] < 0 || t[1] >= res[1] || t[2] != 0) {
      rd.fail(
          fmt::format("{}.actuator_target ({}, {}, {}) is outside the actuator_resolution "
                      "({}, {}, {})",
                      ch.path, t[0], t[1], t[2], res[0], res[1], res[2]));
    }
    ch.col = t[0];
    ch.row = t[1];
    ch.rate = rd.integer_in(c, "frequency_sampling", ch.path, 1,
                            static_cast<std::int64_t>(kMaxMovieRateHz));
    if (c.contains("sample_count")) {
      ch.sample_count =
          rd.integer_in(c, "sample_count", ch.path, 0, std::numeric_limits<std::int32_t>::max());
    }
    if (c.contains("direction")) {
      const auto d = rd.vector(c.at("direction"), ch.path + ".direction");
      if (d[0] == kVectorRange && d[1] == 0 && d[2] == 0) {
        ch.axis = DeflectionAxis::x;
      } else if (d[0] == 0 && d[1] == kVectorRange && d[2] == 0) {
        ch.axis = DeflectionAxis::y;
      } else {
        rd.fail(
            fmt::format("{}.direction ({}, {}, {}) is not the x (127, 0, 0) or y (0, 127, 0) "
                        "axis: contactors move in the plane of the skin",
                        ch.path, d[0], d[1], d[2]));
      }
    }
    ch.description = rd.string(c, "description", ch.path);
    ch.bands = &rd.array(c, "bands", ch.path);
    if (ch.rate != read[0].rate || ch.sample_count != read[0].sample_count ||
        ch.axis != read[0].axis) {
      rd.fail(
          fmt::format("{}: frequency_sampling, sample_count and direction must be those of "
                      "channel 0",
                      ch.path));
    }
  }
  const std::int64_t cols = resolution[0], rows = resolution[1];
  if (static_cast<std::int64_t>(channels.size()) != rows * cols) {
    rd.fail(
        fmt::format("{}.channels holds {} channels but the actuator_resolution {} x {} has {} "
                    "contactors",
                    pp, channels.size(), cols, rows, rows * cols));
  }
  std::vector<std::int64_t> channel_of(static_cast<std::size_t>(rows * cols), -1);
  for (std::size_t i = 0; i < read.size(); ++i) {
    auto& slot = channel_of[static_cast<std::size_t>(read[i].row * cols + read[i].col)];
    if (slot >= 0) {
      rd.fail(fmt::format("{}.actuator_target ({}, {}, 0) is also the target of channel {}",
                          read[i].path, read[i].col, read[i].row, slot));
    }
    slot = static_cast<std::int64_t>(i);
  }

  TactileMovie movie;
  const std::string layout_field = pp + ".description";
  std::optional<Layout> from_file;
  if (perception_description.rfind(kLayoutPrefix, 0) == 0) {
    from_file = parse_layout_json(perception_description.substr(std::string(kLayoutPrefix).size()),
                                  fmt::format("{}: {}", where, layout_field));
  }
  if (options.layout) {
    movie.layout = *options.layout;
  } else if (from_file) {
    movie.layout = *from_file;
  } else {
    rd.fail(
        fmt::format("{} holds no tactile-movie layout; give the display's layout", layout_field));
  }
  if (movie.layout.rows != rows || movie.layout.cols != cols) {
    rd.fail(
        fmt::format("the layout '{}' is {} x {} (rows x cols) but the channels' "
                    "actuator_resolution is {} x {}",
                    movie.layout.name, movie.layout.rows, movie.layout.cols, rows, cols));
  }
  if (read[0].axis && *read[0].axis != movie.layout.axis) {
    rd.fail(fmt::format("the layout '{}' deflects along {} but the channels' direction is {}",
                        movie.layout.name, to_string(movie.layout.axis), to_string(*read[0].axis)));
  }
  const std::int64_t rate = read[0].rate;
  std::int64_t frames = 0;
  if (read[0].sample_count) {
    frames = *read[0].sample_count;
  } else {
    rd.fail(fmt::format("{}.channels[0]: missing field 'sample_count'", pp));
  }
  checks::value_count({static_cast<std::uint64_t>(frames), static_cast<std::uint64_t>(rows * cols)},
                      sizeof(double) + sizeof(float), where, "sample_count x channels");
  movie.rate_hz = static_cast<double>(rate);
  movie.frame_count = static_cast<std::int32_t>(frames);
  std::vector<double> sum(static_cast<std::size_t>(frames * rows * cols), 0.0);
  for (std::size_t i = 0; i < read.size(); ++i) {
    sample_channel(rd, read[i], timescale, rate, frames, rows * cols,
                   read[i].row * cols + read[i].col, sum);
  }
  movie.deflection_um.assign(sum.begin(), sum.end());

  // Provenance: the pieces after a tab in the channel descriptions, in channel order.
  std::string provenance;
  for (const auto& ch : read) {
    const auto tab = ch.description.find('\t');
    if (tab != std::string::npos) provenance += ch.description.substr(tab + 1);
  }
  if (!provenance.empty()) {
    const JsonOrigin at{fmt::format("{}: provenance in the channel descriptions", where)};
    const json j = parse_json(at, provenance);
    movie.provenance = read_provenance_json(at, j, "provenance");
  }
  try {
    validate_movie(movie);
  } catch (const std::invalid_argument& e) {
    throw FormatError(fmt::format("{}: {}", where, e.what()));
  }
  return movie;
}

TactileMovie read_hjif(const std::filesystem::path& path, const HjifImportOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw FormatError(fmt::format("{}: cannot open the HJIF file", path.string()));
  std::ostringstream text;
  text << in.rdbuf();
  if (!in.good() && !in.eof()) {
    throw FormatError(fmt::format("{}: cannot read the HJIF file", path.string()));
  }
  return parse_hjif(text.str(), path.string(), options);
}

}  // namespace tactile::movie
