#pragma once
// `export` as a request: which files a tactile movie is written to for other tools (MPEG-I
// Haptics .hjif, multichannel WAV), its option table (read by the command line and the Python
// module alike) and run_export(), which checks the outputs and writes them together. The HJIF
// option's default is HjifOptions' member initialiser.

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tactile/common/option_table.hpp"
#include "tactile/movie/hjif.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::movie {

struct ExportRequest {
  std::filesystem::path movie;  // the command line's input (Python passes a Movie)
  std::optional<std::filesystem::path> hjif;
  std::optional<std::filesystem::path> wav;
  std::int32_t ticks_per_sample = HjifOptions{}.ticks_per_sample;
};

const std::vector<OptionRow<ExportRequest>>& export_options();

// Every value, and at least one output (RequestError in the front end's spelling).
void check_request(const ExportRequest& request, OptionSpelling spelling);

struct ExportSummary {
  std::optional<HjifSummary> hjif;
  std::optional<double> wav_full_scale_um;  // the deflection a WAV sample of 1.0 stands for
  std::vector<std::string> lines;           // what a front end prints, one line per file
};

// check_request, then refuses outputs over the input (request.movie, when it names one) or
// without their extension (OutputPathError): before the movie is read.
void check_outputs(const ExportRequest& request, OptionSpelling spelling);

// check_outputs, then writes every file or none.
ExportSummary run_export(const ExportRequest& request, const TactileMovie& movie,
                         OptionSpelling spelling);

}  // namespace tactile::movie
