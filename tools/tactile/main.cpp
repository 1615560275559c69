// The `tactile` command line: one program, one subcommand per job.
// Exit codes: 0 success, 1 the work failed (bad file, device error), 2 wrong usage.

#include <fmt/format.h>

#include <malloc.h>
#include <signal.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <CLI/CLI.hpp>
#include <cstdio>
#include <exception>
#include <new>
#include <stdexcept>
#include <string>

#include "command.hpp"
#include "tactile/capture/image.hpp"
#include "tactile/common/option_table.hpp"
#include "tactile/common/output_paths.hpp"
#include "tactile/common/provenance.hpp"
#include "tactile/common/stop_signals.hpp"
#include "tactile/common/version.hpp"
#include "usage_hints.hpp"

namespace {

// SIGINT and SIGTERM in the kernel's signal-set format, and the mask `tactile` was started with:
// file-level because a .preinit_array function takes nothing from main and returns nothing.
constexpr unsigned long kStopSignalBits = (1UL << (SIGINT - 1)) | (1UL << (SIGTERM - 1));
unsigned long g_mask_at_start = 0;

// Runs before any shared library's initialiser (an ELF .preinit_array entry runs first, for the
// program only). Some libraries start threads there: OpenBLAS's threaded build, which Debian may
// install as libblas.so.3, starts its workers before main(). A thread inherits its creator's
// signal mask, so with both signals blocked now, those threads never take them. Otherwise the
// kernel may give a Ctrl-C to one of them and the process ends by the signal, instead of the
// stop request a command's StopSignals makes of it (the device ramped to rest, the counters
// printed). The system call itself: the C library and a sanitizer runtime are not initialised.
void block_stop_signals_before_the_libraries(int, char**, char**) {
  ::syscall(SYS_rt_sigprocmask, SIG_BLOCK, &kStopSignalBits, &g_mask_at_start,
            sizeof kStopSignalBits);
}
[[gnu::used, gnu::section(".preinit_array")]] void (*const block_stop_signals)(
    int, char**, char**) = &block_stop_signals_before_the_libraries;

// A stop signal that came while `tactile` started (loading its libraries, parsing): the main
// thread keeps both blocked until a command begins, so such a signal waits, and is answered in
// words instead of ending the process silently. 0: none came. One the process ignores does not
// count (a blocked ignored signal is kept pending, and dropped once unblocked).
int stop_signal_before_the_command() {
  sigset_t pending;
  if (sigpending(&pending) != 0) return 0;
  for (const int sig : {SIGINT, SIGTERM}) {
    struct sigaction now {};
    const bool ignored = sigaction(sig, nullptr, &now) == 0 && (now.sa_flags & SA_SIGINFO) == 0 &&
                         now.sa_handler == SIG_IGN;
    if (!ignored && sigismember(&pending, sig) == 1) return sig;
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // The capture frees a detector's images, and each frame's buffers, just before it needs as
  // much again. glibc would hand blocks of a frame's size back to the kernel and fault them in
  // again page by page (a 120-frame 640 x 484 capture: 71 000 page faults, 43 000 with these
  // settings, 0.1-0.2 ms of kernel time a frame). Kept in the process, they are reused.
  mallopt(M_MMAP_THRESHOLD, 64 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  CLI::App app{
      "tactile: turn measured skin strain into tactile movies and play them on a\n"
      "lateral-skin-stretch display (STReSS family), or in an emulator window.\n"
      "Start with `tactile demo`; every subcommand has --help."};
  app.set_version_flag("--version", std::string("tactile ") + tactile::kVersion);
  app.require_subcommand(1);
  app.fallthrough(false);

  tactile::cli::Action action;
  const std::string command_line = tactile::command_line_of(argc, argv);
  for (tactile::cli::AddCommand* add : tactile::cli::kCommands) add(app, action, command_line);
  tactile::cli::refuse_empty_values(app);

  // CLI11 reports an unknown first word as a missing subcommand; name it instead.
  if (argc > 1 && argv[1][0] != '-' && !tactile::cli::find_command(app, argv[1])) {
    const auto near = tactile::closest_name(argv[1], tactile::cli::command_names(app));
    fmt::print(stderr,
               "tactile: error: unknown command '{}'{}\nRun `tactile --help` for the list.\n",
               argv[1], near ? fmt::format(" (did you mean '{}'?)", *near) : "");
    return 2;
  }
  const auto usage_error = [&app, argc, argv](const std::string& what) {
    const tactile::cli::CommandPath path = tactile::cli::command_path(app, argc, argv);
    // An unknown flag first: a missing required option is often the misspelt one.
    const std::string message = tactile::cli::unknown_flag(path, argc, argv).value_or(what);
    fmt::print(stderr, "tactile: error: {}\nRun `tactile {}--help`.\n", message,
               path.name.empty() ? "" : path.name + " ");
    return 2;
  };
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    return usage_error(e.what());
  } catch (const std::exception& e) {
    // A check of an option that failed otherwise than CLI11 reports: still a usage error.
    return usage_error(e.what());
  }

  if (!action) return 2;  // unreachable: require_subcommand(1) guarantees a command ran
  // Every failure ends here as one line naming the command, and exit 1; nothing escapes main
  // (an escaped exception aborts with the C++ runtime's words and a core dump).
  const std::string command = app.get_subcommands().front()->get_name();
  const auto failed = [&command](const std::string& why) {
    fmt::print(stderr, "tactile {}: error: {}\n", command, why);
    return 1;
  };
  if (const int sig = stop_signal_before_the_command(); sig != 0) {
    fmt::print(stderr, "tactile {}: stopped by {} before it began: nothing was done\n", command,
               tactile::stop_signal_name(sig));
    return tactile::exit_code_for_signal(sig);
  }
  // A command that watches the signals takes them blocked, so that none falls between here and
  // its StopSignals; any other takes them as `tactile` was started to (the library threads keep
  // the block either way).
  if (action.target<tactile::cli::WatchingStopSignals>() == nullptr) {
    ::syscall(SYS_rt_sigprocmask, SIG_SETMASK, &g_mask_at_start, nullptr, sizeof g_mask_at_start);
  }
  try {
    return action();
  } catch (const tactile::OutputPathError& e) {
    // Found before any work, like a parse error, but only once a command knows its inputs.
    fmt::print(stderr, "tactile {}: error: {}\n", command, e.what());
    return 2;
  } catch (const tactile::RequestError& e) {
    // A rule that needs the input (a range of frames against the video's length): usage.
    fmt::print(stderr, "tactile {}: error: {}\n", command, e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    return failed(
        "out of memory: the work needs more memory than this machine gives it (a smaller "
        "input or a lower setting may fit)");
  } catch (const std::length_error&) {
    return failed(
        "a size beyond what this program can hold (a damaged input or an option far "
        "too large?)");
  } catch (const std::exception& e) {
    return failed(tactile::capture::opencv_error_text(e).value_or(e.what()));
  } catch (...) {
    return failed(
        "an unexpected failure that is not a standard exception (a bug: please report it)");
  }
}
