// The export request's option table and its run; see export_request.hpp.

#include "tactile/movie/export_request.hpp"

#include <fmt/format.h>

#include "tactile/common/atomic_write.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/movie/wav.hpp"

namespace tactile::movie {

namespace rows = option_rows;

const std::vector<OptionRow<ExportRequest>>& export_options() {
  using R = ExportRequest;
  static const std::vector<OptionRow<R>> table = {
      rows::positional_path<R>("movie", &R::movie, "MOVIE_H5", "Tactile movie (HDF5)"),
      rows::path<R>("hjif", &R::hjif,
                    "MPEG-I Haptics interchange file to write (.hjif, one Position channel per "
                    "contactor)"),
      rows::path<R>("wav", &R::wav,
                    "WAV file to write (.wav, float32, one channel per contactor, 1.0 = full "
                    "scale)"),
      rows::number<R>("ticks_per_sample", &R::ticks_per_sample, 1,
                      static_cast<double>(kHjifMaxTimescale), "",
                      "HJIF ticks per movie frame (timescale = rate x ticks; at most the "
                      "profile's 48000 ticks a second)"),
  };
  return table;
}

void check_request(const ExportRequest& request, OptionSpelling spelling) {
  // The movie is the caller's (a checked input or a Movie).
  check_named_options(request, export_options(), spelling);
  if (!request.hjif && !request.wav) {
    throw RequestError(fmt::format("give {} OUT.hjif, {} OUT.wav or both",
                                   option_label("hjif", spelling), option_label("wav", spelling)));
  }
}

void check_outputs(const ExportRequest& request, OptionSpelling spelling) {
  check_request(request, spelling);
  const auto label = [spelling](std::string_view name) { return option_label(name, spelling); };
  std::vector<Output> outputs;
  // Other tools pick the reader by the name: a WAV named x.hjif is a file none can open.
  if (request.hjif) outputs.push_back(output_file_ending(label("hjif"), *request.hjif, ".hjif"));
  if (request.wav) outputs.push_back(output_file_ending(label("wav"), *request.wav, ".wav"));
  std::vector<NamedPath> inputs;
  if (!request.movie.empty()) {
    inputs.push_back({spelling == OptionSpelling::cli ? "MOVIE_H5" : "movie", request.movie});
  }
  refuse_output_over_input(outputs, inputs);
}

ExportSummary run_export(const ExportRequest& request, const TactileMovie& movie,
                         OptionSpelling spelling) {
  check_outputs(request, spelling);
  ExportSummary s;
  CommitTogether together;
  if (request.hjif) {
    HjifOptions options;
    options.ticks_per_sample = request.ticks_per_sample;
    s.hjif = write_hjif(movie, *request.hjif, options);
    s.lines.push_back(fmt::format(
        "export: {} channels, level {}, timescale {}, {} effect(s) per channel, amplitude 1 = "
        "{:g} um -> {}",
        s.hjif->channels, s.hjif->level, s.hjif->timescale, s.hjif->effects_per_channel,
        s.hjif->full_scale_um, request.hjif->string()));
  }
  if (request.wav) {
    s.wav_full_scale_um = write_wav(movie, *request.wav);
    s.lines.push_back(fmt::format("export: {} channels at {:g} Hz, {} frames, 1.0 = {:g} um -> {}",
                                  movie.layout.contactor_count(), movie.rate_hz, movie.frame_count,
                                  *s.wav_full_scale_um, request.wav->string()));
  }
  together.commit();
  return s;
}

}  // namespace tactile::movie
