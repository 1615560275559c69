#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <chrono>
#include <fstream>

#include "../common/bad_input.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/common/error.hpp"
#include "tactile/common/h5.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

StrainMovie sample_movie() {
  StrainMovie m;
  m.frame_rate_hz = 60;
  m.span_frames = 2;
  m.camera_frame_count = 5;
  m.field_width_mm = 10.3;
  m.field_height_mm = 10.9;
  m.calibration = uniform_calibration(62.5, 640, 484);
  m.calibration.px_to_mm[6] = 1e-6;  // a perspective term must survive too
  m.provenance.input = "unit test";
  m.provenance.program_version = "0.1.0-test";
  m.provenance.command_line = "tactile capture 'unit test'";
  m.provenance.method = "capture";
  m.provenance.parameters_json = R"({"span_frames":2})";
  m.provenance.created_utc = "2026-11-25T12:00:00Z";
  for (std::int32_t id = 0; id < 4; ++id) {
    for (std::int32_t f = 0; f < 5; ++f) {
      m.tracks.push_back({id, f, id == 3 ? FeatureType::bifurcation : FeatureType::pore,
                          10.0 * id + f, 5.0 * id, 0.16 * id + 0.01 * f, 0.08 * id});
    }
  }
  for (std::int32_t f = 0; f + 2 < 5; ++f) {
    StrainFrame sf;
    sf.frame_from = f;
    sf.frame_to = f + 2;
    sf.t_s = (f + 2) / 60.0;
    for (std::int32_t id = 0; id < (f == 1 ? 3 : 4); ++id) {
      const auto& a = m.tracks[static_cast<std::size_t>(id * 5 + f)];
      const auto& b = m.tracks[static_cast<std::size_t>(id * 5 + f + 2)];
      sf.points_from.push_back(a);
      sf.points_to.push_back(b);
    }
    sf.edges.push_back({0, 1, 0.2, 0.21, 0.05});
    sf.edges.push_back({1, 2, 0.3, 0.27, -0.1});
    sf.triangles.push_back({{0, 1, 2}});
    m.frames.push_back(sf);
  }
  // Cells of 63 px over 640 x 484 px: 11 columns, 8 rows; contrasts 0..39 in turn, in contact
  // from 20.
  m.contact.grid = contact_grid(640, 484, 62.5);
  m.contact.threshold = 20;
  for (int i = 0; i < 5 * 88; ++i) {
    m.contact.ridge_contrast.push_back(i % 40);
    m.contact.in_contact.push_back(i % 40 >= 20 ? 1 : 0);
  }
  return m;
}

void expect_same_point(const TrackedPoint& a, const TrackedPoint& b) {
  EXPECT_EQ(a.track_id, b.track_id);
  EXPECT_EQ(a.frame, b.frame);
  EXPECT_EQ(a.type, b.type);
  EXPECT_EQ(a.x_px, b.x_px);
  EXPECT_EQ(a.y_px, b.y_px);
  EXPECT_EQ(a.x_mm, b.x_mm);
  EXPECT_EQ(a.y_mm, b.y_mm);
}

