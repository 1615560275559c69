#pragma once
// What the authoring window saves, and how it reopens it: the mappings it compares (A, when
// pinned, and the current one) as an experiment file that `tactile experiment` runs, and their
// movies written exactly as that run writes them, so that the two give equal files (equal bytes
// when SOURCE_DATE_EPOCH fixes the creation time of both).

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "tactile/author/outcome.hpp"
#include "tactile/experiments/experiment.hpp"

namespace tactile::author {

// The experiment that maps `strain_file` with each of `mappings` (A first): one file source
// named "strain", and the layouts, methods and parameters the mappings use, each as the list of
// its distinct values in the mappings' order. The grid they span holds every mapping: its first
// run is the first mapping's and its last the last one's. rate_hz is written only when a mapping
// sets it (unset, each layout plays at its own rate). Throws std::invalid_argument for no
// mappings or an invalid name.
std::string experiment_json(const std::string& name, const std::filesystem::path& strain_file,
                            const std::vector<mapping::MapRequest>& mappings);

struct Saved {
  std::filesystem::path experiment;           // out_dir/NAME.json
  std::vector<std::filesystem::path> movies;  // out_dir/movies/<run id>.h5: A's, the current
  std::vector<std::string> run_ids;           // of those movies
  std::filesystem::path hjif, wav;            // the current mapping, beside its movie
};

// Writes into out_dir (created): NAME.json (experiment_json of A, when given, and the current
// mapping), and the movies of A and the current mapping as `tactile experiment NAME.json --out
// out_dir` would (experiments::run_movie_path, stamp_run_provenance), each from the outcome
// given, not mapped again; the current one also as HJIF and WAV (export's). Every file is
// written atomically; the experiment is read back with the experiment library's own reader
// first, so that a mapping it would refuse is refused here, and nothing is written over the
// strain file or a layout file the mappings read (OutputIsInputError). Throws tactile::FormatError
// or std::invalid_argument naming the problem, std::runtime_error when a file cannot be written.
Saved save_authoring(const std::filesystem::path& out_dir, const std::string& name,
                     const std::filesystem::path& strain_file, const MappingOutcome* a,
                     const MappingOutcome& current);

// The mappings an experiment file holds for the window: its first run as A (when it has more
// than one) and its last as the current, with its first file source's strain file. Throws
// std::invalid_argument when it has no file source (the window maps a strain movie) or its
// runs use a method the window cannot show (profile).
struct ExperimentChoices {
  std::filesystem::path strain_file;
  std::optional<mapping::MapRequest> a;
  mapping::MapRequest current;
};
ExperimentChoices choices_of(const experiments::Experiment& experiment);

}  // namespace tactile::author
