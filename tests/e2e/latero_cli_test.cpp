// The Latero from the command line: `tactile emulate --latero` in the background and `tactile
// play --latero` against it over loopback UDP (127.0.0.1 only, bounded in time), the
// sender's and the emulator's counters compared; mapping for the latero layout; bad input;
// SIGINT and SIGTERM in the middle of a playback (on the Latero and headless).

#include <fcntl.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <sys/wait.h>
#include <unistd.h>

#include <signal.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <sstream>
#include <thread>
// GCC 12 with -O2 and the sanitizers warns falsely (-Wmaybe-uninitialized) inside <regex>'s
// own automaton; the warning is attributed to the header's lines, so it is silenced there only.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <regex>
#pragma GCC diagnostic pop
#include <string>
#include <vector>

#include "../common/temp_dir.hpp"
#include "run.hpp"
#include "tactile/capture/ground_truth.hpp"
#include "tactile/capture/strain_movie_io.hpp"
#include "tactile/movie/movie_io.hpp"

namespace fs = std::filesystem;
using tactile::test::run_tactile;
using ::testing::HasSubstr;

namespace {

// A loopback UDP port nobody uses right now (bound, then released).
int free_udp_port() {
  const int s = ::socket(AF_INET, SOCK_DGRAM, 0);
  sockaddr_in a{};
  a.sin_family = AF_INET;
  a.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  ::bind(s, reinterpret_cast<sockaddr*>(&a), sizeof a);
  socklen_t len = sizeof a;
  ::getsockname(s, reinterpret_cast<sockaddr*>(&a), &len);
  ::close(s);
  return ntohs(a.sin_port);
}

fs::path write_movie(const fs::path& dir, const tactile::movie::Layout& layout, double rate_hz,
                     int frames) {
  tactile::movie::TactileMovie m;
  m.layout = layout;
  m.rate_hz = rate_hz;
  m.frame_count = frames;
  const auto n = static_cast<std::size_t>(layout.contactor_count());
  m.deflection_um.resize(static_cast<std::size_t>(frames) * n);
  for (int f = 0; f < frames; ++f) {
    for (std::size_t k = 0; k < n; ++k) {
      m.deflection_um[static_cast<std::size_t>(f) * n + k] = static_cast<float>(
          40 * std::sin(2 * std::numbers::pi * (3.0 * f / rate_hz + static_cast<double>(k) / n)));
    }
  }
  m.provenance.program_version = "test";
  m.provenance.input = "sine";
  const fs::path path = dir / (layout.name + ".h5");
  tactile::movie::write_tactile_movie(path, m);
  return path;
}

// The numbers captured by `pattern`'s groups at its first match in `text` (fails the test and
// returns zeros when it does not match).
std::vector<double> numbers(const std::string& text, const std::string& pattern) {
  const std::regex re(pattern);
  std::smatch m;
  if (!std::regex_search(text, m, re)) {
    ADD_FAILURE() << "no match for " << pattern << " in:\n" << text;
    return std::vector<double>(re.mark_count(), 0.0);
  }
  std::vector<double> out;
  for (std::size_t i = 1; i < m.size(); ++i) out.push_back(std::stod(m[i]));
  return out;
}

// What `play --latero` and the emulator print (player report, link figures, counters).
const std::string kFrames = R"(frames\s+(\d+) sent \((\d+) movie \+ (\d+) ramp\))";
const std::string kRate = R"(sent at ([0-9.]+) Hz achieved)";
const std::string kLink =
    R"(replies\s+(\d+) requests, (\d+) replies, (\d+) missed \((\d+) of them came late\))";
const std::string kDatagrams =
    R"(datagrams\s+(\d+) received: (\d+) FULL \(frames played\), (\d+) IO, (\d+) RAW, (\d+) malformed)";
const std::string kEmulatorReplies = R"(replies\s+(\d+) sent, (\d+) left out)";
const std::string kBladesLeft = R"(blades\s+left at raw (\d+)\.\.(\d+))";

// Starts the emulator in the background, runs `client_args`, stops the emulator with SIGTERM and
// returns everything both printed (the client first). SIGTERM, not SIGINT: a non-interactive
// shell starts its background jobs with SIGINT ignored, and the emulator keeps an ignored SIGINT
// ignored (as nohup expects), so SIGINT would leave it answering until `seconds` ran out.
// `seconds`: how long the emulator answers at most, should the stop never arrive.
tactile::test::RunResult with_emulator(int port, const std::string& emulator_args,
                                       const std::string& client_args, const fs::path& dir,
                                       int seconds = 60) {
  const std::string bin = TACTILE_CLI_PATH;
  const std::string log = (dir / "emulator.log").string();
  return run_tactile("emulate --latero --port " + std::to_string(port) + " --seconds " +
                     std::to_string(seconds) + " " + emulator_args + " > " + log +
                     " 2>&1 & E=$!; sleep 0.3; " + bin + " " + client_args +
                     " 2>&1; rc=$?; kill -TERM $E; wait $E; cat " + log + "; exit $rc");
}

}  // namespace