TEST(StrainMovieIo, RoundTripKeepsEveryValue) {
  TempDir dir;
  const StrainMovie m = sample_movie();
  write_strain_movie(dir.path() / "m.h5", m);
  const StrainMovie r = read_strain_movie(dir.path() / "m.h5");
  EXPECT_EQ(r.frame_rate_hz, m.frame_rate_hz);
  EXPECT_EQ(r.span_frames, m.span_frames);
  EXPECT_EQ(r.camera_frame_count, m.camera_frame_count);
  EXPECT_EQ(r.field_width_mm, m.field_width_mm);
  EXPECT_EQ(r.field_height_mm, m.field_height_mm);
  EXPECT_EQ(r.calibration.px_to_mm, m.calibration.px_to_mm);
  EXPECT_EQ(r.calibration.mm_per_px, m.calibration.mm_per_px);
  EXPECT_EQ(r.calibration.image_width_px, 640);
  EXPECT_EQ(r.calibration.method, m.calibration.method);
  EXPECT_EQ(r.provenance.input, m.provenance.input);
  EXPECT_EQ(r.provenance.program_version, m.provenance.program_version);
  EXPECT_EQ(r.provenance.command_line, m.provenance.command_line);
  EXPECT_EQ(r.provenance.method, m.provenance.method);
  EXPECT_EQ(r.provenance.parameters_json, m.provenance.parameters_json);
  EXPECT_EQ(r.provenance.created_utc, m.provenance.created_utc);
  ASSERT_EQ(r.tracks.size(), m.tracks.size());
  for (std::size_t i = 0; i < m.tracks.size(); ++i) expect_same_point(r.tracks[i], m.tracks[i]);
  ASSERT_EQ(r.frames.size(), m.frames.size());
  for (std::size_t f = 0; f < m.frames.size(); ++f) {
    const auto& a = r.frames[f];
    const auto& b = m.frames[f];
    EXPECT_EQ(a.frame_from, b.frame_from);
    EXPECT_EQ(a.frame_to, b.frame_to);
    EXPECT_EQ(a.t_s, b.t_s);
    ASSERT_EQ(a.points_from.size(), b.points_from.size());
    for (std::size_t i = 0; i < a.points_from.size(); ++i) {
      expect_same_point(a.points_from[i], b.points_from[i]);
      expect_same_point(a.points_to[i], b.points_to[i]);
    }
    ASSERT_EQ(a.edges.size(), b.edges.size());
    for (std::size_t i = 0; i < a.edges.size(); ++i) {
      EXPECT_EQ(a.edges[i].track_a, b.edges[i].track_a);
      EXPECT_EQ(a.edges[i].track_b, b.edges[i].track_b);
      EXPECT_EQ(a.edges[i].length_from_mm, b.edges[i].length_from_mm);
      EXPECT_EQ(a.edges[i].length_to_mm, b.edges[i].length_to_mm);
      EXPECT_EQ(a.edges[i].rel_change, b.edges[i].rel_change);
    }
    ASSERT_EQ(a.triangles.size(), b.triangles.size());
    EXPECT_EQ(a.triangles[0].point_index, b.triangles[0].point_index);
  }
}

TEST(StrainMovieIo, TheContactMapRoundTripsAndAFileWithoutOneReads) {
  TempDir dir;
  const StrainMovie m = sample_movie();
  ASSERT_EQ(m.contact.grid.columns, 11);
  ASSERT_EQ(m.contact.grid.rows, 8);
  write_strain_movie(dir.path() / "m.h5", m);
  const StrainMovie r = read_strain_movie(dir.path() / "m.h5");
  EXPECT_EQ(r.contact.grid.cell_px, 63);
  EXPECT_EQ(r.contact.grid.columns, 11);
  EXPECT_EQ(r.contact.grid.rows, 8);
  EXPECT_EQ(r.contact.threshold, 20);
  EXPECT_EQ(r.contact.ridge_contrast, m.contact.ridge_contrast);
  EXPECT_EQ(r.contact.in_contact, m.contact.in_contact);
  EXPECT_EQ(r.contact.frame_count(), 5);
  {
    H5::H5File f((dir.path() / "m.h5").string(), H5F_ACC_RDWR);
    f.unlink("/contact");
  }
  EXPECT_FALSE(read_strain_movie(dir.path() / "m.h5").contact.measured());
  // A map that does not fit the movie is refused before anything is written.
  StrainMovie short_map = m;
  short_map.contact.in_contact.resize(4 * 88);
  short_map.contact.ridge_contrast.resize(4 * 88);
  EXPECT_THROW(write_strain_movie(dir.path() / "short.h5", short_map), std::invalid_argument);
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "short.h5"));
}

TEST(StrainMovieIo, EmptyMovieRoundTrips) {
  TempDir dir;
  StrainMovie m;
  m.calibration = uniform_calibration(50, 64, 48);
  write_strain_movie(dir.path() / "e.h5", m);
  const StrainMovie r = read_strain_movie(dir.path() / "e.h5");
  EXPECT_TRUE(r.tracks.empty());
  EXPECT_TRUE(r.frames.empty());
}

