#pragma once
// The Latero on the command line: `play --latero`, `devices --latero`, `emulate --latero`,
// `bench latero` (cmd_latero.cpp).

#include <CLI/CLI.hpp>

#include <string>

#include "tactile/display/latero_protocol.hpp"
#include "tactile/movie/tactile_movie.hpp"

namespace tactile::cli {

// Checks HOST[:PORT] at parse time, so that a bad address is a usage error (exit 2).
CLI::Validator latero_address_check();

struct LateroPlayOptions {
  std::string address;  // HOST[:PORT]; empty: not playing on a Latero
  display::LateroBladeMapping mapping;
};

// Registers --latero HOST[:PORT] and the blade mapping's options on `play`.
void add_latero_play_options(CLI::App& play, LateroPlayOptions& options);
// Registers the blade mapping's options (--blade-centre-raw, ...) on `command`.
void add_blade_mapping_options(CLI::App& command, display::LateroBladeMapping& mapping);

// Plays `movie` on the Latero at options.address and prints the link's figures; stops early,
// blades ramped to centre, when `stop_fd` becomes readable (display::PlayOptions::stop_fd).
int play_on_latero(const movie::TactileMovie& movie, const LateroPlayOptions& options, int loops,
                   int stop_fd = -1);

// Probes the Latero at `address` and prints what it reports.
int print_latero_device(const std::string& address);

}  // namespace tactile::cli