TEST(LateroCli, PlaysTenSecondsAt750HzAndTheEmulatorCountsAgree) {
  const tactile::test::TempDir d_tmp("play");
  const std::filesystem::path& d = d_tmp.path();
  const int port = free_udp_port();
  const fs::path movie = write_movie(d, tactile::movie::latero_layout(), 750, 7500);  // 10 s
  const auto r = with_emulator(
      port, "", "play " + movie.string() + " --latero 127.0.0.1:" + std::to_string(port), d);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string& out = r.output;
  const auto frames = numbers(out, kFrames);  // sent, movie, ramp
  EXPECT_EQ(frames[0], 7500 + frames[2]);
  EXPECT_EQ(frames[1], 7500);
  EXPECT_NEAR(numbers(out, kRate)[0], 750, 750 * 0.05) << out;
  const auto link = numbers(out, kLink);            // requests, replies, missed, late
  EXPECT_GT(link[0], frames[0]);                    // the stop ramp comes after the frames
  EXPECT_EQ(link[0], link[1] - link[3] + link[2]);  // each answered in time or missed
  // The emulator received every request as a FULL request (plus one IO probe), none
  // malformed, and the sender received every reply it sent.
  EXPECT_THAT(out, HasSubstr("emulate: stopped"));
  const auto got = numbers(out, kDatagrams);  // datagrams, full, io, raw, malformed
  EXPECT_EQ(got[1], link[0]);
  EXPECT_EQ(got[2], 1);
  EXPECT_EQ(got[4], 0);
  const auto replies = numbers(out, kEmulatorReplies);  // sent, left out
  EXPECT_EQ(replies[0], link[1] + 1);
  EXPECT_EQ(replies[1], 0);
  // The clean stop left every blade at OpenLatero's centre.
  EXPECT_EQ(numbers(out, kBladesLeft), (std::vector<double>{75, 75}));
}

TEST(LateroCli, BladeMappingIsTheUsersToSet) {
  const tactile::test::TempDir d_tmp("mapping");
  const std::filesystem::path& d = d_tmp.path();
  const int port = free_udp_port();
  const fs::path movie = write_movie(d, tactile::movie::latero_layout(), 750, 75);
  const std::string play = "play " + movie.string() + " --latero 127.0.0.1:" + std::to_string(port);
  const auto r = with_emulator(port, "", play + " --blade-centre-raw 128 --blade-max-raw 255", d);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("raw 128 at rest"));
  EXPECT_EQ(numbers(r.output, kBladesLeft), (std::vector<double>{128, 128}));
  // A mapping no blade can follow is a usage error like any other range error, refused
  // before anything is sent: a centre above the largest raw value, a blade that never moves.
  const auto bad = run_tactile(play + " --blade-centre-raw 200");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_THAT(bad.output, HasSubstr("centre_raw 200 is outside [0, max_raw 150]"));
  EXPECT_EQ(run_tactile(play + " --blade-max-raw 300").exit_code, 2);
  const auto still = run_tactile(play + " --blade-raw-per-unit 0");
  EXPECT_EQ(still.exit_code, 2);
  EXPECT_THAT(still.output, HasSubstr("--blade-raw-per-unit: 0 is out of range"));
  // A blade mapping or --headless without a Latero to apply it to is refused, not ignored.
  const auto headless = run_tactile(play + " --headless");
  EXPECT_EQ(headless.exit_code, 2);
  EXPECT_THAT(headless.output, HasSubstr("--headless: not with --latero"));
  const auto unused = run_tactile("play " + movie.string() + " --headless --blade-max-raw 200");
  EXPECT_EQ(unused.exit_code, 2);
  EXPECT_THAT(unused.output, HasSubstr("the blade mapping is only for a Latero"));
}