TEST(StrainMovieIo, CsvExportHasTheDocumentedHeaders) {
  TempDir dir;
  export_strain_csv(dir.path() / "csv", sample_movie());
  std::ifstream t(dir.path() / "csv" / "tracks.csv");
  std::string line;
  std::getline(t, line);
  EXPECT_EQ(line, "track_id,frame,type,x_px,y_px,x_mm,y_mm");
  std::getline(t, line);
  EXPECT_EQ(line, "0,0,pore,0.0000,0.0000,0.000000,0.000000");
  std::ifstream e(dir.path() / "csv" / "edges.csv");
  std::getline(e, line);
  EXPECT_EQ(line, "frame_from,frame_to,track_a,track_b,length_from_mm,length_to_mm,rel_change");
  std::getline(e, line);
  EXPECT_EQ(line, "0,2,0,1,0.200000,0.210000,0.0500000");
  int rows = 1;
  for (; std::getline(e, line);) ++rows;
  EXPECT_EQ(rows, 6);
}

std::string read_error(const std::filesystem::path& p) {
  try {
    read_strain_movie(p);
  } catch (const FormatError& e) {
    return e.what();
  }
  return "no FormatError";
}

TEST(StrainMovieIo, MissingEmptyTruncatedAndTextFilesAreFormatErrors) {
  TempDir dir;
  EXPECT_THAT(read_error(dir.path() / "absent.h5"), HasSubstr("absent.h5"));
  std::ofstream(dir.path() / "empty.h5").close();
  EXPECT_THAT(read_error(dir.path() / "empty.h5"), HasSubstr("empty.h5"));
  std::ofstream(dir.path() / "text.h5") << "frame,x\n1,2\n";
  EXPECT_THAT(read_error(dir.path() / "text.h5"), HasSubstr("text.h5"));
  write_strain_movie(dir.path() / "full.h5", sample_movie());
  const auto size = std::filesystem::file_size(dir.path() / "full.h5");
  std::filesystem::copy_file(dir.path() / "full.h5", dir.path() / "cut.h5");
  std::filesystem::resize_file(dir.path() / "cut.h5", size / 2);
  EXPECT_THAT(read_error(dir.path() / "cut.h5"), HasSubstr("cut.h5"));
}

// Rewrites one dataset of a valid file, then expects the reader to name the problem.
class Tampered : public ::testing::Test {
 protected:
  void SetUp() override { write_strain_movie(path(), sample_movie()); }
  std::filesystem::path path() const { return dir_.path() / "m.h5"; }
  template <typename T>
  void replace(const std::string& group, const std::string& name, const std::vector<T>& data,
               const std::vector<hsize_t>& dims) {
    H5::H5File f(path().string(), H5F_ACC_RDWR);
    H5::Group g = f.openGroup(group);
    g.unlink(name);
    h5::write_dataset(g, name, data, dims);
  }
  TempDir dir_;
};

// Strain movies written before the provenance attributes held what the frames came from as
// `source`, and the writer's version and time unprefixed: they still read, as the provenance's
// input, program version and time (no method, parameters or command line were recorded).
TEST_F(Tampered, OlderFilesWithoutTheProvenanceAttributesAreRead) {
  {
    H5::H5File f(path().string(), H5F_ACC_RDWR);
    H5::Group root = f.openGroup("/");
    for (const char* name :
         {"provenance_input", "provenance_program_version", "provenance_command_line",
          "provenance_method", "provenance_parameters_json", "provenance_created_utc"})
      root.removeAttr(name);
    h5::write_attr(root, "source", "/data/prints/seq1");
    h5::write_attr(root, "program_version", "0.3.0");
    h5::write_attr(root, "created_utc", "2026-10-01T08:00:00Z");
  }
  const StrainMovie m = read_strain_movie(path());
  EXPECT_EQ(m.provenance.input, "/data/prints/seq1");
  EXPECT_EQ(m.provenance.program_version, "0.3.0");
  EXPECT_EQ(m.provenance.created_utc, "2026-10-01T08:00:00Z");
  EXPECT_EQ(m.provenance.method, "");
  EXPECT_EQ(m.provenance.command_line, "");
  EXPECT_EQ(m.frames.size(), 3u);
}

TEST_F(Tampered, OtherFormatIsNamed) {
  {
    H5::H5File f(path().string(), H5F_ACC_RDWR);
    H5::Group root = f.openGroup("/");
    root.removeAttr("format");
    h5::write_attr(root, "format", "tactile-movie");
  }
  EXPECT_THAT(read_error(path()), HasSubstr("format is 'tactile-movie'"));
}

