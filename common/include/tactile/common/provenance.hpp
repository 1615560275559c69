#pragma once
// Where a file came from, stored with every movie and scene this program writes. Each field means
// one thing whichever command or library call wrote the file.

#include <string>

namespace tactile {

struct Provenance {
  // The file or folder the output was made from, its path as given; empty when it was made from
  // no file (a synthetic scene, a simulated sensor: see method and parameters_json).
  std::string input;
  std::string program_version;  // version of the tactile libraries that wrote it
  // The command that wrote it, as typed; empty when a library call (Python, a test) wrote it.
  std::string command_line;
  // How it was made from the input: a mapping method ("integrated"), "capture", "synthetic
  // ground truth", "hjif import", ...
  std::string method;
  std::string parameters_json;  // the method's parameters as one JSON object
  std::string created_utc;      // ISO 8601 UTC time it was made
};

// The provenance of output made now: this library's version and the current UTC time, with the
// input, method and parameters the writer names (command_line is the command line's to fill).
Provenance make_provenance(std::string input, std::string method,
                           std::string parameters_json = "{}");

// The command line as typed, each argument that holds a space or a quote in single quotes.
std::string command_line_of(int argc, const char* const* argv);

// What a message names the output's origin by: the input, else the method (and its parameters).
std::string origin_of(const Provenance& provenance);

}  // namespace tactile
