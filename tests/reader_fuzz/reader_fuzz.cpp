// libFuzzer on the file readers: the bytes of each input are written to a file and read back by
// the reader named in TACTILE_FUZZ_READER. A reader may refuse its input only with
// tactile::FormatError (or std::runtime_error / std::invalid_argument it documents); any other
// exception, crash or sanitizer report is a finding.
//
//   TACTILE_FUZZ_READER=strain-movie reader_fuzz --write-seeds DIR   writes a few valid files
//   TACTILE_FUZZ_READER=strain-movie reader_fuzz [libFuzzer flags] CORPUS...

#include <fmt/format.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>

#include "pores/pore_model.hpp"
#include "tactile/capture/calibration_io.hpp"
#include "tactile/capture/pore_model_io.hpp"
#include "tactile/capture/pore_training_io.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/experiments/experiment.hpp"
#include "tactile/movie/hjif.hpp"
#include "tactile/movie/layout_json.hpp"
#include "tactile/movie/movie_io.hpp"
#include "tactile/perception/classifier_model.hpp"
#include "tactile/perception/recording_csv.hpp"

namespace fs = std::filesystem;
using namespace tactile;

namespace {

struct Reader {
  const char* extension;
  std::function<void(const fs::path&)> read;
  std::function<void(const fs::path& dir)> write_seeds;
};

void copy_head(const fs::path& from, const fs::path& to, int lines) {
  std::ifstream in(from);
  std::ofstream out(to);
  std::string line;
  for (int i = 0; i < lines && std::getline(in, line); ++i) out << line << '\n';
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream(path) << text;
}

capture::StrainMovie small_strain_movie(int points) {
  capture::StrainMovie m;
  m.frame_rate_hz = 60;
  m.span_frames = 1;
  m.camera_frame_count = 2;
  m.field_width_mm = 10;
  m.field_height_mm = 8;
  m.calibration = capture::uniform_calibration(47, 640, 480);
  capture::StrainFrame f;
  f.frame_from = 0;
  f.frame_to = 1;
  f.t_s = 1.0 / 60;
  for (int i = 0; i < points; ++i) {
    const double x = 1.0 + i, y = 1.0 + (i % 2);
    m.tracks.push_back({i, 0, capture::FeatureType::pore, x * 47, y * 47, x, y});
    m.tracks.push_back({i, 1, capture::FeatureType::pore, x * 47 + 1, y * 47, x + 0.02, y});
    f.points_from.push_back(m.tracks[m.tracks.size() - 2]);
    f.points_to.push_back(m.tracks.back());
  }
  for (int i = 0; i + 1 < points; ++i) f.edges.push_back({i, i + 1, 1.0, 1.01, 0.01});
  for (int i = 0; i + 2 < points; ++i) f.triangles.push_back({{i, i + 1, i + 2}});
  m.frames.push_back(f);
  // A contact map of 4 x 3 cells of 160 px over both frames, so that its reader is fuzzed too.
  if (points > 3) {
    m.contact.grid = {160, 4, 3};
    m.contact.threshold = 10;
    for (int i = 0; i < 2 * 12; ++i) {
      m.contact.ridge_contrast.push_back(i);
      m.contact.in_contact.push_back(i >= 10 ? 1 : 0);
    }
  }
  return m;
}

movie::TactileMovie small_tactile_movie(int frames) {
  movie::TactileMovie m;
  m.layout = movie::stress_layout();
  m.rate_hz = 700;
  m.frame_count = frames;
  m.deflection_um.assign(static_cast<std::size_t>(frames * m.layout.contactor_count()), 0.0F);
  for (std::size_t i = 0; i < m.deflection_um.size(); ++i) {
    m.deflection_um[i] = static_cast<float>(i % 7) - 3.0F;
  }
  return m;
}

// One reading child for the whole run: the movie readers' crash containment forks once, and
// again only after an input that crashed or hung the child (see h5::ReadingProcess).
h5::ReadingProcess& reading_process() {
  static h5::ReadingProcess process;
  return process;
}

const std::map<std::string, Reader>& readers() {
  static const fs::path data = fs::path(TACTILE_SOURCE_DIR) / "tests" / "data";
  static const std::map<std::string, Reader> all = {
      {"strain-movie",
       {".h5", [](const fs::path& p) { capture::read_strain_movie(p, &reading_process()); },
        [](const fs::path& dir) {
          capture::write_strain_movie(dir / "one.h5", small_strain_movie(3));
          capture::write_strain_movie(dir / "some.h5", small_strain_movie(8));
          // A live recording's map: a threshold per frame, the second frame dropped unseen.
          capture::StrainMovie live = small_strain_movie(8);
          live.contact.frame_threshold = {10, 0};
          live.contact.frame_seen = {1, 0};
          for (std::size_t i = 12; i < 24; ++i) {
            live.contact.ridge_contrast[i] = 0;
            live.contact.in_contact[i] = 0;
          }
          capture::write_strain_movie(dir / "live.h5", live);
        }}},
      {"tactile-movie",
       {".h5", [](const fs::path& p) { movie::read_tactile_movie(p, &reading_process()); },
        [](const fs::path& dir) {
          movie::write_tactile_movie(dir / "one.h5", small_tactile_movie(1));
          movie::write_tactile_movie(dir / "some.h5", small_tactile_movie(5));
        }}},
      {"hjif",
       {".hjif", [](const fs::path& p) { movie::read_hjif(p); },
        [](const fs::path& dir) {
          movie::TactileMovie m = small_tactile_movie(5);
          m.layout.rows = 2;
          m.layout.cols = 2;
          m.deflection_um.resize(20);
          m.provenance.parameters_json = R"({"gain":1})";
          write_text(dir / "small.hjif", movie::hjif_text(m));
          m.frame_count = 1;
          m.deflection_um.resize(4);
          write_text(dir / "one.hjif", movie::hjif_text(m));
        }}},
      {"layout-json",
       {".json", [](const fs::path& p) { movie::read_layout_json(p); },
        [](const fs::path& dir) {
          write_text(dir / "stress.json", movie::layout_to_json(movie::stress_layout()));
          write_text(dir / "stress2.json", movie::layout_to_json(movie::stress2_layout()));
        }}},
      {"calibration-json",
       {".json", [](const fs::path& p) { capture::read_calibration_json(p); },
        [](const fs::path& dir) {
          capture::write_calibration_json(dir / "calib.json",
                                          capture::uniform_calibration(47, 640, 480));
        }}},
      {"pore-model-json",
       {".json", [](const fs::path& p) { capture::read_pore_model_json(p); },
        [](const fs::path& dir) {
          capture::PoreModelFile m;
          m.coefficients.assign(capture::kPoreModelSize, 0.01);
          m.px_per_mm = 47;
          m.label_radius_mm = 0.1;
          m.trained_on = {"image_01"};
          capture::write_pore_model_json(dir / "model.json", m);
        }}},
      {"classifier-model-json",
       {".json", [](const fs::path& p) { perception::read_classifier_model(p); },
        [](const fs::path& dir) {
          write_text(dir / "model.json",
                     R"({"format":"tactile classifier model","format_version":2,"svm":{"c":1}})");
        }}},
      {"recording-csv",
       {".csv", [](const fs::path& p) { perception::read_sensor_csv(p); },
        [](const fs::path& dir) {
          copy_head(data / "biotac-materials" / "mat1_1_bio.csv", dir / "rec.csv", 12);
        }}},
      {"labels-csv",
       {".csv", [](const fs::path& p) { perception::read_recording_labels(p); },
        [](const fs::path& dir) {
          write_text(dir / "labels.csv",
                     "file,class,value\na_bio.csv,rough,-2.5\nb_bio.csv,smooth,4\n");
          write_text(dir / "plain.csv", "class,file\nx,sub/c.csv\n");
        }}},
      // Parsing only (the file's runs are not made): every field of the experiment, its
      // ground-truth and synthetic scenes, its parameters and its perception section.
      {"experiment-json",
       {".json", [](const fs::path& p) { experiments::read_experiment(p); },
        [](const fs::path& dir) {
          write_text(dir / "small.json", R"({"name": "small", "seed": 3,
  "sources": [{"name": "bump", "ground_truth": {"scene": "bump", "frames": 12,
               "frame_rate_hz": 60, "height_mm": 0.5}, "grid_spacing_mm": 0.5},
              {"name": "slide", "synthetic": {"scene": "flat-slide", "frames": 4, "noise": 2}}],
  "layouts": ["stress", "latero"], "methods": ["proportional", "integrated", "profile"],
  "parameters": {"strain": ["per-frame"], "rate_hz": 200, "gain_um_per_strain": [500, 1000],
                 "peak_fraction": 0.9, "reference_frame": -1},
  "perception": {"trials": 2, "degree": [1], "footprints_mm": [5]}})");
        }}},
      {"pore-marks",
       {".txt", [](const fs::path& p) { capture::read_pore_marks(p, 640, 480); },
        [](const fs::path& dir) {
          copy_head(data / "polyu-hrf-pores" / "pores_01.txt", dir / "pores.txt", 30);
        }}},
  };
  return all;
}

