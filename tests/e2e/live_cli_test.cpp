// `tactile live` on a real print moved by an exact warp and played at its frame rate, as a
// camera would deliver it: every frame accounted for (processed or dropped), the latency of
// each written, the recording readable after the end, after Ctrl-C and after SIGKILL, and the
// live strain measured against the warp's truth beside the batch capture of the same frames.

#include <fmt/format.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <arpa/inet.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/capture/capture_run.hpp"
#include "tactile/capture/contact_map.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/capture/video.hpp"
#include "tactile/movie/movie_io.hpp"

namespace {

namespace fs = std::filesystem;
using tactile::test::run_tactile;
using tactile::test::test_data;
using ::testing::HasSubstr;

std::vector<std::vector<std::string>> csv_rows(const fs::path& path) {
  std::ifstream in(path);
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> fields;
    std::stringstream s(line);
    std::string field;
    while (std::getline(s, field, ',')) fields.push_back(field);
    if (!line.empty() && line.back() == ',') fields.emplace_back();
    rows.push_back(fields);
  }
  return rows;
}

// The number that follows `label` (and spaces) in `text`; NaN when there is none.
double number_after(const std::string& text, const std::string& label) {
  const std::size_t at = text.find(label);
  if (at == std::string::npos) return NAN;
  const char* start = text.c_str() + at + label.size();
  char* end = nullptr;
  const double v = std::strtod(start, &end);
  return end == start ? NAN : v;
}

// The moment `text` first appears in the file `log`, polled every 10 ms for at most `limit_s`.
std::optional<std::chrono::steady_clock::time_point> wait_for_text(const fs::path& log,
                                                                   const std::string& text,
                                                                   double limit_s) {
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::duration<double>(limit_s);
  while (std::chrono::steady_clock::now() < give_up) {
    std::ifstream in(log);
    std::stringstream content;
    content << in.rdbuf();
    if (content.str().find(text) != std::string::npos) return std::chrono::steady_clock::now();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  return std::nullopt;
}

class Live : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    dir_ = new tactile::test::TempDir("live");
    // Held-out print 12 under a travelling wave, 60 frames at 60 Hz: a second of skin.
    const auto r = run_tactile("synth " + (dir_->path() / "wave").string() + " --from-print " +
                               (test_data("polyu-hrf-pores") / "image_12.jpg").string() +
                               " --px-per-mm 47 --warp wave --frames 60");
    ASSERT_EQ(r.exit_code, 0) << r.output;
  }
  static void TearDownTestSuite() {
    delete dir_;
    dir_ = nullptr;
  }
  static fs::path frames() { return dir_->path() / "wave"; }
  static tactile::test::TempDir* dir_;
};
tactile::test::TempDir* Live::dir_ = nullptr;