TEST(LateroCli, MissedRepliesAreCountedByTheSender) {
  const tactile::test::TempDir d_tmp("loss");
  const std::filesystem::path& d = d_tmp.path();
  const int port = free_udp_port();
  const fs::path movie = write_movie(d, tactile::movie::latero_layout(), 750, 750);  // 1 s
  const auto r =
      with_emulator(port, "--drop-every 10",
                    "play " + movie.string() + " --latero 127.0.0.1:" + std::to_string(port), d);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto link = numbers(r.output, kLink);                // requests, replies, missed, late
  const auto replies = numbers(r.output, kEmulatorReplies);  // sent, left out
  EXPECT_GT(replies[1], 70);                                 // every 10th of ~800 requests
  EXPECT_EQ(link[2] - link[3], replies[1]);
  EXPECT_EQ(link[1], replies[0] - 1);  // all but the probe's reply
}

TEST(LateroCli, StressMovieIsRefusedNamingBothLayouts) {
  const tactile::test::TempDir d_tmp("stress");
  const std::filesystem::path& d = d_tmp.path();
  const fs::path movie = write_movie(d, tactile::movie::stress_layout(), 700, 10);
  const auto r = run_tactile("play " + movie.string() +
                             " --latero 127.0.0.1:" + std::to_string(free_udp_port()));
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr("'stress'"));
  EXPECT_THAT(r.output, HasSubstr("'latero'"));
  EXPECT_THAT(r.output, HasSubstr("--layout latero"));
}

TEST(LateroCli, BadAddressesAreUsageErrors) {
  const tactile::test::TempDir d_tmp("usage");
  const std::filesystem::path& d = d_tmp.path();
  const fs::path movie = write_movie(d, tactile::movie::latero_layout(), 750, 10);
  for (const auto& [address, why] :
       std::vector<std::pair<std::string, std::string>>{{"127.0.0.1:0", "outside 1..65535"},
                                                        {"127.0.0.1:65536", "outside 1..65535"},
                                                        {"127.0.0.1:port", "not a number"},
                                                        {":8900", "no host"},
                                                        {"[::1", "without ']'"}}) {
    const auto r = run_tactile("play " + movie.string() + " --latero '" + address + "'");
    EXPECT_EQ(r.exit_code, 2) << address << "\n" << r.output;
    EXPECT_THAT(r.output, HasSubstr(why)) << address;
    const auto dev = run_tactile("devices --latero '" + address + "'");
    EXPECT_EQ(dev.exit_code, 2) << address;
  }
}

TEST(LateroCli, NothingListeningTimesOutNamingTheAddress) {
  const int port = free_udp_port();
  const std::string address = "127.0.0.1:" + std::to_string(port);
  const auto r = run_tactile("devices --latero " + address);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_THAT(r.output, HasSubstr(address));
  EXPECT_THAT(r.output, HasSubstr("no reply within"));
}

TEST(LateroCli, DevicesPrintsWhatTheEmulatorReports) {
  const tactile::test::TempDir d_tmp("devices");
  const std::filesystem::path& d = d_tmp.path();
  const int port = free_udp_port();
  const auto r =
      with_emulator(port, "--no-io-board", "devices --latero 127.0.0.1:" + std::to_string(port), d);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_THAT(r.output, HasSubstr("controller FPGA 1.0, high voltage active"));
  EXPECT_THAT(r.output, HasSubstr("no IO board"));
  EXPECT_THAT(r.output, HasSubstr("left released, right released"));
}