TEST_F(Tampered, MissingGroupIsNamed) {
  {
    H5::H5File f(path().string(), H5F_ACC_RDWR);
    f.unlink("/tracks");
  }
  EXPECT_THAT(read_error(path()), HasSubstr("tracks"));
}

TEST_F(Tampered, FloatWhereIntegersBelongIsNamed) {
  replace<double>("/frames", "frame_from", {0, 1, 2}, {3});
  EXPECT_THAT(read_error(path()), HasSubstr("frame_from"));
}

TEST_F(Tampered, WrongRankIsNamed) {
  replace<double>("/tracks", "position_mm", std::vector<double>(40, 0.0), {40});
  EXPECT_THAT(read_error(path()), HasSubstr("position_mm"));
}

TEST_F(Tampered, InconsistentLengthIsNamed) {
  replace<std::int32_t>("/tracks", "frame", std::vector<std::int32_t>(19, 0), {19});
  EXPECT_THAT(read_error(path()), HasSubstr("/tracks/frame: has 19 rows, expected 20"));
}

TEST_F(Tampered, EdgeNamingAMissingTrackIsNamed) {
  replace<std::int32_t>("/frames", "edge_tracks", {0, 1, 1, 2, 0, 1, 1, 2, 0, 1, 1, 77}, {6, 2});
  EXPECT_THAT(read_error(path()), HasSubstr("edge 5 names track 77, which does not exist"));
}

TEST_F(Tampered, BadOffsetsAreNamed) {
  replace<std::int32_t>("/frames", "edge_offset", {0, 2, 1, 6}, {4});
  EXPECT_THAT(read_error(path()), HasSubstr("edge_offset: decreases"));
}

TEST_F(Tampered, TriangleOutsideItsFrameIsNamed) {
  replace<std::int32_t>("/frames", "triangle_points", {0, 1, 2, 0, 1, 3, 0, 1, 2}, {3, 3});
  EXPECT_THAT(read_error(path()), HasSubstr("triangle 1 uses point 3"));
}

// An edge whose length changed by more than any skin can stretch (or below no length at all)
// is refused naming the dataset, the strain frame, the edge and the range.
TEST_F(Tampered, RelativeChangesNoSkinCanHaveAreNamed) {
  replace<double>("/frames", "edge_rel_change", {0.05, -0.1, 0.05, 1000, 0.05, -0.1}, {6});
  EXPECT_THAT(read_error(path()),
              HasSubstr("/frames/edge_rel_change: strain frame 1 (camera frames 1 to 3): edge 3 "
                        "(tracks 1 and 2) changed its length by 1000, out of range: must be from "
                        "-1 to 10"));
  replace<double>("/frames", "edge_rel_change", {0.05, -0.1, 0.05, -0.1, -1.5, -0.1}, {6});
  EXPECT_THAT(read_error(path()), HasSubstr("strain frame 2 (camera frames 2 to 4): edge 4 "
                                            "(tracks 0 and 1) changed its length by -1.5"));
  // The ends of the range are still measurements.
  replace<double>("/frames", "edge_rel_change", {10, -1, 0.05, -0.1, 0.05, -0.1}, {6});
  EXPECT_EQ(read_strain_movie(path()).frames[0].edges[0].rel_change, 10);
}