TEST_F(Live, EveryFrameIsAccountedForAndRecorded) {
  const fs::path record = dir_->path() / "session";
  // At 10 Hz with room for 3 s of frames, nothing is dropped even on a slow (sanitizer) build
  // while the first frame chooses the pore detector.
  const auto r = run_tactile("live " + frames().string() +
                             " --px-per-mm 47 --rate-hz 10 --queue-frames 30 --headless --record " +
                             record.string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("60 in, 60 processed, 0 dropped"));
  EXPECT_THAT(r.output, HasSubstr("latency     p50"));
  EXPECT_THAT(r.output, HasSubstr("the emulated device's outputs ended at most 0 um from rest"));
  const auto latency = csv_rows(record / "latency.csv");
  ASSERT_EQ(latency.size(), 61u);
  EXPECT_EQ(latency[0],
            (std::vector<std::string>{"frame", "source_time_s", "latency_ms", "dropped"}));
  for (std::size_t i = 1; i < latency.size(); ++i) {
    ASSERT_EQ(latency[i].size(), 4u) << i;
    EXPECT_EQ(std::stoi(latency[i][0]), static_cast<int>(i - 1));
    EXPECT_EQ(latency[i][3], "0");
    const double ms = std::stod(latency[i][2]);
    // A latency beyond the queue's 3 s would be a queue that grows.
    EXPECT_GT(ms, 0);
    EXPECT_LT(ms, 3000);
  }
  const auto strain = tactile::capture::read_strain_movie(record / "strain.h5");
  EXPECT_EQ(strain.camera_frame_count, 60);
  EXPECT_EQ(strain.frames.size(), 59u);
  for (const auto& f : strain.frames) EXPECT_GT(f.edges.size(), 100u) << f.frame_to;
  const auto movie = tactile::movie::read_tactile_movie(record / "movie.h5");
  EXPECT_EQ(movie.layout.name, "stress");
  EXPECT_EQ(movie.rate_hz, 700);
  // 60 camera frames at 10 Hz are 6 s of display frames.
  EXPECT_EQ(movie.frame_count, 4200);
  // frames.mkv holds every frame as received, lossless: the same pixels as the source.
  tactile::capture::VideoReader video(record / "frames.mkv");
  EXPECT_EQ(video.info().frame_count, 60);
  tactile::capture::FrameRange source(frames(), 0, std::nullopt);
  tactile::capture::GrayImage recorded, original;
  int compared = 0;
  while (source.next(original)) {
    ASSERT_TRUE(video.read(recorded)) << compared;
    EXPECT_EQ(recorded.width_px, original.width_px);
    EXPECT_TRUE(recorded.pixels == original.pixels) << "frame " << compared;
    ++compared;
  }
  EXPECT_EQ(compared, 60);
  // The contact map holds every camera frame, each row measured on its own frame: the cells'
  // contrast as the batch capture measures them, judged by a threshold that only grows (the
  // contrast of skin in contact seen so far), never under the floor of camera noise.
  const tactile::capture::ContactMap& contact = strain.contact;
  ASSERT_TRUE(contact.per_frame());
  ASSERT_EQ(contact.frame_count(), 60);
  EXPECT_EQ(contact.frame_seen, std::vector<std::uint8_t>(60, 1));
  tactile::capture::FrameRange again(frames(), 0, std::nullopt);
  const auto cells = static_cast<std::size_t>(contact.grid.cells());
  for (std::size_t f = 0; again.next(original); ++f) {
    const std::vector<double> expected =
        tactile::capture::cell_ridge_contrast(original, contact.grid, 47);
    const auto at = contact.ridge_contrast.begin() + static_cast<std::ptrdiff_t>(f * cells);
    EXPECT_TRUE(std::equal(expected.begin(), expected.end(), at)) << "frame " << f;
    EXPECT_GE(contact.frame_threshold[f], tactile::capture::kContactFloorGrey) << f;
    if (f > 0) {
      EXPECT_GE(contact.frame_threshold[f], contact.frame_threshold[f - 1]) << f;
    }
  }
  // The edges.csv rows are the strain movie's edges.
  std::size_t edges = 0;
  for (const auto& f : strain.frames) edges += f.edges.size();
  EXPECT_EQ(csv_rows(record / "edges.csv").size(), edges + 1);
}

TEST_F(Live, StrainAgainstTheTruthBesideTheBatchCapture) {
  const fs::path record = dir_->path() / "truth";
  const auto live = run_tactile(
      "live " + frames().string() +
      " --px-per-mm 47 --rate-hz 10 --queue-frames 30 --headless --record " + record.string());
  ASSERT_EQ(live.exit_code, 0) << live.output;
  const auto live_eval =
      run_tactile("evaluate " + frames().string() + " " + (record / "strain.h5").string());
  ASSERT_EQ(live_eval.exit_code, 0) << live_eval.output;
  const auto batch = run_tactile("capture " + frames().string() + " --px-per-mm 47 --out " +
                                 (dir_->path() / "batch.h5").string());
  ASSERT_EQ(batch.exit_code, 0) << batch.output;
  const auto batch_eval =
      run_tactile("evaluate " + frames().string() + " " + (dir_->path() / "batch.h5").string());
  const double live_rms = number_after(live_eval.output, "edge strain RMS error");
  const double batch_rms = number_after(batch_eval.output, "edge strain RMS error");
  const double live_r = number_after(live_eval.output, "correlation with truth");
  std::cout << "live: RMS error " << live_rms << ", correlation " << live_r
            << "; batch capture: RMS error " << batch_rms << "\n";
  EXPECT_TRUE(std::isfinite(live_rms) && std::isfinite(batch_rms));
  // Causal, the live strain is noisier than the batch capture's, which smooths each track over
  // up to 33 frames around each one (measured here: RMS error 0.00091 against 0.00014,
  // correlation 0.815 against 0.995, the frames being the same every run; 0.00059 and 0.922
  // once each frame's steps were smoothed across the skin). The bounds keep that margin and
  // fail a tracker that lost the skin (correlation near 0).
  EXPECT_GT(live_r, 0.75);
  EXPECT_LT(live_rms, 10 * batch_rms);
}