TEST(LateroCli, MapForTheLateroLayoutMakesA750HzMovie) {
  const tactile::test::TempDir d_tmp("map");
  const std::filesystem::path& d = d_tmp.path();
  tactile::capture::SceneSpec spec;
  spec.frame_count = 12;
  tactile::capture::write_strain_movie(d / "strain.h5",
                                       tactile::capture::ground_truth_strain_movie(spec, 0.25));
  const auto r = run_tactile("map " + (d / "strain.h5").string() + " --layout latero --out " +
                             (d / "movie.h5").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto movie = tactile::movie::read_tactile_movie(d / "movie.h5");
  EXPECT_EQ(movie.layout.name, "latero");
  EXPECT_DOUBLE_EQ(movie.rate_hz, 750);
  // Asked for explicitly, another rate is kept.
  const auto r2 = run_tactile("map " + (d / "strain.h5").string() +
                              " --layout latero --rate-hz 500 --out " + (d / "m2.h5").string());
  ASSERT_EQ(r2.exit_code, 0) << r2.output;
  EXPECT_DOUBLE_EQ(tactile::movie::read_tactile_movie(d / "m2.h5").rate_hz, 500);
}

namespace {

std::string text_of(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void sleep_s(double s) {
  std::this_thread::sleep_for(std::chrono::duration<double>(s));
}

const std::string kInterrupted = "stopped     by a stop request before the end";

}  // namespace

// Ctrl-C (or a service manager's SIGTERM) 1.5 s into a ten-second movie: the player stops
// within the stop ramp, brings every blade back to OpenLatero's centre (raw 75; the movie holds
// them at 71..80) and prints the summary of what it played before exiting 128 + the signal.
TEST(StopCli, SignalMidPlayLeavesTheLateroBladesAtRest) {
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(sig == SIGINT ? "SIGINT" : "SIGTERM");
    const tactile::test::TempDir d_tmp("stop");
    const fs::path& d = d_tmp.path();
    const int port = free_udp_port();
    const fs::path movie = write_movie(d, tactile::movie::latero_layout(), 750, 7500);  // 10 s
    tactile::test::Started emulator(
        {"emulate", "--latero", "--port", std::to_string(port), "--seconds", "60"},
        d / "emulator.log");
    sleep_s(0.3);
    tactile::test::Started play(
        {"play", movie.string(), "--latero", "127.0.0.1:" + std::to_string(port)}, d / "play.log");
    ASSERT_TRUE(play.wait_until_watching(sig, 30)) << text_of(d / "play.log");
    sleep_s(1.0);
    const auto signalled = std::chrono::steady_clock::now();
    play.signal(sig);
    const auto ended = play.wait(5);
    const double stop_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - signalled).count();
    emulator.signal(SIGINT);
    ASSERT_TRUE(emulator.wait(5).ended);
    const std::string out = text_of(d / "play.log");
    const std::string emulated = text_of(d / "emulator.log");
    ASSERT_TRUE(ended.ended) << out;
    EXPECT_EQ(ended.killed_by, 0) << out;
    EXPECT_EQ(ended.exit_code, 128 + sig) << out;
    // The 20 ms stop ramp and the wait for its replies, with room for a busy machine.
    EXPECT_LT(stop_s, 1.0);
    EXPECT_THAT(out, HasSubstr(kInterrupted));
    EXPECT_THAT(out, HasSubstr(sig == SIGINT ? "stopped by SIGINT" : "stopped by SIGTERM"));
    // Part of the movie was played before the stop (about a second of it, less on a busy
    // machine where starting takes longer).
    const auto frames = numbers(out, kFrames);  // sent, movie, ramp
    EXPECT_GT(frames[0], 0);
    EXPECT_LT(frames[0], 7500);
    // The emulator saw every request the player counted (the stop ramp included), and the
    // blades where the last of them left them.
    const auto link = numbers(out, kLink);
    EXPECT_EQ(numbers(emulated, kDatagrams)[1], link[0]) << emulated;
    EXPECT_EQ(numbers(emulated, kBladesLeft), (std::vector<double>{75, 75})) << emulated;
  }
}

