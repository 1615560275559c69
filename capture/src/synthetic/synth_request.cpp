// The synth request's option table, its rules and its run; see synth_request.hpp.

#include "tactile/capture/synth_request.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <set>
#include <stdexcept>
#include <system_error>

#include "tactile/capture/image.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/output_paths.hpp"

namespace tactile::capture {

namespace {

namespace rows = option_rows;

// `row` showing `value` as its default: an unset option takes the spec's member initialiser,
// which the help reads from there.
template <typename R, typename T>
OptionRow<R> shows(OptionRow<R> row, const T& value) {
  row.shown = [text = rows::shown_value(value)](const R&) { return text; };
  return row;
}

// The options that describe a scene and not a print (a print takes frames, noise and seed too).
bool scene_only(std::string_view name) {
  return name != "frames" && name != "noise" && name != "seed";
}

// pores_NN.txt beside image_NN.*, the PolyU HRF layout, when it exists.
std::optional<std::filesystem::path> marks_beside(const std::filesystem::path& image) {
  const std::string stem = image.stem().string();
  if (stem.rfind("image_", 0) != 0) return std::nullopt;
  const auto marks = image.parent_path() / ("pores_" + stem.substr(6) + ".txt");
  std::error_code ec;
  if (std::filesystem::is_regular_file(marks, ec)) return marks;
  return std::nullopt;
}

const std::vector<OptionRow<WarpRequest>>& warp_options() {
  using R = WarpRequest;
  const PrintWarpSpec d;
  static const std::vector<OptionRow<R>> table = {
      shows(rows::number<R>("px_per_mm", &R::px_per_mm, 5, 500, "px/mm",
                            "With a print: the print's scale"),
            d.px_per_mm),
      shows(rows::choice<R>("warp", &R::warp, kWarpPatternNames,
                            "With a print: strain pattern: rigid (slide and rotation only),\n"
                            "stretch (along x), compress (along y), bump (radial), wave\n"
                            "(travelling along x), pulse (a bump crossing along x), ridge\n"
                            "(compression ahead of a sliding edge), stick-slip (rim loads and\n"
                            "slips around a sticking centre), kernels (random smooth field),\n"
                            "full-slip (the skin slides through the view at travel-speed,\n"
                            "strained by a static field; the print mirrored without end)"),
            to_string(d.pattern)),
      shows(rows::number<R>("strain_pct", &R::strain_pct, -20, 20, "%",
                            "With a print: peak strain of the pattern"),
            100 * d.strain),
      shows(rows::number<R>("warp_width", &R::warp_width_mm, 0.5, 50, "mm",
                            "With a print: width (FWHM) of the pattern, or the wavelength"),
            d.width_mm),
      shows(rows::number<R>("slide_x", &R::slide_x_mm, -5, 5, "mm",
                            "With a print: slide along x over the sequence"),
            d.slide_x_mm),
      shows(rows::number<R>("slide_y", &R::slide_y_mm, -5, 5, "mm",
                            "With a print: slide along y over the sequence"),
            d.slide_y_mm),
      shows(rows::number<R>("turn", &R::turn_deg, -30, 30, "degrees",
                            "With a print: rotation over the sequence"),
            d.rotation_deg),
      shows(rows::number<R>("blur", &R::blur_px, 0, 10, "px", "With a print: camera blur (sigma)"),
            d.blur_sigma_px),
      shows(rows::number<R>("drift", &R::drift, -0.5, 0.5, "",
                            "With a print: change of exposure over the sequence (0.06 = 6 %)"),
            d.brightness_drift),
      shows(rows::number<R>("travel_speed", &R::travel_speed_mm_per_s, 0, 1000, "mm/s",
                            "With a print: speed at which the pattern crosses the field (0: "
                            "wave,\npulse and ridge take the whole sequence; full-slip: the "
                            "skin's speed)"),
            d.travel_speed_mm_per_s),
      shows(rows::number<R>("rate_hz", &R::rate_hz, 1, 100000, "Hz", "With a print: camera rate"),
            d.frame_rate_hz),
      shows(rows::number<R>("exposure_ms", &R::exposure_ms, 0, 1000, "ms",
                            "With a print: shutter time (motion blur; at most one frame)"),
            1000 * d.exposure_s),
      shows(rows::number<R>("supersample", &R::supersample, 1, 8, "",
                            "With a print: samples per pixel side over the pixel's area"),
            d.supersample),
      shows(rows::number<R>("contact_loss", &R::contact_loss, 0, 1, "",
                            "With a print: a region lifts off mid-sequence and lands again,\n"
                            "0 (none) to 1 (fully lifted)"),
            d.contact_loss),
      shows(rows::number<R>("patch_speed", &R::patch_speed_mm_per_s, -1000, 1000, "mm/s",
                            "With a print: the skin touches the glass in a patch smaller than\n"
                            "the view (outside it: out of contact), moving along x at this speed"),
            d.patch_speed_mm_per_s),
      shows(rows::number<R>("patch_breathing", &R::patch_breathing, 0, 0.5, "",
                            "With a print: the contact patch grows and shrinks by this fraction\n"
                            "of its size, one cycle over the sequence"),
            d.patch_breathing),
      rows::number<R>("slide_speed", &R::slide_speed_mm_per_s, -1000, 1000, "mm/s",
                      "With a print: slide along x as a speed (instead of slide-x)"),
      rows::number<R>("turn_rate", &R::turn_rate_deg_per_s, -10000, 10000, "degrees/s",
                      "With a print: rotation as a rate (instead of turn)"),
  };
  return table;
}

}  // namespace

const std::vector<OptionRow<SceneRequest>>& scene_options() {
  using R = SceneRequest;
  const SceneSpec d;
  static const std::vector<OptionRow<R>> table = {
      shows(rows::choice<R>("scene", &R::scene, kSceneNames,
                            "Scene: bump, hole, flat-slide (slide over a feature or flat glass), "
                            "flat-rotate (press and twist), flat-stick-slip (push back and forth "
                            "with a sticking centre)"),
            to_string(d.scene)),
      shows(rows::number<R>("frames", &R::frames, 2, 100000, "", "Number of camera frames"),
            d.frame_count),
      shows(rows::number<R>("speed", &R::speed_mm_per_s, 0, 100, "mm/s", "Sliding speed"),
            d.speed_mm_per_s),
      shows(rows::number<R>("height", &R::height_mm, 0, 5, "mm", "Bump height / hole depth"),
            d.feature_height_mm),
      shows(rows::number<R>("width", &R::width_mm, 0.1, 50, "mm", "Bump / hole width (FWHM)"),
            d.feature_width_mm),
      shows(rows::number<R>("contact_semi_x", &R::contact_semi_x_mm, 0.5, 20, "mm",
                            "Half-width of the fingertip contact patch along the slide"),
            d.contact_semi_x_mm),
      shows(rows::number<R>("rotation", &R::rotation_deg, -45, 45, "degrees",
                            "flat-rotate: twist at the last frame"),
            d.rotation_deg),
      shows(rows::number<R>("lateral_amplitude", &R::lateral_amplitude_mm, -3, 3, "mm",
                            "flat-stick-slip: peak rim displacement"),
            d.lateral_amplitude_mm),
      shows(rows::number<R>("stick_ratio", &R::stick_ratio, 0, 0.9, "",
                            "flat-rotate, flat-stick-slip: stick radius / contact radius"),
            d.stick_ratio),
      shows(rows::number<R>("noise", &R::noise, 0, 128, "grey levels", "Camera noise (sigma)"),
            d.noise_sigma),
      shows(rows::seed<R>("seed", &R::seed, "Random seed (same seed, same images)"), d.seed),
  };
  return table;
}

SceneSpec scene_spec(const SceneRequest& r) {
  SceneSpec s;
  s.scene = r.scene.value_or(s.scene);
  s.frame_count = r.frames.value_or(s.frame_count);
  s.speed_mm_per_s = r.speed_mm_per_s.value_or(s.speed_mm_per_s);
  s.feature_height_mm = r.height_mm.value_or(s.feature_height_mm);
  s.feature_width_mm = r.width_mm.value_or(s.feature_width_mm);
  s.contact_semi_x_mm = r.contact_semi_x_mm.value_or(s.contact_semi_x_mm);
  s.rotation_deg = r.rotation_deg.value_or(s.rotation_deg);
  s.lateral_amplitude_mm = r.lateral_amplitude_mm.value_or(s.lateral_amplitude_mm);
  s.stick_ratio = r.stick_ratio.value_or(s.stick_ratio);
  s.noise_sigma = r.noise.value_or(s.noise_sigma);
  s.seed = r.seed.value_or(s.seed);
  return s;
}

const std::vector<OptionRow<SynthRequest>>& synth_options() {
  using R = SynthRequest;
  static const std::vector<OptionRow<R>> table = [] {
    std::vector<OptionRow<R>> t = {rows::positional_path<R>(
        "out_dir", &R::out_dir, "OUT_DIR", "Folder to write into (created if missing)")};
    t.back().must_exist = false;
    const auto scene = [](auto& r) -> auto& {
      return r.scene;
    };
    for (const auto& row : scene_options()) t.push_back(rows::nested<R>(row, scene));
    // Two kinds of sequence, two default lengths: said in words.
    OptionRow<R>& frames =
        *std::find_if(t.begin(), t.end(), [](const auto& row) { return row.name == "frames"; });
    frames.help =
        fmt::format("Number of camera frames (default {} for a scene, {} with --from-print)",
                    SceneSpec{}.frame_count, PrintWarpSpec{}.frame_count);
    frames.shown = [](const R&) { return std::string(); };
    t.push_back(rows::existing_path<R>(
        "from_print", &R::from_print,
        "A real fingerprint image (ridges dark) to warp instead of a synthetic scene"));
    t.push_back(rows::existing_path<R>(
        "marks", &R::marks,
        "With a print: hand-marked pores ('row col' per line, 1-based) to carry\nthrough the warp "
        "as landmarks.csv; default pores_NN.txt beside image_NN.*,\nwhen there is one"));
    const auto print = [](auto& r) -> auto& {
      return r.print;
    };
    for (const auto& row : warp_options()) t.push_back(rows::nested<R>(row, print));
    return t;
  }();
  return table;
}

ResolvedSynth resolve(const SynthRequest& r, OptionSpelling spelling) {
  check_options(r, synth_options(), spelling);
  const auto label = [spelling](std::string_view name) { return option_label(name, spelling); };
  ResolvedSynth out;
  out.out_dir = r.out_dir;
  out.spelling = spelling;
  if (!r.from_print) {
    if (r.marks)
      throw RequestError(fmt::format("{}: needs {}", label("marks"), label("from_print")));
    for (const auto& row : warp_options()) {
      if (!std::holds_alternative<std::monostate>(row.get(r.print))) {
        throw RequestError(fmt::format("{}: needs {} (it describes a print's warp)",
                                       label(row.name), label("from_print")));
      }
    }
    out.scene = scene_spec(r.scene);
    return out;
  }
  for (const auto& row : scene_options()) {
    if (scene_only(row.name) && !std::holds_alternative<std::monostate>(row.get(r.scene))) {
      throw RequestError(fmt::format("{}: describes a synthetic scene, not {}", label(row.name),
                                     label("from_print")));
    }
  }
  const WarpRequest& p = r.print;
  const auto instead = [&](const auto& speed, const auto& distance, std::string_view speed_name,
                           std::string_view distance_name) {
    if (speed && distance) {
      throw RequestError(fmt::format("{}: not with {}: give a distance or a speed",
                                     label(speed_name), label(distance_name)));
    }
  };
  instead(p.slide_speed_mm_per_s, p.slide_x_mm, "slide_speed", "slide_x");
  instead(p.turn_rate_deg_per_s, p.turn_deg, "turn_rate", "turn");
  PrintWarpSpec w;
  w.px_per_mm = p.px_per_mm.value_or(w.px_per_mm);
  w.pattern = p.warp.value_or(w.pattern);
  if (p.strain_pct) w.strain = *p.strain_pct / 100;
  w.width_mm = p.warp_width_mm.value_or(w.width_mm);
  w.slide_x_mm = p.slide_x_mm.value_or(w.slide_x_mm);
  w.slide_y_mm = p.slide_y_mm.value_or(w.slide_y_mm);
  w.rotation_deg = p.turn_deg.value_or(w.rotation_deg);
  w.blur_sigma_px = p.blur_px.value_or(w.blur_sigma_px);
  w.brightness_drift = p.drift.value_or(w.brightness_drift);
  w.travel_speed_mm_per_s = p.travel_speed_mm_per_s.value_or(w.travel_speed_mm_per_s);
  w.frame_rate_hz = p.rate_hz.value_or(w.frame_rate_hz);
  if (p.exposure_ms) w.exposure_s = *p.exposure_ms / 1000;
  w.supersample = p.supersample.value_or(w.supersample);
  w.contact_loss = p.contact_loss.value_or(w.contact_loss);
  w.patch_speed_mm_per_s = p.patch_speed_mm_per_s.value_or(w.patch_speed_mm_per_s);
  w.patch_breathing = p.patch_breathing.value_or(w.patch_breathing);
  w.frame_count = r.scene.frames.value_or(w.frame_count);
  w.noise_sigma = r.scene.noise.value_or(w.noise_sigma);
  w.seed = r.scene.seed.value_or(w.seed);
  if (w.pattern == WarpPattern::full_slip && !(w.travel_speed_mm_per_s > 0)) {
    throw RequestError(
        fmt::format("{} full-slip: needs {} above 0 (the skin's speed through the view, mm/s)",
                    label("warp"), label("travel_speed")));
  }
  const double duration_s = sequence_duration_s(w);
  if (p.slide_speed_mm_per_s) w.slide_x_mm = *p.slide_speed_mm_per_s * duration_s;
  if (p.turn_rate_deg_per_s) w.rotation_deg = *p.turn_rate_deg_per_s * duration_s;
  out.warp = w;
  out.print = *r.from_print;
  out.marks = r.marks ? r.marks : marks_beside(*r.from_print);
  return out;
}

SynthSummary run_synth(const ResolvedSynth& synth, const std::string& command_line,
                       const std::function<void(int done, int total)>& progress) {
  const auto label = [&](std::string_view name) { return option_label(name, synth.spelling); };
  const std::string out_label =
      synth.spelling == OptionSpelling::cli ? std::string("OUT_DIR") : std::string("out_dir");
  const auto t0 = std::chrono::steady_clock::now();
  const auto seconds = [&] {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  };
  SynthSummary s;
  if (synth.scene) {
    const SceneSpec& spec = *synth.scene;
    validate_scene(spec);
    refuse_output_over_input({output_folder(out_label, synth.out_dir, {})}, {});
    refuse_stale_frames(out_label, synth.out_dir, spec.frame_count);
    const SyntheticSequence seq = render_sequence(spec, progress);
    std::filesystem::create_directories(synth.out_dir);
    write_sequence(synth.out_dir, seq, command_line);
    s.frames = static_cast<int>(seq.frames.size());
    s.width_px = spec.width_px;
    s.height_px = spec.height_px;
    s.landmark_positions = seq.landmarks.size();
    s.seconds = seconds();
    s.text = fmt::format(
        "synth: {} frames of {} x {} px ({} scene at {:g} mm/s, {:g} Hz) and {} landmark "
        "positions -> {} ({:.1f} s)",
        s.frames, s.width_px, s.height_px, to_string(spec.scene), spec.speed_mm_per_s,
        spec.frame_rate_hz, s.landmark_positions, synth.out_dir.string(), s.seconds);
    return s;
  }
  PrintWarpSpec warp = *synth.warp;
  std::vector<std::filesystem::path> writes = {"landmarks.csv", "scene.json"};
  for (int f = 0; f < warp.frame_count; ++f) {
    writes.push_back(frame_file_name(static_cast<std::size_t>(f)));
  }
  refuse_output_over_input(
      {output_folder(out_label, synth.out_dir, writes)},
      {{label("from_print"), synth.print}, {label("marks"), synth.marks.value_or(synth.print)}});
  refuse_stale_frames(out_label, synth.out_dir, warp.frame_count);
  const GrayImage print = read_image(synth.print);
  warp.source = synth.print.filename().string();
  warp.width_px = print.width_px;
  warp.height_px = print.height_px;
  std::vector<std::array<double, 2>> pores;
  if (synth.marks) {
    // The file's own complaint, led by the option that named it (or would have: marks found
    // beside the print are the option's default).
    try {
      pores = read_pore_marks(*synth.marks, print.width_px, print.height_px);
    } catch (const FormatError& e) {
      throw FormatError(fmt::format("{}: {}", label("marks"), e.what()));
    }
  }
  // The warp's own checks know the print's size, not its file.
  const PrintSequence seq = [&] {
    try {
      return render_print_sequence(warp, print, pores);
    } catch (const std::invalid_argument& e) {
      throw std::invalid_argument(
          fmt::format("{} {}: {}", label("from_print"), synth.print.string(), e.what()));
    }
  }();
  write_print_sequence(synth.out_dir, seq, synth.print, command_line);
  s.frames = static_cast<int>(seq.frames.size());
  s.width_px = warp.width_px;
  s.height_px = warp.height_px;
  s.marked_pores = pores.size();
  s.seconds = seconds();
  s.text = fmt::format(
      "synth: {} frames of {} x {} px from {} ({} warp, {:.1f} % peak strain, {}{:g} Hz, {} "
      "marked pores{}) -> {} ({:.1f} s)",
      s.frames, s.width_px, s.height_px, synth.print.string(), to_string(warp.pattern),
      100 * warp.strain,
      warp.travel_speed_mm_per_s > 0 ? fmt::format("{:g} mm/s, ", warp.travel_speed_mm_per_s)
                                     : std::string(),
      warp.frame_rate_hz, s.marked_pores,
      synth.marks ? " from " + synth.marks->filename().string() : std::string(),
      synth.out_dir.string(), s.seconds);
  return s;
}

void refuse_stale_frames(const std::string& option, const std::filesystem::path& dir,
                         int frame_count) {
  std::error_code ec;
  if (!std::filesystem::is_directory(dir, ec)) return;
  std::set<std::string> written;
  for (int f = 0; f < frame_count; ++f) {
    written.insert(frame_file_name(static_cast<std::size_t>(f)));
  }
  std::vector<std::string> stale;
  try {
    for (const auto& p : list_frames(dir)) {
      if (!written.contains(p.filename().string())) stale.push_back(p.filename().string());
    }
  } catch (const FormatError&) {
    return;  // no image at all
  }
  if (stale.empty()) return;
  throw OutputPathError(fmt::format(
      "{} {} already holds {} image file(s) this run of {} frames would not replace ({}{}): "
      "`tactile capture` would read them as part of the sequence; remove them or choose another "
      "folder",
      option, dir.string(), stale.size(), frame_count, stale.front(),
      stale.size() > 1 ? fmt::format(" .. {}", stale.back()) : std::string()));
}

}  // namespace tactile::capture
