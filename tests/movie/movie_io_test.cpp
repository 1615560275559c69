// Tactile movie files: HDF5 round trip, every kind of malformed file, CSV export.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <H5Cpp.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <limits>
#include <sstream>

#include "../common/bad_input.hpp"
#include "../common/temp_dir.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/h5.hpp"
#include "tactile/movie/movie_io.hpp"
#include "test_movies.hpp"

namespace tactile::movie {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

class MovieIo : public ::testing::Test {
 protected:
  // A valid movie file, then `edit` changes it in place through the raw HDF5 API.
  fs::path edited(const std::string& name, const std::function<void(H5::H5File&)>& edit) {
    const fs::path p = dir_ / name;
    write_tactile_movie(p, testing::sine_movie(stress_layout(), 700, 7, 20));
    H5::H5File f(p.string(), H5F_ACC_RDWR);
    edit(f);
    f.close();
    return p;
  }

  void expect_format_error(const fs::path& p, const std::string& words) {
    try {
      read_tactile_movie(p);
      FAIL() << p << " was accepted; expected an error about " << words;
    } catch (const FormatError& e) {
      EXPECT_THAT(e.what(), HasSubstr(words));
      EXPECT_THAT(e.what(), HasSubstr(p.filename().string()));  // names the file
    }
  }