// A contact map of another shape than the movie's frames and image, a contrast no 8-bit image
// has, a mark that is neither 0 nor 1 or that disagrees with its contrast: each named with the
// camera frame and the cell.
TEST_F(Tampered, ContactMapsThatDisagreeWithTheMovieOrThemselvesAreNamed) {
  const StrainMovie sample = sample_movie();
  const std::vector<double> contrast = sample.contact.ridge_contrast;
  const std::vector<std::int32_t> marks(sample.contact.in_contact.begin(),
                                        sample.contact.in_contact.end());
  replace<double>("/contact", "ridge_contrast", std::vector<double>(4 * 88, 30.0), {4, 8, 11});
  EXPECT_THAT(read_error(path()), HasSubstr("/contact/ridge_contrast: has shape 4 x 8 x 11, "
                                            "expected 5 x 8 x 11"));
  auto hot = contrast;
  hot[100] = 300;  // frame 1 (88 cells a frame), cell 12: row 1, column 1
  replace<double>("/contact", "ridge_contrast", hot, {5, 8, 11});
  EXPECT_THAT(read_error(path()),
              HasSubstr("camera frame 1, cell row 1, column 1: ridge contrast 300 is out of "
                        "range: must be from 0 to 255 grey levels"));
  replace<double>("/contact", "ridge_contrast", contrast, {5, 8, 11});
  auto two = marks;
  two[5] = 2;
  replace<std::int32_t>("/contact", "in_contact", two, {5, 8, 11});
  EXPECT_THAT(read_error(path()),
              HasSubstr("camera frame 0, cell row 0, column 5: 2 is neither 0 (no contact) nor "
                        "1 (contact)"));
  auto flipped = marks;
  flipped[0] = 1;  // contrast 0
  replace<std::int32_t>("/contact", "in_contact", flipped, {5, 8, 11});
  EXPECT_THAT(read_error(path()), HasSubstr("marked in contact but its ridge contrast 0 is below "
                                            "the threshold 20"));
  replace<std::int32_t>("/contact", "in_contact", marks, {5, 8, 11});
  EXPECT_EQ(read_strain_movie(path()).contact.frame_count(), 5);
  for (const double bad : {-1.0, 300.0, std::nan("")}) {
    {
      H5::H5File f(path().string(), H5F_ACC_RDWR);
      H5::Group g = f.openGroup("/contact");
      g.removeAttr("threshold");
      h5::write_attr(g, "threshold", bad);
    }
    EXPECT_THAT(read_error(path()), HasSubstr("threshold")) << bad;
  }
}

// A map judged frame by frame (a live session's): thresholds and seen flags round-trip; a seen
// flag other than 0 or 1, an unseen frame whose cells say something, a mark that disagrees with
// its own frame's threshold, a threshold per frame beside the whole map's or one per frame too
// few: each named.
TEST_F(Tampered, AContactMapJudgedFrameByFrameRoundTripsAndItsFlagsAreChecked) {
  StrainMovie m = sample_movie();
  ContactMap& c = m.contact;
  c.frame_threshold = {20, 20, 30, 0, 20};
  c.frame_seen = {1, 1, 1, 0, 1};
  for (std::size_t i = 0; i < c.in_contact.size(); ++i) {
    const std::size_t frame = i / 88;
    if (frame == 3) c.ridge_contrast[i] = 0;
    c.in_contact[i] =
        c.frame_seen[frame] && c.ridge_contrast[i] >= c.frame_threshold[frame] ? 1 : 0;
  }
  write_strain_movie(path(), m);
  const StrainMovie r = read_strain_movie(path());
  EXPECT_EQ(r.contact.frame_threshold, c.frame_threshold);
  EXPECT_EQ(r.contact.frame_seen, c.frame_seen);
  EXPECT_EQ(r.contact.in_contact, c.in_contact);
  EXPECT_FALSE(r.contact.seen(3));

  replace<std::int32_t>("/contact", "seen", {1, 1, 1, 2, 1}, {5});
  EXPECT_THAT(read_error(path()),
              HasSubstr("/contact/seen: camera frame 3: 2 is neither 0 (dropped unseen) nor 1"));
  replace<std::int32_t>("/contact", "seen", {1, 1, 1, 0}, {4});
  EXPECT_THAT(read_error(path()),
              HasSubstr("/contact/seen: has 4 values, expected one per camera frame (5)"));
  replace<std::int32_t>("/contact", "seen", {1, 1, 0, 0, 1}, {5});
  EXPECT_THAT(read_error(path()),
              HasSubstr("camera frame 2, cell row 0, column 0: the frame is marked unseen, but "
                        "the cell has contrast 16"));
  replace<std::int32_t>("/contact", "seen", {1, 1, 1, 0, 1}, {5});
  // Frame 2 (cells 176 on, contrast i % 40) judged by 20 instead of its own 30: its cell 4 of
  // contrast 20 is marked out of contact.
  replace<double>("/contact", "frame_threshold", {20, 20, 20, 0, 20}, {5});
  EXPECT_THAT(read_error(path()),
              HasSubstr("camera frame 2, cell row 0, column 4: marked out of contact but its "
                        "ridge contrast 20 is at or above the threshold 20"));
  replace<double>("/contact", "frame_threshold", {20, 20, 30, 0, 256}, {5});
  EXPECT_THAT(read_error(path()),
              HasSubstr("camera frame 4: threshold 256 is out of range: must be from 0 to 255"));
  replace<double>("/contact", "frame_threshold", c.frame_threshold, {5});
  EXPECT_EQ(read_strain_movie(path()).contact.frame_count(), 5);
  {
    H5::H5File f(path().string(), H5F_ACC_RDWR);
    H5::Group g = f.openGroup("/contact");
    h5::write_attr(g, "threshold", 20.0);
  }
  EXPECT_THAT(read_error(path()), HasSubstr("has both a `threshold` attribute and a "
                                            "`frame_threshold` dataset"));
}

