// A strain movie written as it is measured: read back whole when closed, and up to its last
// flush when the writing process is killed.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <set>
#include <tuple>

#include "tactile/capture/strain_movie_io.hpp"
#include "test_util.hpp"

namespace tactile::capture {
namespace {

using testing::TempDir;

// Four tracks over six frames, strain frames of span 1, each with its points, two edges and a
// triangle; track 3 starts at frame 2 (a detection during the movie).
StrainMovie sample_movie() {
  StrainMovie m;
  m.frame_rate_hz = 60;
  m.span_frames = 1;
  m.camera_frame_count = 6;
  m.calibration = uniform_calibration(47, 320, 240);
  m.field_width_mm = 320 / 47.0;
  m.field_height_mm = 240 / 47.0;
  m.provenance.method = "live";
  const auto point = [](std::int32_t id, std::int32_t f) {
    return TrackedPoint{id,      f, FeatureType::pore, 10.0 * id + f, 5.0 * id, 0.2 * id + 0.01 * f,
                        0.1 * id};
  };
  for (std::int32_t f = 0; f + 1 < 6; ++f) {
    StrainFrame sf;
    sf.frame_from = f;
    sf.frame_to = f + 1;
    sf.t_s = (f + 1) / 60.0;
    for (std::int32_t id = 0; id < (f >= 2 ? 4 : 3); ++id) {
      sf.points_from.push_back(point(id, f));
      sf.points_to.push_back(point(id, f + 1));
    }
    sf.edges.push_back({0, 1, 0.2, 0.21, 0.05});
    sf.edges.push_back({1, 2, 0.3, 0.27, -0.1 * f});
    sf.triangles.push_back({{0, 1, 2}});
    m.frames.push_back(sf);
  }
  return m;
}

using PointKey = std::tuple<std::int32_t, std::int32_t, double, double>;

std::set<PointKey> point_set(const std::vector<TrackedPoint>& points) {
  std::set<PointKey> out;
  for (const auto& p : points) out.insert({p.track_id, p.frame, p.x_px, p.y_px});
  return out;
}

void expect_same_frames(const StrainMovie& read, const StrainMovie& written, std::size_t frames) {
  ASSERT_EQ(read.frames.size(), frames);
  for (std::size_t f = 0; f < frames; ++f) {
    const auto& a = read.frames[f];
    const auto& b = written.frames[f];
    EXPECT_EQ(a.frame_from, b.frame_from);
    EXPECT_EQ(a.t_s, b.t_s);
    EXPECT_EQ(point_set(a.points_from), point_set(b.points_from));
    EXPECT_EQ(point_set(a.points_to), point_set(b.points_to));
    ASSERT_EQ(a.edges.size(), b.edges.size());
    for (std::size_t i = 0; i < a.edges.size(); ++i) {
      EXPECT_EQ(a.edges[i].rel_change, b.edges[i].rel_change);
    }
    EXPECT_EQ(a.triangles.size(), b.triangles.size());
  }
}

TEST(StrainMovieAppender, ClosedFileHoldsWhatTheBatchWriterWrites) {
  TempDir dir;
  const StrainMovie m = sample_movie();
  StrainMovieAppender out(dir.path() / "grown.h5", m);
  std::size_t new_points = 0;
  for (const auto& f : m.frames) {
    new_points += out.append(f).size();
    out.flush();
  }
  out.close();
  const StrainMovie r = read_strain_movie(dir.path() / "grown.h5");
  EXPECT_EQ(r.camera_frame_count, 6);
  expect_same_frames(r, m, m.frames.size());
  // Every point of every track once: tracks 0-2 in frames 0-5, track 3 in frames 2-5.
  std::set<PointKey> expected;
  for (const auto& f : m.frames) {
    for (const auto& p : point_set(f.points_from)) expected.insert(p);
    for (const auto& p : point_set(f.points_to)) expected.insert(p);
  }
  EXPECT_EQ(expected.size(), 3u * 6u + 4u);
  EXPECT_EQ(new_points, expected.size());
  EXPECT_EQ(r.tracks.size(), expected.size());
  EXPECT_EQ(point_set(r.tracks), expected);
}

// A session that dropped camera frame 3 measured 2 -> 4: a strain frame of span 2 in a movie of
// span 1, left out of the file and counted; the others are kept in order.
TEST(StrainMovieAppender, AFrameOfAnotherSpanIsLeftOutAndCounted) {
  TempDir dir;
  const StrainMovie m = sample_movie();
  StrainMovieAppender out(dir.path() / "gap.h5", m);
  StrainFrame across = m.frames[2];
  across.frame_to = 4;
  for (auto& p : across.points_to) p.frame = 4;
  out.append(m.frames[0]);
  out.append(m.frames[1]);
  EXPECT_EQ(out.frames_left_out(), 0);
  out.append(across);
  EXPECT_EQ(out.frames_left_out(), 1);
  out.append(m.frames[4]);
  out.close();
  const StrainMovie r = read_strain_movie(dir.path() / "gap.h5");
  ASSERT_EQ(r.frames.size(), 3u);
  EXPECT_EQ(r.frames[0].frame_from, 0);
  EXPECT_EQ(r.frames[1].frame_from, 1);
  EXPECT_EQ(r.frames[2].frame_from, 4);
}

// Whether a child that writes `path` with `header` by `write` and is then killed by SIGKILL
// died of it.
template <typename Write>
bool killed_while_writing(const std::filesystem::path& path, const StrainMovie& header,
                          Write write) {
  const pid_t child = ::fork();
  if (child < 0) return false;
  if (child == 0) {
    StrainMovieAppender out(path, header);
    write(out);
    ::kill(::getpid(), SIGKILL);
    ::_exit(1);
  }
  int status = 0;
  return ::waitpid(child, &status, 0) == child && WIFSIGNALED(status) &&
         WTERMSIG(status) == SIGKILL;
}

// The child appends three strain frames, flushes, appends two more and is killed.
TEST(StrainMovieAppender, KilledWriterLeavesWhatWasFlushed) {
  TempDir dir;
  const StrainMovie m = sample_movie();
  const auto path = dir.path() / "killed.h5";
  ASSERT_TRUE(killed_while_writing(path, m, [&](StrainMovieAppender& out) {
    for (std::size_t f = 0; f < m.frames.size(); ++f) {
      out.append(m.frames[f]);
      if (f == 2) out.flush();
    }
  }));
  const StrainMovie r = read_strain_movie(path);
  expect_same_frames(r, m, 3);
  EXPECT_EQ(r.camera_frame_count, 4);
}

// Cells of 47 px over 320 x 240 px: 7 columns, 6 rows. Frame f's cell i has contrast f + i / 2,
// judged by threshold 10 + f.
constexpr int kCells = 42;
std::vector<double> frame_contrast(int frame) {
  std::vector<double> c;
  for (int i = 0; i < kCells; ++i) c.push_back(frame + i / 2.0);
  return c;
}
std::vector<std::uint8_t> judged(const std::vector<double>& contrast, double threshold) {
  std::vector<std::uint8_t> in;
  for (const double c : contrast) in.push_back(c >= threshold ? 1 : 0);
  return in;
}
void append_frame_contact(StrainMovieAppender& out, int frame) {
  out.append_contact(frame, 10 + frame, frame_contrast(frame),
                     judged(frame_contrast(frame), 10 + frame));
}

// A live session reports a dropped frame when it next looks at its queue, so frame 3's "unseen"
// comes before frame 2's contact; frame 5 is never reported (the session ended). The file holds
// every camera frame in order: 3 and 5 unseen, with cells of 0.
TEST(StrainMovieAppender, TheContactOfFramesAsTheyComeIsWrittenInOrderWithDroppedFramesUnseen) {
  TempDir dir;
  StrainMovie m = sample_movie();
  m.contact.grid = contact_grid(320, 240, 47);
  ASSERT_EQ(m.contact.grid.cells(), kCells);
  StrainMovieAppender out(dir.path() / "contact.h5", m);
  append_frame_contact(out, 0);
  append_frame_contact(out, 1);
  out.append_unseen(3);
  out.flush();
  append_frame_contact(out, 2);
  append_frame_contact(out, 4);
  for (const auto& f : m.frames) out.append(f);
  out.close();
  const StrainMovie r = read_strain_movie(dir.path() / "contact.h5");
  ASSERT_TRUE(r.contact.per_frame());
  EXPECT_EQ(r.camera_frame_count, 6);
  ASSERT_EQ(r.contact.frame_count(), 6);
  EXPECT_EQ(r.contact.frame_seen, (std::vector<std::uint8_t>{1, 1, 1, 0, 1, 0}));
  for (int f = 0; f < 6; ++f) {
    SCOPED_TRACE(f);
    const auto at = r.contact.ridge_contrast.begin() + f * kCells;
    const std::vector<double> contrast(at, at + kCells);
    const auto marks_at = r.contact.in_contact.begin() + f * kCells;
    const std::vector<std::uint8_t> marks(marks_at, marks_at + kCells);
    if (f == 3 || f == 5) {
      EXPECT_FALSE(r.contact.seen(f));
      EXPECT_EQ(contrast, std::vector<double>(kCells, 0.0));
      EXPECT_EQ(marks, std::vector<std::uint8_t>(kCells, 0));
    } else {
      EXPECT_TRUE(r.contact.seen(f));
      EXPECT_EQ(r.contact.frame_threshold[static_cast<std::size_t>(f)], 10 + f);
      EXPECT_EQ(contrast, frame_contrast(f));
      EXPECT_EQ(marks, judged(frame_contrast(f), 10 + f));
    }
  }
}

// Killed after frames 0-2's contact was flushed and 3-4's was not: the file opens with frames
// 0-2 seen as written and every later camera frame of the movie unseen.
TEST(StrainMovieAppender, KilledWriterLeavesTheContactItFlushed) {
  TempDir dir;
  StrainMovie m = sample_movie();
  m.contact.grid = contact_grid(320, 240, 47);
  const auto path = dir.path() / "killed.h5";
  ASSERT_TRUE(killed_while_writing(path, m, [&](StrainMovieAppender& out) {
    for (int f = 0; f < 3; ++f) append_frame_contact(out, f);
    for (std::size_t f = 0; f < 3; ++f) out.append(m.frames[f]);
    out.flush();
    for (int f = 3; f < 5; ++f) append_frame_contact(out, f);
    out.append(m.frames[3]);
  }));
  const StrainMovie r = read_strain_movie(path);
  EXPECT_EQ(r.camera_frame_count, 4);
  ASSERT_EQ(r.contact.frame_count(), r.camera_frame_count);
  for (int f = 0; f < 3; ++f) {
    EXPECT_TRUE(r.contact.seen(f)) << f;
    const auto at = r.contact.ridge_contrast.begin() + f * kCells;
    EXPECT_EQ(std::vector<double>(at, at + kCells), frame_contrast(f)) << f;
  }
  EXPECT_FALSE(r.contact.seen(3));
}

}  // namespace
}  // namespace tactile::capture
