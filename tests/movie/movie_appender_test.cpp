// A movie written as it grows: read back whole when closed, and up to its last flush when the
// writing process is killed.

#include <gtest/gtest.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <vector>

#include "../common/temp_dir.hpp"
#include "tactile/movie/movie_io.hpp"
#include "test_movies.hpp"

namespace tactile::movie {
namespace {

std::vector<float> frame_of(const TactileMovie& m, std::int32_t f) {
  const auto n = static_cast<std::size_t>(m.layout.contactor_count());
  const auto begin = m.deflection_um.begin() + static_cast<std::ptrdiff_t>(f * n);
  return {begin, begin + static_cast<std::ptrdiff_t>(n)};
}

TEST(MovieAppender, ClosedFileHoldsEveryFrame) {
  tactile::test::TempDir dir;
  const TactileMovie m = testing::sine_movie(stress_layout(), 400, 25, 50);
  TactileMovieAppender out(dir.path() / "m.h5", m);
  for (std::int32_t f = 0; f < m.frame_count; ++f) {
    out.append(frame_of(m, f));
    if (f % 7 == 0) out.flush();
  }
  out.close();
  const TactileMovie r = read_tactile_movie(dir.path() / "m.h5");
  EXPECT_EQ(r.frame_count, m.frame_count);
  EXPECT_EQ(r.rate_hz, m.rate_hz);
  EXPECT_EQ(r.layout.name, m.layout.name);
  EXPECT_EQ(r.deflection_um, m.deflection_um);
}

// The child writes 10 frames, flushes, writes 5 more and is killed: the file holds the 10.
TEST(MovieAppender, KilledWriterLeavesWhatWasFlushed) {
  tactile::test::TempDir dir;
  const TactileMovie m = testing::sine_movie(stress_layout(), 400, 15, 50);
  const auto path = dir.path() / "killed.h5";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    TactileMovieAppender out(path, m);
    for (std::int32_t f = 0; f < 15; ++f) {
      out.append(frame_of(m, f));
      if (f == 9) out.flush();
    }
    ::kill(::getpid(), SIGKILL);
    ::_exit(1);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFSIGNALED(status));
  ASSERT_EQ(WTERMSIG(status), SIGKILL);
  const TactileMovie r = read_tactile_movie(path);
  ASSERT_EQ(r.frame_count, 10);
  for (std::int32_t f = 0; f < 10; ++f) EXPECT_EQ(frame_of(r, f), frame_of(m, f)) << f;
}

TEST(MovieAppender, NeverOverwritesOrFollowsALink) {
  tactile::test::TempDir dir;
  const TactileMovie m = testing::sine_movie(stress_layout(), 400, 1, 50);
  const auto existing = dir.path() / "existing.h5";
  std::ofstream(existing) << "kept";
  EXPECT_THROW(TactileMovieAppender(existing, m), std::runtime_error);
  std::ifstream in(existing);
  std::string content;
  in >> content;
  EXPECT_EQ(content, "kept");
  const auto target = dir.path() / "target.h5";
  std::filesystem::create_symlink(target, dir.path() / "link.h5");
  EXPECT_THROW(TactileMovieAppender(dir.path() / "link.h5", m), std::runtime_error);
  EXPECT_FALSE(std::filesystem::exists(target));
}

}  // namespace
}  // namespace tactile::movie