// Every numeric attribute, every hostile value: refused, naming the file and the attribute.
TEST_F(Tampered, HostileNumbersInEveryAttributeAreNamed) {
  const std::vector<std::pair<std::string, std::string>> doubles = {{"/", "frame_rate_hz"},
                                                                    {"/", "field_width_mm"},
                                                                    {"/", "field_height_mm"},
                                                                    {"/calibration", "mm_per_px"}};
  const auto original = tactile::testing::file_bytes(path());
  for (const auto& [group, name] : doubles) {
    for (double v : tactile::testing::hostile_doubles()) {
      tactile::testing::write_bytes(path(), original);
      {
        H5::H5File f(path().string(), H5F_ACC_RDWR);
        H5::Group g = f.openGroup(group);
        tactile::testing::set_attr(g, name, v);
      }
      const std::string e = read_error(path());
      EXPECT_THAT(e, HasSubstr("m.h5")) << name << " = " << v;
      EXPECT_THAT(e, HasSubstr(name)) << name << " = " << v;
    }
  }
  const std::vector<std::pair<std::string, std::string>> ints = {
      {"/", "span_frames"},
      {"/", "camera_frame_count"},
      {"/calibration", "image_width_px"},
      {"/calibration", "image_height_px"}};
  for (const auto& [group, name] : ints) {
    for (std::int64_t v : tactile::testing::hostile_ints()) {
      tactile::testing::write_bytes(path(), original);
      {
        H5::H5File f(path().string(), H5F_ACC_RDWR);
        H5::Group g = f.openGroup(group);
        tactile::testing::set_attr(g, name, v);
      }
      EXPECT_THAT(read_error(path()), HasSubstr(name)) << name << " = " << v;
    }
  }
}

TEST_F(Tampered, MissingOrMistypedAttributesAreNamed) {
  const auto original = tactile::testing::file_bytes(path());
  for (const char* name : {"frame_rate_hz", "span_frames", "camera_frame_count", "field_width_mm",
                           "field_height_mm"}) {
    tactile::testing::write_bytes(path(), original);
    {
      H5::H5File f(path().string(), H5F_ACC_RDWR);
      H5::Group root = f.openGroup("/");
      root.removeAttr(name);
    }
    EXPECT_THAT(read_error(path()), HasSubstr(std::string("'") + name + "' is missing"));
    tactile::testing::write_bytes(path(), original);
    {
      H5::H5File f(path().string(), H5F_ACC_RDWR);
      H5::Group root = f.openGroup("/");
      tactile::testing::set_attr(root, name, std::string("60"));
    }
    EXPECT_THAT(read_error(path()), HasSubstr(name));
  }
}

