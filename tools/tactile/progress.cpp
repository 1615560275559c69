#include "progress.hpp"

#include <fmt/format.h>
#include <unistd.h>

namespace tactile::cli {

Progress::Progress(bool quiet) : quiet_(quiet), tty_(isatty(fileno(stderr)) != 0) {}

void Progress::operator()(const std::string& stage, int done, int total) {
  if (quiet_ || total <= 0) return;
  // Results go to stdout, progress to stderr: flush stdout first so a log reads in order.
  std::fflush(stdout);
  if (stage != stage_) {
    finish();
    stage_ = stage;
    last_quarter_ = -1;
  }
  if (tty_) {
    fmt::print(stderr, "\r  {:<12} {:>5}/{:<5} ({:3d} %)", stage, done, total, 100 * done / total);
    open_line_ = true;
    if (done == total) finish();
    return;
  }
  const int quarter = 4 * done / total;
  if (quarter != last_quarter_) {
    last_quarter_ = quarter;
    fmt::print(stderr, "  {:<12} {:>5}/{:<5}\n", stage, done, total);
  }
}

void Progress::finish() {
  if (open_line_) fmt::print(stderr, "\n");
  open_line_ = false;
}

}  // namespace tactile::cli