  tactile::test::TempDir tmp_;
  const fs::path dir_ = tmp_.path();
};

TEST_F(MovieIo, RoundTripKeepsEverything) {
  TactileMovie m = testing::sine_movie(latero_layout(), 1000, 123, 33.3);
  m.provenance.created_utc = "2026-11-22T20:00:00Z";
  m.layout.axis = DeflectionAxis::y;
  const fs::path p = dir_ / "movie.h5";
  write_tactile_movie(p, m);
  const TactileMovie r = read_tactile_movie(p);
  EXPECT_EQ(r.layout.name, "latero");
  EXPECT_EQ(r.layout.rows, 8);
  EXPECT_EQ(r.layout.cols, 8);
  EXPECT_DOUBLE_EQ(r.layout.pitch_y_mm, 1.6125);
  EXPECT_DOUBLE_EQ(r.layout.contactor_height_mm, 1.4);
  EXPECT_EQ(r.layout.axis, DeflectionAxis::y);
  EXPECT_DOUBLE_EQ(r.layout.deflection_min_um, -100);
  EXPECT_DOUBLE_EQ(r.layout.max_rate_hz, 750);
  EXPECT_DOUBLE_EQ(r.rate_hz, 1000);
  EXPECT_EQ(r.frame_count, 123);
  EXPECT_EQ(r.deflection_um, m.deflection_um);  // float32 on disk: bit-exact
  EXPECT_EQ(r.provenance.program_version, "test");
  EXPECT_EQ(r.provenance.created_utc, "2026-11-22T20:00:00Z");
  EXPECT_EQ(r.provenance.input, "sine");
  EXPECT_EQ(r.provenance.method, "none");
  EXPECT_EQ(r.provenance.parameters_json, R"({"amplitude_um":1})");
  EXPECT_EQ(r.provenance.command_line, "tactile test --sine");
}

// Movies written before the provenance's fields were renamed hold provenance_source,
// provenance_mapping_method and provenance_mapping_parameters_json (and no command line): they
// still read, as input, method and parameters.
TEST_F(MovieIo, OlderFilesWithTheFormerProvenanceNamesAreRead) {
  const auto p = edited("old-provenance.h5", [](H5::H5File& f) {
    for (const char* name : {"provenance_input", "provenance_command_line", "provenance_method",
                             "provenance_parameters_json"})
      f.removeAttr(name);
    h5::write_attr(f, "provenance_source", "/data/strain.h5");
    h5::write_attr(f, "provenance_mapping_method", "proportional");
    h5::write_attr(f, "provenance_mapping_parameters_json", R"({"gain_um_per_strain":500})");
  });
  const TactileMovie m = read_tactile_movie(p);
  EXPECT_EQ(m.provenance.input, "/data/strain.h5");
  EXPECT_EQ(m.provenance.method, "proportional");
  EXPECT_EQ(m.provenance.parameters_json, R"({"gain_um_per_strain":500})");
  EXPECT_EQ(m.provenance.command_line, "");
  EXPECT_EQ(m.provenance.program_version, "test");
}

TEST_F(MovieIo, SchemaIsWhatFormatMdDocuments) {
  const fs::path p = dir_ / "movie.h5";
  write_tactile_movie(p, testing::sine_movie(stress_layout(), 700, 5, 10));
  H5::H5File f(p.string(), H5F_ACC_RDONLY);
  EXPECT_EQ(h5::read_attr_string(f, "format", "t"), "tactile-movie");
  EXPECT_EQ(h5::read_attr_int(f, "format_version", "t"), 1);
  EXPECT_EQ(h5::read_attr_string(f, "units", "t"), "um");
  EXPECT_FALSE(h5::read_attr_string(f, "provenance_created_utc", "t").empty());
  EXPECT_EQ(h5::read_attr_string(f, "provenance_input", "t"), "sine");
  EXPECT_EQ(h5::read_attr_string(f, "provenance_method", "t"), "none");
  EXPECT_EQ(h5::read_attr_string(f, "provenance_command_line", "t"), "tactile test --sine");
  H5::DataSet ds = f.openDataSet("deflection_um");
  EXPECT_EQ(ds.getTypeClass(), H5T_FLOAT);
  EXPECT_EQ(ds.getFloatType().getSize(), 4u);
  hsize_t dims[3];
  ASSERT_EQ(ds.getSpace().getSimpleExtentDims(dims), 3);
  EXPECT_EQ(dims[0], 5u);
  EXPECT_EQ(dims[1], 10u);
  EXPECT_EQ(dims[2], 10u);
}

TEST_F(MovieIo, EmptyMovieRoundTrips) {
  TactileMovie m = testing::sine_movie(stress_layout(), 700, 0, 10);
  const fs::path p = dir_ / "empty_movie.h5";
  write_tactile_movie(p, m);
  EXPECT_EQ(read_tactile_movie(p).frame_count, 0);
}

TEST_F(MovieIo, MissingEmptyTruncatedAndForeignFiles) {
  expect_format_error(dir_ / "nothing_here.h5", "no such file");
  const fs::path empty = dir_ / "empty.h5";
  std::ofstream(empty).close();
  expect_format_error(empty, "empty");
  const fs::path text = dir_ / "text.h5";
  std::ofstream(text) << "frame,t_s\n0,0\n";
  expect_format_error(text, "not an HDF5 file");
  // Truncation: the superblock survives but the objects it points to do not.
  const fs::path good = dir_ / "good.h5";
  write_tactile_movie(good, testing::sine_movie(stress_layout(), 700, 2000, 20));
  const fs::path cut = dir_ / "cut.h5";
  fs::copy_file(good, cut);
  fs::resize_file(cut, fs::file_size(good) / 2);
  try {
    read_tactile_movie(cut);
    FAIL() << "truncated file accepted";
  } catch (const FormatError& e) {
    EXPECT_THAT(e.what(), HasSubstr("cut.h5"));
    EXPECT_THAT(e.what(), ::testing::AnyOf(HasSubstr("truncated"), HasSubstr("cannot read")));
  }
}

TEST_F(MovieIo, WrongSchema) {
  expect_format_error(edited("noformat.h5", [](H5::H5File& f) { f.removeAttr("format"); }),
                      "'format' is missing");
  expect_format_error(edited("strain.h5",
                             [](H5::H5File& f) {
                               f.removeAttr("format");
                               h5::write_attr(f, "format", "strain-movie");
                             }),
                      "format is 'strain-movie'");
  expect_format_error(edited("future.h5",
                             [](H5::H5File& f) {
                               f.removeAttr("format_version");
                               h5::write_attr(f, "format_version", std::int64_t{2});
                             }),
                      "format_version 2 is not supported");
  expect_format_error(edited("norate.h5", [](H5::H5File& f) { f.removeAttr("rate_hz"); }),
                      "'rate_hz' is missing");
  expect_format_error(edited("textrate.h5",
                             [](H5::H5File& f) {
                               f.removeAttr("rate_hz");
                               h5::write_attr(f, "rate_hz", "fast");
                             }),
                      "rate_hz");
  expect_format_error(edited("mm.h5",
                             [](H5::H5File& f) {
                               f.removeAttr("units");
                               h5::write_attr(f, "units", "mm");
                             }),
                      "units is 'mm'");
  expect_format_error(edited("nodata.h5", [](H5::H5File& f) { f.unlink("deflection_um"); }),
                      "deflection_um: dataset is missing");
}

TEST_F(MovieIo, WrongDatasetTypeRankAndSize) {
  expect_format_error(
      edited(
          "int.h5",
          [](H5::H5File& f) {
            f.unlink("deflection_um");
            h5::write_dataset(f, "deflection_um", std::vector<std::int32_t>(700, 1), {7, 10, 10});
          }),
      "expected floating-point");
  expect_format_error(
      edited("rank2.h5",
             [](H5::H5File& f) {
               f.unlink("deflection_um");
               h5::write_dataset(f, "deflection_um", std::vector<float>(700, 1), {7, 100});
             }),
      "expected 3 dimension(s), found 2");
  expect_format_error(
      edited("size.h5",
             [](H5::H5File& f) {
               f.unlink("deflection_um");
               h5::write_dataset(f, "deflection_um", std::vector<float>(630, 1), {7, 9, 10});
             }),
      "frames are 9 x 10 but the layout is 10 x 10");
  expect_format_error(
      edited("frames.h5",
             [](H5::H5File& f) {
               f.unlink("deflection_um");
               h5::write_dataset(f, "deflection_um", std::vector<float>(600, 1), {6, 10, 10});
             }),
      "has 6 frames but frame_count says 7");
  expect_format_error(edited("nan.h5",
                             [](H5::H5File& f) {
                               std::vector<float> v(700, 1);
                               v[4 * 100 + 5 * 10 + 6] = std::numeric_limits<float>::quiet_NaN();
                               f.unlink("deflection_um");
                               h5::write_dataset(f, "deflection_um", v, {7, 10, 10});
                             }),
                      "frame 4, row 5, col 6 is not finite");
  expect_format_error(edited("grid.h5",
                             [](H5::H5File& f) {
                               f.removeAttr("layout_rows");
                               h5::write_attr(f, "layout_rows", std::int64_t{-3});
                             }),
                      "layout_rows x layout_cols = -3 x 10");
}

TEST_F(MovieIo, FailedWriteLeavesTheOldFile) {
  const fs::path p = dir_ / "keep.h5";
  write_tactile_movie(p, testing::sine_movie(stress_layout(), 700, 3, 10));
  TactileMovie bad = testing::sine_movie(stress_layout(), 700, 3, 10);
  bad.deflection_um.resize(bad.deflection_um.size() - 1);
  EXPECT_THROW(write_tactile_movie(p, bad), std::invalid_argument);
  EXPECT_EQ(read_tactile_movie(p).frame_count, 3);
}

TEST_F(MovieIo, CsvHasOneRowPerFrame) {
  const TactileMovie m = testing::sine_movie(stress2_layout(), 1000, 4, 12.5);
  const fs::path p = dir_ / "movie.csv";
  export_tactile_csv(p, m);
  std::ifstream in(p);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("frame,t_s,r0c0_um,r0c1_um,", 0), 0u);
  EXPECT_NE(header.find(",r7c7_um"), std::string::npos);
  EXPECT_EQ(std::count(header.begin(), header.end(), ','), 2 + 64 - 1);
  std::string line;
  int rows = 0;
  while (std::getline(in, line)) {
    std::stringstream ss(line);
    std::string cell;
    std::vector<double> cells;
    while (std::getline(ss, cell, ',')) cells.push_back(std::stod(cell));
    ASSERT_EQ(cells.size(), 66u);
    EXPECT_EQ(cells[0], rows);
    EXPECT_DOUBLE_EQ(cells[1], rows / 1000.0);
    EXPECT_FLOAT_EQ(static_cast<float>(cells[2 + 9]), m.frame(rows)[9]);
    ++rows;
  }
  EXPECT_EQ(rows, 4);
}