// A NaN or infinity anywhere in any floating-point dataset, and a zero or NaN calibration.
TEST_F(Tampered, NonFiniteValuesInEveryDatasetAreNamed) {
  const auto original = tactile::testing::file_bytes(path());
  for (const char* name :
       {"/tracks/position_px", "/tracks/position_mm", "/frames/t_s", "/frames/point_position_px",
        "/frames/point_position_mm", "/frames/point_to_position_px", "/frames/point_to_position_mm",
        "/frames/edge_length_mm", "/frames/edge_rel_change", "/calibration/px_to_mm"}) {
    for (double v : {std::nan(""), std::numeric_limits<double>::infinity()}) {
      tactile::testing::write_bytes(path(), original);
      {
        H5::H5File f(path().string(), H5F_ACC_RDWR);
        H5::DataSet ds = f.openDataSet(name);
        std::vector<double> data(static_cast<std::size_t>(ds.getSpace().getSimpleExtentNpoints()));
        ds.read(data.data(), H5::PredType::NATIVE_DOUBLE);
        data[data.size() / 2] = v;
        ds.write(data.data(), H5::PredType::NATIVE_DOUBLE);
      }
      const std::string leaf = std::string(name).substr(std::string(name).rfind('/') + 1);
      EXPECT_THAT(read_error(path()), HasSubstr(leaf)) << name << " = " << v;
    }
  }
  tactile::testing::write_bytes(path(), original);
  replace<double>("/calibration", "px_to_mm", std::vector<double>(9, 0.0), {3, 3});
  EXPECT_THAT(read_error(path()), HasSubstr("px_to_mm"));
}

// Declared sizes beyond memory fail at once with the limit, never in the allocator.
TEST_F(Tampered, HugeDeclaredSizesNameTheLimitQuickly) {
  const auto original = tactile::testing::file_bytes(path());
  for (const char* name : {"frame_from", "edge_rel_change", "point_track_id"}) {
    tactile::testing::write_bytes(path(), original);
    {
      H5::H5File f(path().string(), H5F_ACC_RDWR);
      H5::Group g = f.openGroup("/frames");
      const bool ints = std::string(name) != "edge_rel_change";
      tactile::testing::set_huge_dataset(
          g, name, {hsize_t{2000000000000}},
          ints ? H5::PredType::NATIVE_INT32 : H5::PredType::NATIVE_DOUBLE);
    }
    const auto t0 = std::chrono::steady_clock::now();
    const std::string e = read_error(path());
    EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(2)) << name;
    EXPECT_THAT(e, HasSubstr(name));
    EXPECT_THAT(e, HasSubstr("more than the limit of"));
  }
}

// Found by the reader fuzzer: one byte makes /frames/point_type declare about 2 GB of values the
// file does not hold (tests/data/damaged-movies/README.md). Refused before they are allocated.
TEST(StrainMovieIo, DatasetDeclaringMoreThanTheFileHoldsIsRefusedQuickly) {
  const auto path = std::filesystem::path(TACTILE_TEST_DATA_DIR) / "damaged-movies" /
                    "strain-oversized-dataset.h5";
  const auto t0 = std::chrono::steady_clock::now();
  const std::string e = read_error(path);
  EXPECT_LT(std::chrono::steady_clock::now() - t0, std::chrono::seconds(5));
  EXPECT_THAT(e, HasSubstr("strain-oversized-dataset.h5:/frames/point_type"));
  EXPECT_THAT(e, HasSubstr("but the file stores"));
}

// Cut at every eighth, filled with random bytes, or with bytes scrambled: a FormatError naming
// the file, or (a scramble that left the data readable) a movie; never a crash.
TEST(StrainMovieIo, CutRandomAndScrambledFilesAreFormatErrors) {
  TempDir dir;
  write_strain_movie(dir.path() / "full.h5", sample_movie());
  const auto full = tactile::testing::file_bytes(dir.path() / "full.h5");
  const auto bad = dir.path() / "bad.h5";
  for (std::size_t eighth = 1; eighth < 8; ++eighth) {
    tactile::testing::write_bytes(
        bad, std::vector<char>(full.begin(),
                               full.begin() + static_cast<long>(full.size() * eighth / 8)));
    EXPECT_THAT(read_error(bad), HasSubstr("bad.h5")) << eighth << "/8";
  }
  for (std::uint32_t seed = 1; seed <= 20; ++seed) {
    tactile::testing::write_bytes(bad, tactile::testing::random_bytes(seed, 64 * seed));
    EXPECT_THAT(read_error(bad), HasSubstr("bad.h5")) << "random seed " << seed;
    tactile::testing::write_bytes(bad, tactile::testing::scrambled(full, seed, 4));
    try {
      read_strain_movie(bad);
    } catch (const FormatError& e) {
      EXPECT_THAT(e.what(), HasSubstr("bad.h5")) << "scramble seed " << seed;
    }
  }
}

}  // namespace
}  // namespace tactile::capture