// A print of the held-out set sliding through the view at 25 mm/s for 40 frames (`synth` with
// `extra` added), played live at 10 Hz into the emulated display and recorded (the frames are
// rendered for 60 Hz; at 10 Hz a slow build drops none), and the recording's strain evaluated
// against the exact warp. Asserts that each step ran and that every frame was processed.
struct SlipSession {
  std::string live, eval;
  double rms = NAN, r = NAN;
};
SlipSession live_full_slip(const fs::path& dir, const std::string& print, const std::string& extra,
                           int speed_mm_per_s = 25) {
  const fs::path seq =
      dir / fmt::format("slip{}at{}{}", print, speed_mm_per_s, extra.empty() ? "" : "-more");
  const fs::path record = seq.string() + "-rec";
  const auto synth =
      run_tactile("synth " + seq.string() + " --from-print " +
                  (test_data("polyu-hrf-pores") / fmt::format("image_{}.jpg", print)).string() +
                  fmt::format(" --px-per-mm 47 --warp full-slip --travel-speed {} --frames 40 ",
                              speed_mm_per_s) +
                  extra);
  EXPECT_EQ(synth.exit_code, 0) << synth.output;
  const auto live = run_tactile("live " + seq.string() +
                                " --px-per-mm 47 --rate-hz 10 --queue-frames 30 --headless "
                                "--record " +
                                record.string());
  EXPECT_EQ(live.exit_code, 0) << live.output;
  EXPECT_THAT(live.output, HasSubstr("40 in, 40 processed, 0 dropped"));
  const auto eval = run_tactile("evaluate " + seq.string() + " " + (record / "strain.h5").string());
  EXPECT_EQ(eval.exit_code, 0) << eval.output;
  return {live.output, eval.output, number_after(eval.output, "edge strain RMS error"),
          number_after(eval.output, "correlation with truth")};
}

// Skin sliding through the view (full slip at 25 mm/s, 20 px a frame): the live session, frame
// by frame, keeps tracks as short as the skin stays in view and measures the strain field the
// skin crosses. Held-out prints 13 and 15, nothing tuned on them. Measured here as this test
// plays them (10 Hz; twice, the same figures): RMS error 0.00111 and 0.00116, correlation 0.957
// and 0.953 (at 60 Hz 0.959 and 0.958, 264 and 254 points a frame; the batch capture of the same
// frames: 0.00085 / 0.974 and 0.00083 / 0.975); since the session corrects the windows' curvature
// bias (one fit per track, kept), blends in their deformation and smooths each track looking
// back: 0.00117 / 0.955 and 0.00108 / 0.960. The bounds are the batch capture's full-slip
// bars for error and points, and a correlation that a lost track would not reach.
TEST_F(Live, FullSlipFrameByFrameOnHeldOutPrints) {
  for (const char* print : {"13", "15"}) {
    SCOPED_TRACE(print);
    const SlipSession s = live_full_slip(dir_->path(), print, "");
    EXPECT_GE(number_after(s.live, "; median "), 150) << s.live;
    std::cout << "live full slip, print " << print << ": RMS error " << s.rms << ", correlation "
              << s.r << "\n";
    EXPECT_LE(s.rms, 0.0025);
    EXPECT_GE(s.r, 0.9);
  }
}

