#pragma once
// Help for wrong usage: the command a command line names (also `bench map`, `classify train`),
// and the first flag it does not know, with the closest one it does.

#include <CLI/CLI.hpp>
#include <optional>
#include <string>
#include <vector>

namespace tactile::cli {

struct CommandPath {
  const CLI::App* command = nullptr;  // the innermost command named; nullptr: none
  std::string name;                   // e.g. "bench map"; empty: none
  int first_argument = 1;             // index in argv after the command's words
};

const CLI::App* find_command(const CLI::App& parent, const std::string& word);
std::vector<std::string> command_names(const CLI::App& parent);
CommandPath command_path(const CLI::App& app, int argc, char** argv);

// "unknown option '--min-tracks' for `tactile capture` (did you mean '--min-track'?)" for the
// first flag of argv the command does not take; nothing when it takes them all.
std::optional<std::string> unknown_flag(const CommandPath& path, int argc, char** argv);

// Every option of `app` and its commands that takes a value refuses the empty string at parse
// time: an empty path would be taken as the current folder or as no file at all (an empty
// --screenshot opened the window and waited for a person), and no option gives "" a meaning.
void refuse_empty_values(CLI::App& app);

}  // namespace tactile::cli
