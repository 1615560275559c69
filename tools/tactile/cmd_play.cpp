// `tactile play`, `tactile view`, `tactile devices`, `tactile info`: the display side.

#include <fmt/format.h>

#include <filesystem>
#include <memory>

#include "command.hpp"
#include "latero_cli.hpp"
#include "number_checks.hpp"
#include "own_options.hpp"
#include "request_options.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/display/play_anywhere.hpp"
#include "tactile/display/play_request.hpp"
#include "tactile/display/preview.hpp"
#include "tactile/display/summary.hpp"
#include "tactile/display/usb_transports.hpp"
#include "tactile/display/viewer.hpp"
#include "tactile/mapping/strain_panel.hpp"
#include "tactile/movie/movie_io.hpp"

namespace tactile::cli {
namespace fs = std::filesystem;

namespace {

// The movie to play or view; a strain movie given instead is named as such, with the command
// that makes a tactile movie of it (the reader alone would only say its format is another).
movie::TactileMovie read_movie_to_play(const fs::path& path) {
  try {
    return movie::read_tactile_movie(path);
  } catch (const FormatError&) {
    bool strain = false;
    try {
      const H5::H5File file = h5::open_for_reading(path);
      strain = h5::has_attr(file, "format") &&
               h5::read_attr_string(file, "format", path.string()) == capture::kStrainMovieFormat;
    } catch (const std::exception&) {
      // Not readable as HDF5 at all: the reader's own message says so.
    }
    if (!strain) throw;
    throw FormatError(fmt::format(
        "{}: a strain movie, not a tactile movie: make one of it with `tactile map {} --out "
        "MOVIE.h5`, then play that",
        path.string(), path.string()));
  }
}

}  // namespace

void add_play(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  const auto [request, sub] = add_request_command<display::PlayRequest>(
      app, "play",
      "Play a tactile movie: on an attached display; with none, in the emulator window; with no\n"
      "screen either, headless into the emulated device (firmware limits applied), writing a\n"
      "preview image strip and printing a summary.",
      display::play_options());
  sub->callback([request, &action] {
    action = WatchingStopSignals{[request] {
      // Before reading: fail fast on options that do not go together.
      display::ResolvedPlay choice = display::resolve(*request, OptionSpelling::cli);
      // Checked even if the movie ends up on a device: whether it plays headless (the one case
      // that writes the preview) is decided only while playing.
      if (request->preview) {
        refuse_output_over_input({output_file_ending("--preview", *request->preview, ".png")},
                                 {{"MOVIE_H5", request->movie}});
      }
      // Before any device is opened: the threads USB libraries and the window start inherit
      // the blocked signals, so Ctrl-C reaches the player and not the default action. Before
      // reading too: a long movie takes a second to read, and a Ctrl-C then ended the process
      // silently, leaving the user to guess whether anything had reached the display.
      StopSignals stop;
      choice.stop_fd = stop.fd();
      const movie::TactileMovie movie = read_movie_to_play(request->movie);
      if (const int signal = stop.received(); signal != 0) {
        fmt::print("play: stopped by {} while reading {}: nothing was sent to any display\n",
                   stop_signal_name(signal), request->movie.string());
        return exit_code_for_signal(signal);
      }
      // A stopped playback returns too, after its summary; the signal decides the exit code.
      display::play_anywhere(
          movie, choice, [](const std::string& text) { fmt::print("{}", text); },
          display::with_window(display::usb_play_backends()));
      if (const int signal = stop.received(); signal != 0) {
        fmt::print("play: stopped by {}\n", stop_signal_name(signal));
        return exit_code_for_signal(signal);
      }
      return 0;
    }};
  });
}

void add_view(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  struct Options {
    fs::path movie;
    fs::path strain;
    bool no_strain = false;
    fs::path screenshot;
    display::ViewerOptions viewer;
  };
  const auto [opt, sub] = add_own_command<Options>(
      app, "view",
      "Open the emulator window: contactors drawn at their rest positions, displaced by their\n"
      "deflection (magnified) and coloured by the stretch between neighbours, as the emulated\n"
      "device outputs them, with the source strain movie's edges beside them (black compressed\n"
      "... white stretched) when the movie's provenance names one that exists, or --strain.\n"
      "Keys: space play/pause, arrows step, up/down speed, L loop, Esc quit; drag the bottom\n"
      "bar to seek.");
  add_input_file(*sub, "MOVIE_H5", opt->movie, "Tactile movie (HDF5)");
  CLI::Option* strain =
      sub->add_option("--strain", opt->strain, "Strain movie to show beside the array (HDF5)")
          ->check(CLI::ExistingFile);
  sub->add_flag("--no-strain", opt->no_strain, "Show no strain field, even when one is found")
      ->excludes(strain);
  sub->add_flag("--loop", opt->viewer.loop, "Loop the movie");
  sub->add_option("--at", opt->viewer.start_s, "Start at this movie time (s)")
      ->check(non_negative());
  sub->add_option("--screenshot", opt->screenshot,
                  "Draw the window once (at --at), write it to this PNG and quit");
  sub->callback([opt, &action] {
    action = [opt] {
      const movie::TactileMovie movie = read_movie_to_play(opt->movie);
      // Only the movie knows its length; the viewer would clamp a later time to the end.
      if (opt->viewer.start_s > movie.duration_s()) {
        fmt::print(stderr,
                   "tactile view: error: --at: {:g} is out of range: {} lasts {:g} s (0 to {:g})\n",
                   opt->viewer.start_s, opt->movie.string(), movie.duration_s(),
                   movie.duration_s());
        return 2;
      }
      if (!opt->screenshot.empty()) {
        opt->viewer.visible = false;
        opt->viewer.start_paused = true;
        opt->viewer.fixed_step = true;
        opt->viewer.exit_after_frames = 1;
      }
      std::vector<NamedPath> inputs = {{"MOVIE_H5", opt->movie}};
      if (!opt->strain.empty()) inputs.push_back({"--strain", opt->strain});
      const auto source = opt->no_strain
                              ? std::nullopt
                              : mapping::find_source_strain(movie, opt->movie, opt->strain);
      if (source && opt->strain.empty()) inputs.push_back({"the movie's source", *source});
      if (!opt->screenshot.empty()) {
        refuse_output_over_input({output_file_ending("--screenshot", opt->screenshot, ".png")},
                                 inputs);
      }
      if (source) {
        try {
          opt->viewer.field = mapping::strain_side_field(capture::read_strain_movie(*source),
                                                         "strain: " + source->filename().string());
        } catch (const std::invalid_argument& e) {
          // Asked for: an error. Found through the provenance: show the movie without it.
          if (!opt->strain.empty()) throw std::invalid_argument(source->string() + ": " + e.what());
          fmt::print(stderr, "view: not showing the source strain movie {}: {}\n", source->string(),
                     e.what());
        }
      }
      if (!display::screen_available()) {
        throw std::runtime_error(
            "no screen (DISPLAY is unset or cannot be opened); use `tactile play --headless` for "
            "a preview image instead");
      }
      const display::ViewerResult r = display::run_viewer(movie, opt->viewer);
      if (!opt->screenshot.empty()) {
        display::write_png(opt->screenshot, r.last_image);
        fmt::print("view: frame {} of {} ({}) drawn to {}{}\n", r.last_movie_frame + 1,
                   r.shown_frame_count,
                   display::frame_count_text(r.shown_frame_count - r.device_report.ramp_frames,
                                             r.device_report.ramp_frames),
                   opt->screenshot.string(),
                   opt->viewer.field ? " (with the source strain field)" : "");
      }
      return 0;
    };
  });
}

void add_devices(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  auto latero = std::make_shared<std::string>();
  CLI::App* sub = app.add_subcommand(
      "devices", "List attached tactile displays (USB vendor/product 1209:0001) and their state.");
  sub->add_option("--latero", *latero,
                  "Probe the Latero at HOST[:PORT] instead: FPGA versions, high voltage, buttons")
      ->check(latero_address_check());
  sub->callback([latero, &action] {
    action = [latero] {
      if (!latero->empty()) return print_latero_device(*latero);
      const auto devices = display::list_usb_devices();
      if (devices.empty()) {
        fmt::print("devices: none attached (looking for USB {:04x}:{:04x})\n",
                   display::kUsbVendorId, display::kUsbProductId);
        return 0;
      }
      for (const auto& d : devices) {
        fmt::print("{:<7} {:04x}:{:04x} {:<12} {} {} {}{}\n", to_string(d.backend), d.vendor_id,
                   d.product_id, d.path, d.manufacturer, d.product, d.serial,
                   d.accessible ? "" : "  (no permission: install the udev rules)");
      }
      return 0;
    };
  });
}

void add_info(CLI::App& app, Action& action, const std::string& /*command_line*/) {
  auto file = std::make_shared<fs::path>();
  CLI::App* sub = app.add_subcommand("info", "Describe a strain movie or tactile movie file.");
  add_input_file(*sub, "FILE_H5", *file, "Strain or tactile movie (HDF5)");
  sub->callback([file, &action] {
    action = [file] {
      const std::string kind = [&] {
        H5::H5File f = h5::open_for_reading(*file);
        return h5::read_attr_string(f, "format", file->string());
      }();
      if (kind == "tactile-strain-movie") {
        const capture::StrainMovie m = capture::read_strain_movie(*file);
        std::size_t edges = 0;
        for (const auto& f : m.frames) edges += f.edges.size();
        fmt::print(
            "{}: strain movie, {} camera frames at {:g} Hz, span {}, {} strain frames, "
            "{:.0f} edges per frame, field {:.2f} x {:.2f} mm, calibration: {}, source: {}\n",
            file->string(), m.camera_frame_count, m.frame_rate_hz, m.span_frames, m.frames.size(),
            m.frames.empty() ? 0.0 : static_cast<double>(edges) / m.frames.size(), m.field_width_mm,
            m.field_height_mm, m.calibration.method, origin_of(m.provenance));
        return 0;
      }
      const movie::TactileMovie movie = movie::read_tactile_movie(*file);
      fmt::print("{}: tactile movie, {}\n", file->string(), movie.provenance.method);
      fmt::print("{}", display::format_summary(display::summarize(movie)));
      return 0;
    };
  });
}

}  // namespace tactile::cli