// Every numeric attribute, every hostile value: refused, naming the file and the attribute
// (rate_hz 1e308 and 1e-300 once crashed `info`).
TEST_F(MovieIo, HostileNumbersInEveryAttributeAreNamed) {
  for (const char* name :
       {"rate_hz", "layout_pitch_x_mm", "layout_pitch_y_mm", "layout_contactor_width_mm",
        "layout_contactor_height_mm", "layout_deflection_min_um", "layout_deflection_max_um",
        "layout_max_rate_hz"}) {
    for (double v : tactile::testing::hostile_doubles()) {
      // The deflection range may hold tiny numbers; only the non-finite and huge are nonsense.
      const bool range = std::string(name).find("deflection") != std::string::npos;
      if (range && std::isfinite(v) && std::abs(v) < 1) continue;
      const auto p = edited("m.h5", [&](H5::H5File& f) { tactile::testing::set_attr(f, name, v); });
      expect_format_error(p, name);
    }
  }
  for (const char* name : {"frame_count", "layout_rows", "layout_cols"}) {
    for (std::int64_t v : tactile::testing::hostile_ints()) {
      const auto p = edited("m.h5", [&](H5::H5File& f) { tactile::testing::set_attr(f, name, v); });
      expect_format_error(p, name);
    }
  }
}

