#pragma once
// Progress lines for long work. On a terminal one line is rewritten in place; in a log (CI, a
// pipe) a line is printed every 25 % so logs stay short but still show the work moving.

#include <cstdio>
#include <string>

namespace tactile::cli {

class Progress {
 public:
  explicit Progress(bool quiet = false);
  void operator()(const std::string& stage, int done, int total);
  // Ends the current line, if one is open.
  void finish();

 private:
  bool quiet_;
  bool tty_;
  std::string stage_;
  int last_quarter_ = -1;
  bool open_line_ = false;
};

}  // namespace tactile::cli