const Reader* chosen = nullptr;
fs::path scratch;

}  // namespace

extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
  const char* name = std::getenv("TACTILE_FUZZ_READER");
  const auto it = name ? readers().find(name) : readers().end();
  if (it == readers().end()) {
    std::string known;
    for (const auto& [n, r] : readers()) known += " " + n;
    std::fprintf(stderr, "reader_fuzz: set TACTILE_FUZZ_READER to one of:%s\n", known.c_str());
    std::exit(2);
  }
  chosen = &it->second;
  if (*argc >= 3 && std::strcmp((*argv)[1], "--write-seeds") == 0) {
    fs::create_directories((*argv)[2]);
    chosen->write_seeds((*argv)[2]);
    std::exit(0);
  }
  // Each input is written to a file before it is read. In a memory file system (/dev/shm) that
  // costs a copy; on ext4 rewriting a truncated file queues its blocks for the disk at every
  // close, which made the fast readers wait on the disk more than they parsed.
  std::error_code ec;
  const fs::path shm = "/dev/shm";
  const fs::path dir = fs::is_directory(shm, ec) && ::access(shm.c_str(), W_OK) == 0
                           ? shm
                           : fs::temp_directory_path();
  scratch = dir / fmt::format("tactile-reader-fuzz-{}-{}{}", name, ::getpid(), chosen->extension);
  std::atexit([] {
    std::error_code ignored;
    fs::remove(scratch, ignored);
  });
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  {
    std::ofstream out(scratch, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    chosen->read(scratch);
  } catch (const FormatError&) {
  } catch (const std::invalid_argument&) {
  } catch (const std::runtime_error&) {
  }
  // Anything else (std::bad_alloc, std::length_error, nlohmann's or HDF5's own exceptions)
  // escapes and libFuzzer reports it as a crash.
  return 0;
}
