#pragma once
// The Latero on the command line: `play --latero`, `devices --latero`, `emulate --latero`,
// `bench latero` (cmd_latero.cpp).

#include <CLI/CLI.hpp>

#include <string>

#include "tactile/display/tactile_movie.hpp"

namespace tactile::cli {

// Checks HOST[:PORT] at parse time, so that a bad address is a usage error (exit 2).
CLI::Validator latero_address_check();

// Plays `movie` on the Latero at `address` (HOST[:PORT]) and prints the link's figures.
int play_on_latero(const display::TactileMovie& movie, const std::string& address, int loops);

// Probes the Latero at `address` and prints what it reports.
int print_latero_device(const std::string& address);

}  // namespace tactile::cli