// Found by the second hostile-input run: a range edited to [-50, -5] was read as valid; a layout
// file with it is refused, and rest (0) is where every contactor starts and is parked. (Values
// outside a range that holds 0 stay legal: the player decides, see docs/formats.md.)
TEST_F(MovieIo, DeflectionRangeWithoutRestIsNamed) {
  expect_format_error(
      edited(
          "m.h5",
          [](H5::H5File& f) { tactile::testing::set_attr(f, "layout_deflection_max_um", -5.0); }),
      "layout deflection range [-50, -5] um does not contain 0 (the rest position)");
  expect_format_error(
      edited("m.h5",
             [](H5::H5File& f) { tactile::testing::set_attr(f, "layout_deflection_min_um", 3.0); }),
      "does not contain 0");
  EXPECT_NO_THROW(read_tactile_movie(edited("m.h5", [](H5::H5File& f) {
    tactile::testing::set_attr(f, "layout_deflection_max_um", 0.0);
  })));
}

// A deflection no contactor of the layout can take (here 1 m on a display that moves 50 um
// either way) is refused naming the frame, the contactor and the range; a little saturation
// beyond the layout's range is still a movie.
TEST_F(MovieIo, DeflectionsNoContactorCanTakeAreNamed) {
  const auto with_value = [&](float value) {
    return edited("far.h5", [value](H5::H5File& f) {
      std::vector<float> v(700, 1);
      v[4 * 100 + 5 * 10 + 6] = value;
      f.unlink("deflection_um");
      h5::write_dataset(f, "deflection_um", v, {7, 10, 10});
    });
  };
  expect_format_error(with_value(1e6f),
                      "deflection_um: frame 4, row 5, col 6: deflection 1000000 um is out of "
                      "range: layout 'stress' moves from -50 to 50 um, and a movie's values "
                      "may go beyond that by at most its width (-150 to 150 um)");
  expect_format_error(with_value(-151), "deflection -151 um is out of range");
  EXPECT_EQ(read_tactile_movie(with_value(-150)).frame(4)[56], -150);
  EXPECT_EQ(read_tactile_movie(with_value(60)).frame(4)[56], 60);
}

TEST_F(MovieIo, HugeDeclaredFrameCountNamesTheLimitQuickly) {
  for (const hsize_t frames : {hsize_t{2000000000}, hsize_t{1} << 40}) {
    const auto p = edited("huge.h5", [&](H5::H5File& f) {
      H5::Group root = f.openGroup("/");
      tactile::testing::set_huge_dataset(root, "deflection_um", {frames, 10, 10},
                                         H5::PredType::NATIVE_FLOAT);
      tactile::testing::set_attr(f, "frame_count", static_cast<std::int64_t>(frames));
    });
    const auto t0 = std::chrono::steady_clock::now();
    try {
      read_tactile_movie(p);
      ADD_FAILURE() << frames << " frames accepted";
    } catch (const FormatError& e) {
      EXPECT_THAT(e.what(),
                  ::testing::AnyOf(HasSubstr("more than the limit of"), HasSubstr("frame_count")));
      EXPECT_THAT(e.what(), HasSubstr("huge.h5"));
    }
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2));
  }
}