// Skin that lifts off and lands again while it slides (full slip, a region fully out of contact
// mid-sequence): frame by frame, the session leaves out the strain at or beside the cells that
// the step's two frames, or the frame before them, show out of contact, so no edge spans the
// gap. Prints 12 and 14 at 25 mm/s, 13 at 50 mm/s. Measured here (10 Hz, 40 frames): RMS error
// 0.00132 / 0.00123 / 0.00127, correlation 0.942 / 0.948 / 0.986, edges across the gap 0 / 0 / 0
// (with the curvature correction, the windows' deformation and the smoothing looking back:
// 0.00127 / 0.00114 / 0.00119, 0.949 / 0.957 / 0.987, 0 / 0 / 0);
// with no rule at all (a probe build) 0.00274 / 0.00410 / 0.00425, 0.803 / 0.657 / 0.856 and
// 26 / 73 / 78 across; with the step's two frames alone (the rule before the frame before was
// added) 0 / 0 / 5 across, the 5 on one point of print 13 on the spot where the gap closes.
// Prints 12 and 14 were run only after the rule of two frames was fixed; print 13 at 50 mm/s
// showed the closing spot, so it is not held out of the frame before.
// One place is out of the rule's reach: the frame where the gap first shows, a spot of about
// 0.6 mm at 0.4 of full contact, smaller than a contact cell, which a session that sees no later
// frame cannot tell from skin in contact (the batch capture sees it in the next frame). A point
// that happens to sit on that spot brings its edges across; here none does at these speeds (at
// 100 mm/s 9-22 edges do, on prints 12-15), and on a loaded machine (the sanitizer build beside
// other tests) the detections land elsewhere and 9-15 edges of one point did at 25 mm/s, so the
// test allows edges across the gap in that frame only. The same load lowers the correlation to
// 0.906-0.921 (fewer landmarks detected in time); 0.85 keeps that apart from 12 and 14 without
// the rule (13 at 50 mm/s without it correlates 0.856: its error and its 78 edges across tell).
TEST_F(Live, SkinThatLiftsOffInFullSlipGivesNoStrainAcrossTheGap) {
  for (const auto& [print, speed] :
       {std::pair{"12", 25}, std::pair{"14", 25}, std::pair{"13", 50}}) {
    SCOPED_TRACE(fmt::format("print {} at {} mm/s", print, speed));
    const SlipSession s = live_full_slip(dir_->path(), print, "--contact-loss 1", speed);
    // Said, with a count: the gap is a few cells over several frames.
    EXPECT_GE(number_after(s.live, "contact     "), 100) << s.live;
    // "...; N edges across the contact gap[, M of them in a frame where it opens])"
    const std::size_t said = s.eval.find(" edges across the contact gap");
    const std::size_t from = s.eval.rfind("; ", said);
    ASSERT_TRUE(said != std::string::npos && from != std::string::npos) << s.eval;
    const int across = std::stoi(s.eval.substr(from + 2, said - from - 2));
    const std::size_t opening = s.eval.find(" of them in a frame where it opens", said);
    const int where_it_opens =
        opening == std::string::npos
            ? 0
            : std::stoi(
                  s.eval.substr(said + std::string(" edges across the contact gap, ").size()));
    EXPECT_EQ(across, where_it_opens) << s.eval;
    // The recording's contact map, judged frame by frame, against where the skin truly touched
    // (the batch capture's bar; the gap is 54 of 1608 cells, so a map saying "all in contact"
    // would also pass: the count of edges left out above says the gap was seen).
    EXPECT_GE(number_after(s.eval, "contact map                right on "), 90.0) << s.eval;
    std::cout << "live full slip with lift-off, print " << print << " at " << speed
              << " mm/s: RMS error " << s.rms << ", correlation " << s.r << ", " << across
              << " edges across the gap (" << where_it_opens << " where it opens)\n";
    EXPECT_LE(s.rms, 0.0025);
    EXPECT_GE(s.r, 0.85);
  }
}

// The smoothing across the skin, chosen by the steps unless fixed, and the tracks' density, every
// landmark while the session keeps up (at 10 Hz it always does) unless a spacing is given: each
// said in the summary.
TEST_F(Live, TheSmoothingAcrossTheSkinAndTheDensityAreSaid) {
  const std::string run =
      "live " + frames().string() + " --px-per-mm 47 --rate-hz 10 --queue-frames 30 --headless";
  const auto chosen = run_tactile(run);
  ASSERT_EQ(chosen.exit_code, 0) << chosen.output;
  EXPECT_THAT(chosen.output, HasSubstr("by the steps, 0."));
  EXPECT_THAT(chosen.output, HasSubstr("density     every landmark found\n"));
  const auto fixed = run_tactile(run + " --neighbour-sigma 0.5 --min-spacing 0.4");
  ASSERT_EQ(fixed.exit_code, 0) << fixed.output;
  EXPECT_THAT(fixed.output, HasSubstr("sigma 0.5 mm; no look-ahead)\n"));
  EXPECT_THAT(fixed.output, HasSubstr("density     landmarks at least 0.40 mm apart\n"));
  // Pores about 0.3 mm apart (PolyU prints at 47 px/mm): 0.4 mm keeps fewer of them.
  EXPECT_LT(number_after(fixed.output, "; median "), number_after(chosen.output, "; median "));
  const auto none = run_tactile(run + " --neighbour-sigma 0");
  ASSERT_EQ(none.exit_code, 0) << none.output;
  EXPECT_THAT(none.output, HasSubstr("across      none\n"));
  const auto too_short = run_tactile(run + " --neighbour-sigma 0.05");
  EXPECT_NE(too_short.exit_code, 0);
  EXPECT_THAT(too_short.output,
              HasSubstr("--neighbour-sigma: 0.05 mm reaches fewer tracks than a quadratic fit "
                        "needs: give 0 (none) or 0.1 to 5 mm"));
}