// The names of a process's threads.
std::vector<std::string> thread_names(int pid) {
  std::vector<std::string> names;
  for (const auto& task : fs::directory_iterator("/proc/" + std::to_string(pid) + "/task")) {
    std::ifstream in(task.path() / "comm");
    std::string name;
    if (std::getline(in, name)) names.push_back(name);
  }
  return names;
}

// A thread a library starts before main() (OpenBLAS's threaded build does, where Debian installs
// it as libblas.so.3) would not block the stop signals, and the kernel may give it a signal sent
// to the process. Preloaded with such a thread, the player and the emulator still take SIGINT
// as a stop request (`tactile` blocks both signals before any library starts a thread): the
// player ends the movie at rest, the emulator prints its counters and exits 0, neither dies of
// the signal.
TEST(StopCli, ASignalTakenByALibrarysEarlyThreadStillStopsAtRest) {
  const tactile::test::TempDir d_tmp("early-thread");
  const fs::path& d = d_tmp.path();
  const char* asan = std::getenv("ASAN_OPTIONS");
  // The preloaded library comes before the sanitizer's runtime in a sanitizer build.
  const std::vector<std::string> preload = {std::string("LD_PRELOAD=") + TACTILE_THREAD_BEFORE_MAIN,
                                            std::string("ASAN_OPTIONS=") +
                                                (asan != nullptr ? std::string(asan) + ":" : "") +
                                                "verify_asan_link_order=0"};
  const int port = free_udp_port();
  const fs::path movie = write_movie(d, tactile::movie::latero_layout(), 750, 7500);  // 10 s
  tactile::test::Started emulator(
      {"emulate", "--latero", "--port", std::to_string(port), "--seconds", "60"},
      d / "emulator.log", preload);
  ASSERT_TRUE(emulator.wait_until_watching(SIGINT, 30)) << text_of(d / "emulator.log");
  sleep_s(0.3);  // until it answers on the port, as in the test above
  tactile::test::Started play(
      {"play", movie.string(), "--latero", "127.0.0.1:" + std::to_string(port)}, d / "play.log",
      preload);
  ASSERT_TRUE(play.wait_until_watching(SIGINT, 30)) << text_of(d / "play.log");
  for (const int pid : {emulator.pid(), play.pid()}) {
    EXPECT_THAT(thread_names(pid), ::testing::Contains("before-main"))
        << "pid " << pid << (pid == play.pid() ? " play" : " emulator");
  }
  sleep_s(1.0);
  play.signal(SIGINT);
  const auto played = play.wait(5);
  emulator.signal(SIGINT);
  const auto emulated = emulator.wait(5);
  const std::string out = text_of(d / "play.log");
  const std::string emulator_out = text_of(d / "emulator.log");
  ASSERT_TRUE(played.ended) << out;
  EXPECT_EQ(played.killed_by, 0) << out;
  EXPECT_EQ(played.exit_code, 130) << out;
  EXPECT_THAT(out, HasSubstr(kInterrupted));
  ASSERT_TRUE(emulated.ended) << emulator_out;
  EXPECT_EQ(emulated.killed_by, 0) << emulator_out;
  EXPECT_EQ(emulated.exit_code, 0) << emulator_out;
  EXPECT_EQ(numbers(emulator_out, kDatagrams)[1], numbers(out, kLink)[0]) << emulator_out;
  EXPECT_EQ(numbers(emulator_out, kBladesLeft), (std::vector<double>{75, 75})) << emulator_out;
}