// Cut at every eighth, random bytes: a FormatError naming the file, never a crash or another
// exception.
TEST_F(MovieIo, CutAndRandomFilesAreFormatErrors) {
  const auto good = edited("good.h5", [](H5::H5File&) {});
  const auto full = tactile::testing::file_bytes(good);
  const fs::path bad = dir_ / "bad.h5";
  for (std::size_t eighth = 1; eighth < 8; ++eighth) {
    tactile::testing::write_bytes(
        bad, std::vector<char>(full.begin(),
                               full.begin() + static_cast<long>(full.size() * eighth / 8)));
    expect_format_error(bad, "bad.h5");
  }
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    tactile::testing::write_bytes(bad, tactile::testing::random_bytes(seed, 64 * seed));
    expect_format_error(bad, "bad.h5");
  }
}

// Movies written before strings were fixed-length hold variable-length ones, which HDF5 reads
// through its global heap.
void make_strings_variable_length(H5::H5File& f) {
  H5::StrType vlen(H5::PredType::C_S1, H5T_VARIABLE);
  vlen.setCset(H5T_CSET_UTF8);
  for (const char* name : {"format", "units", "layout_name", "layout_axis",
                           "provenance_program_version", "provenance_method"}) {
    const std::string value = h5::read_attr_string(f, name, "edit");
    f.removeAttr(name);
    f.createAttribute(name, vlen, H5::DataSpace()).write(vlen, value);
  }
}

TEST_F(MovieIo, OlderFilesWithVariableLengthStringsAreRead) {
  const auto p = edited("old.h5", make_strings_variable_length);
  ASSERT_TRUE(
      H5::H5File(p.string(), H5F_ACC_RDONLY).openAttribute("format").getStrType().isVariableStr());
  const TactileMovie m = read_tactile_movie(p);
  EXPECT_EQ(m.layout.name, "stress");
  EXPECT_EQ(m.frame_count, 7);
  EXPECT_EQ(m.provenance.method, "none");
}

// Bytes scrambled inside a valid file, with fixed- and (older files) variable-length strings:
// a FormatError naming the file, or (a scramble that left it readable) a movie. Some of these
// crash or hang HDF5 1.10 itself; the reader contains that in a child process, so this test
// fails (or dies) if it does not.
TEST_F(MovieIo, ScrambledFilesAreFormatErrorsOrMovies) {
  const fs::path bad = dir_ / "bad.h5";
  int refused = 0;
  int crashed = 0;
  for (const bool variable : {false, true}) {
    const auto good = variable ? edited("old.h5", make_strings_variable_length)
                               : edited("good.h5", [](H5::H5File&) {});
    const auto full = tactile::testing::file_bytes(good);
    for (std::uint32_t seed = 1; seed <= 60; ++seed) {
      tactile::testing::write_bytes(bad, tactile::testing::scrambled(full, seed, 4));
      try {
        read_tactile_movie(bad);
      } catch (const FormatError& e) {
        EXPECT_THAT(e.what(), HasSubstr("bad.h5")) << "scramble seed " << seed;
        ++refused;
        if (std::string(e.what()).find("damaged file: reading it") != std::string::npos) {
          ++crashed;
        }
      }
    }
  }
  // Four random bytes in a file of a few kilobytes mostly land in metadata or data checks.
  EXPECT_GT(refused, 10);
  std::printf("scrambled movies: %d of 120 refused, %d of them crashed the reading child\n",
              refused, crashed);
}

// Files on which HDF5 1.10 itself misbehaves (tests/data/damaged-movies/README.md): each is a
// FormatError naming the file, whatever HDF5 does in the reading child. The stalled one costs
// the reader's bound for a small file (10 s).
TEST_F(MovieIo, FilesThatBreakHdf5ItselfAreFormatErrors) {
  const fs::path data = fs::path(TACTILE_TEST_DATA_DIR) / "damaged-movies";
  for (const char* name : {"heap-overlap.h5", "negative-size.h5", "heap-stall.h5"}) {
    const auto t0 = std::chrono::steady_clock::now();
    try {
      read_tactile_movie(data / name);
      ADD_FAILURE() << name << " was accepted";
    } catch (const FormatError& e) {
      EXPECT_THAT(e.what(), HasSubstr(name));
      std::printf("%s: %s\n", name, e.what());
    }
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(30)) << name;
  }
}

}  // namespace
}  // namespace tactile::movie