TEST_F(Live, ARecordingFolderThatHoldsFilesIsRefused) {
  const fs::path record = dir_->path() / "kept";
  fs::create_directories(record);
  std::ofstream(record / "notes.txt") << "mine\n";
  const auto r = run_tactile("live " + frames().string() + " --px-per-mm 47 --headless --record " +
                             record.string());
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.output, HasSubstr("is not an empty folder"));
  std::ifstream in(record / "notes.txt");
  std::string kept;
  std::getline(in, kept);
  EXPECT_EQ(kept, "mine");
}

// No output named: where `play` would play. With no display attached (none is, in the tests)
// and no screen (DISPLAY and WAYLAND_DISPLAY emptied), that is the emulated device, said so.
TEST_F(Live, WithNoOutputNamedItGoesWherePlayWould) {
  // No screen for it, whatever this test runs under; put back afterwards.
  std::vector<std::pair<std::string, std::string>> kept;
  for (const char* name : {"DISPLAY", "WAYLAND_DISPLAY"}) {
    if (const char* v = std::getenv(name)) kept.emplace_back(name, v);
    ::unsetenv(name);
  }
  const auto r = run_tactile("live " + frames().string() + " --px-per-mm 47 --seconds 0.5");
  for (const auto& [name, value] : kept) ::setenv(name.c_str(), value.c_str(), 1);
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("live: no display attached; no screen either: playing headless "
                                  "into the emulated device"));
  EXPECT_THAT(r.output, HasSubstr("device frames sent"));
}