// Headless, the emulated device's firmware plays the movie on a simulated clock; a signal
// mid-play stops it, the firmware's own outputs (as it wrote them, tick by tick) end at rest,
// and no preview is written, not even a temporary file.
TEST(StopCli, SignalMidHeadlessPlayEndsTheFirmwareOutputsAtRest) {
  for (const int sig : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(sig == SIGINT ? "SIGINT" : "SIGTERM");
    const tactile::test::TempDir d_tmp("headless");
    const fs::path& d = d_tmp.path();
    const fs::path movie = write_movie(d, tactile::movie::latero_layout(), 750, 7500);
    tactile::test::Started play({"play", movie.string(), "--headless", "--loops", "40", "--preview",
                                 (d / "preview.png").string()},
                                d / "play.log");
    ASSERT_TRUE(play.wait_until_watching(sig, 30)) << text_of(d / "play.log");
    sleep_s(1.0);  // some 75 000 frames a second of 300 000
    play.signal(sig);
    const auto ended = play.wait(10);
    const std::string out = text_of(d / "play.log");
    ASSERT_TRUE(ended.ended) << out;
    EXPECT_EQ(ended.killed_by, 0) << out;
    EXPECT_EQ(ended.exit_code, 128 + sig) << out;
    EXPECT_THAT(out, HasSubstr("stopped by a stop request, every contactor ramped to rest"));
    // Before the stop the outputs followed the 40 um sine; after it, none is off rest.
    const auto played = numbers(out, R"((\d+) frames played at 750 Hz)");
    EXPECT_GT(played[0], 0);
    EXPECT_LT(played[0], 40 * 7500);
    EXPECT_EQ(numbers(out, R"(outputs ended at most ([0-9.e+-]+) um from rest)")[0], 0) << out;
    EXPECT_THAT(out, HasSubstr("no preview written"));
    EXPECT_FALSE(fs::exists(d / "preview.png"));
    for (const auto& e : fs::directory_iterator(d)) {
      EXPECT_THAT(e.path().filename().string(), ::testing::Not(HasSubstr("preview"))) << e.path();
    }
  }
}

// A signal while the movie is still being read (a long one takes about a second) stops the
// play there, saying so and that nothing reached a display, instead of ending the process by
// the default action with nothing printed.
TEST(StopCli, SignalWhileReadingTheMovieSaysNothingWasSent) {
  const tactile::test::TempDir d_tmp("reading");
  const fs::path& d = d_tmp.path();
  const fs::path movie = write_movie(d, tactile::movie::latero_layout(), 750, 150000);  // 200 s
  tactile::test::Started play(
      {"play", movie.string(), "--headless", "--preview", (d / "preview.png").string()},
      d / "play.log");
  ASSERT_TRUE(play.wait_until_watching(SIGINT, 30)) << text_of(d / "play.log");
  play.signal(SIGINT);
  const auto ended = play.wait(30);
  const std::string out = text_of(d / "play.log");
  ASSERT_TRUE(ended.ended) << out;
  EXPECT_EQ(ended.killed_by, 0) << out;
  EXPECT_EQ(ended.exit_code, 130) << out;
  EXPECT_THAT(out, HasSubstr("play: stopped by SIGINT while reading " + movie.string() +
                             ": nothing was sent to any display"));
  EXPECT_THAT(out, ::testing::Not(HasSubstr("frames played")));
  EXPECT_FALSE(fs::exists(d / "preview.png"));
}

// A stop signal that comes while `tactile` is still starting (its libraries' initialisers, the
// command line being parsed) waits until the command would begin, and is then answered in
// words and the signal's exit code. Made certain here, not left to timing: the child blocks
// SIGINT and sends it to itself before exec, which keeps both the block and the pending signal.
TEST(StopCli, ASignalBeforeTheCommandBeganIsAnsweredInWords) {
  const tactile::test::TempDir d_tmp("early");
  const fs::path log = d_tmp.path() / "play.log";
  const fs::path preview = d_tmp.path() / "preview.png";
  const std::string movie = (tactile::test::demo_dir() / "movie.h5").string();
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int out = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (out < 0 || ::dup2(out, 1) < 0 || ::dup2(out, 2) < 0) _exit(101);
    sigset_t set;
    sigemptyset(&set);
    sigaddset(&set, SIGINT);
    if (sigprocmask(SIG_BLOCK, &set, nullptr) != 0 || ::kill(::getpid(), SIGINT) != 0) _exit(102);
    ::execl(TACTILE_CLI_PATH, TACTILE_CLI_PATH, "play", movie.c_str(), "--headless", "--preview",
            preview.c_str(), static_cast<char*>(nullptr));
    _exit(103);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(pid, &status, 0), pid);
  const std::string out = text_of(log);
  ASSERT_TRUE(WIFEXITED(status)) << "ended by signal " << WTERMSIG(status) << ": " << out;
  EXPECT_EQ(WEXITSTATUS(status), 130) << out;
  EXPECT_THAT(out, HasSubstr("tactile play: stopped by SIGINT before it began: nothing was done"));
  EXPECT_THAT(out, ::testing::Not(HasSubstr("frames played")));
  EXPECT_FALSE(fs::exists(preview));
}