TEST_F(Live, FallingBehindDropsTheOldestFrameAndCountsIt) {
  // 60 frames handed over at 5000 Hz, one every 0.2 ms: faster than a 320 x 240 frame is
  // tracked (about 3 ms of CPU in the batch capture), into a queue of 4 (by default it would
  // hold 50 ms of frames, at most 64: more than the 60 handed over).
  const fs::path record = dir_->path() / "behind";
  const auto r = run_tactile(
      "live " + frames().string() +
      " --px-per-mm 47 --rate-hz 5000 --queue-frames 4 --headless --record " + record.string());
  EXPECT_THAT(r.output, HasSubstr("queue of 4 frames (1 ms at 5000 Hz); when full the oldest is "
                                  "dropped"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::size_t at = r.output.find("frames      ");
  ASSERT_NE(at, std::string::npos) << r.output;
  int in = -1, processed = -1, dropped = -1;
  ASSERT_EQ(std::sscanf(r.output.c_str() + at, "frames %d in, %d processed, %d dropped", &in,
                        &processed, &dropped),
            3)
      << r.output;
  EXPECT_EQ(in, 60);
  EXPECT_EQ(processed + dropped, in);
  EXPECT_GT(dropped, 0);
  // Strain measured across a dropped frame has another span than strain.h5's frames: the
  // recording says how many of them its strain.h5 holds, and the file agrees. Every processed
  // frame after the first gives a strain frame.
  const std::size_t said = r.output.find("; strain.h5 holds ");
  ASSERT_NE(said, std::string::npos) << r.output;
  int held = -1, measured = -1;
  ASSERT_EQ(
      std::sscanf(r.output.c_str() + said, "; strain.h5 holds %d of the %d", &held, &measured), 2)
      << r.output;
  EXPECT_EQ(measured, processed - 1);
  EXPECT_LT(held, measured);
  // Its contact map has a row for every camera frame: those processed seen, those dropped not.
  const auto movie = tactile::capture::read_strain_movie(record / "strain.h5");
  ASSERT_EQ(movie.contact.frame_count(), 60);
  EXPECT_EQ(std::count(movie.contact.frame_seen.begin(), movie.contact.frame_seen.end(), 1),
            processed);
  const auto info = run_tactile("info " + (record / "strain.h5").string());
  ASSERT_EQ(info.exit_code, 0) << info.output;
  EXPECT_THAT(info.output, HasSubstr(fmt::format("span 1, {} strain frames", held))) << info.output;
}

// A free UDP port on the loopback interface (bound, read, released).
int free_udp_port() {
  const int fd = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  socklen_t length = sizeof address;
  if (fd < 0 || ::bind(fd, reinterpret_cast<sockaddr*>(&address), sizeof address) != 0 ||
      ::getsockname(fd, reinterpret_cast<sockaddr*>(&address), &length) != 0) {
    if (fd >= 0) ::close(fd);
    return -1;
  }
  ::close(fd);
  return ntohs(address.sin_port);
}

// Whether a socket is bound to UDP `port` on this machine (/proc/net/udp lists them in hex).
bool udp_port_bound(int port) {
  std::ifstream in("/proc/net/udp");
  std::string line;
  const std::string needle = fmt::format(":{:04X} ", port);
  std::getline(in, line);  // the header
  while (std::getline(in, line)) {
    // "  sl  local_address ...": the local address is the second field, IP:PORT.
    std::istringstream fields(line);
    std::string slot, local;
    fields >> slot >> local;
    if ((local + " ").find(needle) != std::string::npos) return true;
  }
  return false;
}

// A real stream: Debian's ffmpeg encodes the 60 frames (MPEG-2 in MPEG-TS) and sends them over
// UDP to the loopback address at 25 Hz; the session reads them through FFmpeg as they arrive.
TEST_F(Live, ReadsAnFfmpegUdpStream) {
  const int port = free_udp_port();
  ASSERT_GT(port, 0);
  const std::string url = fmt::format("udp://127.0.0.1:{}", port);
  const fs::path log = dir_->path() / "udp.log";
  // 25 Hz (a rate MPEG-2 has) and the longest queue: a sanitizer build, several times slower,
  // holds the 60 frames back rather than drop them (what is tested is the stream's path).
  tactile::test::Started run(
      {"live", url, "--px-per-mm", "47", "--headless", "--queue-frames", "64", "--seconds", "30"},
      log);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (!udp_port_bound(port) && std::chrono::steady_clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  ASSERT_TRUE(udp_port_bound(port)) << "the session never listened on " << url;
  const std::string send = fmt::format(
      "timeout 60 ffmpeg -nostdin -hide_banner -loglevel error -re -framerate 25 -i "
      "'{}/frame_%03d.png' "
      "-c:v mpeg2video -q:v 2 -pix_fmt yuv420p -f mpegts '{}?pkt_size=1316' 2>&1",
      frames().string(), url);
  ASSERT_EQ(std::system(send.c_str()), 0) << send;
  // The stream's end: nothing for 2 s ends the session.
  const auto ended = run.wait(20.0);
  ASSERT_TRUE(ended.ended);
  std::ifstream in(log);
  std::stringstream output;
  output << in.rdbuf();
  ASSERT_EQ(ended.exit_code, 0) << output.str();
  EXPECT_THAT(output.str(), HasSubstr("320 x 240 px at 25 Hz"));
  const std::string text = output.str();
  const std::size_t at = text.find("frames      ");
  ASSERT_NE(at, std::string::npos) << text;
  int in_frames = 0, processed = 0, dropped = 0;
  ASSERT_EQ(std::sscanf(text.c_str() + at, "frames %d in, %d processed, %d dropped", &in_frames,
                        &processed, &dropped),
            3)
      << text;
  EXPECT_GE(in_frames, 57) << text;
  EXPECT_LE(in_frames, 60) << text;
  // At least 95 % of the 60 frames sent.
  EXPECT_GE(processed, 57) << text;
}

// Ctrl-C ends the session cleanly: exit 130, every file complete.
TEST_F(Live, StoppedTheRecordingIsComplete) {
  const fs::path record = dir_->path() / "stopped";
  tactile::test::Started run({"live", frames().string(), "--px-per-mm", "47", "--rate-hz", "20",
                              "--headless", "--record", record.string()},
                             dir_->path() / "run.log");
  ASSERT_TRUE(run.wait_until_watching(SIGINT, 10.0));
  std::this_thread::sleep_for(std::chrono::milliseconds(2500));
  run.signal(SIGINT);
  const auto ended = run.wait(10.0);
  ASSERT_TRUE(ended.ended);
  EXPECT_EQ(ended.exit_code, 130);
  const auto strain = tactile::capture::read_strain_movie(record / "strain.h5");
  EXPECT_GT(strain.frames.size(), 20u);
  const auto movie = tactile::movie::read_tactile_movie(record / "movie.h5");
  EXPECT_GT(movie.frame_count, 0);
  const auto latency = csv_rows(record / "latency.csv");
  for (const auto& row : latency) EXPECT_EQ(row.size(), 4u);
  // 2.5 s at 20 Hz is 50 frames, less the start.
  EXPECT_GE(latency.size(), 1u + 25u);
  for (const auto& row : csv_rows(record / "edges.csv")) EXPECT_EQ(row.size(), 7u);
}

// SIGKILL at a random moment, ten times: every file the recording had made opens in the
// project's readers, and strain.h5 and frames.mkv hold every camera frame up to a second before
// the kill.
TEST_F(Live, KilledAtAnyMomentTheRecordingOpens) {
  std::random_device seed_source;
  const unsigned seed = seed_source();
  std::mt19937 random(seed);
  // 60 frames at 10 Hz: a 6 s session, killed between 0.2 and 5 s after its first frame.
  std::uniform_real_distribution<double> moment_s(0.2, 5.0);
  for (int run_index = 0; run_index < 10; ++run_index) {
    const double after_s = moment_s(random);
    SCOPED_TRACE(fmt::format("run {}, seed {}: killed {:.3f} s after the first frame", run_index,
                             seed, after_s));
    const fs::path record = dir_->path() / fmt::format("killed-{}", run_index);
    const fs::path log = dir_->path() / fmt::format("killed-{}.log", run_index);
    // Before the session's first frame is available: frames after the kill are counted from here.
    const auto spawned = std::chrono::steady_clock::now();
    tactile::test::Started run({"live", frames().string(), "--px-per-mm", "47", "--rate-hz", "10",
                                "--queue-frames", "30", "--headless", "--record", record.string()},
                               log);
    // The session's first frame: the line giving its size is printed as it is processed.
    const auto first_frame = wait_for_text(log, " px at ", 30.0);
    ASSERT_TRUE(first_frame.has_value());
    std::this_thread::sleep_until(*first_frame + std::chrono::duration<double>(after_s));
    run.signal(SIGKILL);
    const auto killed_at = std::chrono::steady_clock::now();
    const auto ended = run.wait(10.0);
    ASSERT_TRUE(ended.ended);
    ASSERT_EQ(ended.killed_by, SIGKILL);
    const double elapsed_s = std::chrono::duration<double>(killed_at - *first_frame).count();
    // The first frame was available before its line was printed (its detector is chosen first,
    // slowly on a sanitizer build), but not before the program started.
    const int available = static_cast<int>(
        std::ceil(10 * std::chrono::duration<double>(killed_at - spawned).count()) + 1);

    const auto strain = tactile::capture::read_strain_movie(record / "strain.h5");
    const auto movie = tactile::movie::read_tactile_movie(record / "movie.h5");
    // Frame k is available k / 10 s after the first; the ones up to a second before the kill
    // were processed and flushed (a frame takes far less than 0.1 s here, sanitizers included).
    const int expected = static_cast<int>(std::floor(10 * (elapsed_s - 1.0)));
    EXPECT_GE(strain.camera_frame_count, expected);
    EXPECT_GE(static_cast<int>(strain.frames.size()), expected - 1);
    // Nothing after the kill: at most the frames available by then.
    EXPECT_LE(strain.camera_frame_count, available);
    if (expected > 2) {
      EXPECT_GT(movie.frame_count, 0);
    }
    // Every frame received is in frames.mkv, dropped or not, up to a second before the kill.
    tactile::capture::VideoReader video(record / "frames.mkv");
    EXPECT_GE(video.info().frame_count, expected);
    EXPECT_LE(video.info().frame_count, available);
    // The contact map of the frames kept, seen up to a second before the kill too.
    ASSERT_EQ(strain.contact.frame_count(), strain.camera_frame_count);
    EXPECT_GE(std::count(strain.contact.frame_seen.begin(), strain.contact.frame_seen.end(), 1),
              expected);
    for (const auto& row : csv_rows(record / "latency.csv")) EXPECT_EQ(row.size(), 4u);
    for (const auto& row : csv_rows(record / "edges.csv")) EXPECT_EQ(row.size(), 7u);
    for (const auto& row : csv_rows(record / "tracks.csv")) EXPECT_EQ(row.size(), 7u);
  }
}

}  // namespace