// A live session played on the Latero: every frame the session sent reached the emulator
// (it also counts the stop ramp's), none malformed, and the blades were left at rest.
TEST(LateroCli, LiveSessionPlaysOnTheLateroAndEndsAtRest) {
  const tactile::test::TempDir d_tmp("live");
  const fs::path& d = d_tmp.path();
  const auto synth =
      run_tactile("synth " + (d / "wave").string() + " --from-print " +
                  (tactile::test::test_data("polyu-hrf-pores") / "image_12.jpg").string() +
                  " --px-per-mm 47 --warp wave --frames 30");
  ASSERT_EQ(synth.exit_code, 0) << synth.output;
  const int port = free_udp_port();
  const auto r = with_emulator(port, "",
                               "live " + (d / "wave").string() +
                                   " --px-per-mm 47 --rate-hz 20 --queue-frames 30 --layout "
                                   "latero --latero 127.0.0.1:" +
                                   std::to_string(port) + " --seconds 1.5",
                               d, 8);
  ASSERT_EQ(r.exit_code, 0) << r.output;
  // The figures as both programs print them (read without std::regex, which GCC 12's
  // -Wmaybe-uninitialized takes wrongly for uninitialised under the sanitizers' -O2).
  int frames_sent = -1, frames_played = -1, malformed = -1, left_lo = -1, left_hi = -2;
  int received = 0, io = 0, raw = 0;
  const auto line = [&r](const std::string& start) {
    const std::size_t at = r.output.find(start);
    return at == std::string::npos ? std::string() : r.output.substr(at);
  };
  ASSERT_EQ(std::sscanf(line("display ").c_str(), "display %d device frames sent at 750 Hz",
                        &frames_sent),
            1)
      << r.output;
  ASSERT_EQ(std::sscanf(line("datagrams ").c_str(),
                        "datagrams %d received: %d FULL (frames played), %d IO, %d RAW, %d "
                        "malformed",
                        &received, &frames_played, &io, &raw, &malformed),
            5)
      << r.output;
  ASSERT_EQ(std::sscanf(line("blades ").c_str(), "blades left at raw %d..%d", &left_lo, &left_hi),
            2)
      << r.output;
  EXPECT_GT(frames_sent, 500);  // 1.5 s at 750 Hz, less the session's start
  // The stop ramp (20 ms at 750 Hz: 15 frames) comes on top of the session's frames.
  EXPECT_GE(frames_played, frames_sent);
  EXPECT_LE(frames_played, frames_sent + 20);
  EXPECT_EQ(malformed, 0);
  EXPECT_EQ(left_lo, left_hi);  // every blade at one value: rest
}

// A Latero that does not answer ends the session with the sender's words naming the address
// (exit 1), not a crash or a hang.
TEST(LateroCli, LiveSessionWithNoLateroNamesTheAddress) {
  const tactile::test::TempDir d_tmp("live-none");
  const fs::path& d = d_tmp.path();
  ASSERT_EQ(run_tactile("synth " + (d / "wave").string() + " --from-print " +
                        (tactile::test::test_data("polyu-hrf-pores") / "image_12.jpg").string() +
                        " --px-per-mm 47 --warp wave --frames 30")
                .exit_code,
            0);
  const std::string address = "127.0.0.1:" + std::to_string(free_udp_port());
  const auto r = run_tactile("live " + (d / "wave").string() +
                             " --px-per-mm 47 --rate-hz 20 --layout latero --latero " + address);
  EXPECT_EQ(r.exit_code, 1) << r.output;
  EXPECT_THAT(r.output, HasSubstr("Latero at " + address));
}
