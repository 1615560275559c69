#pragma once
// The Latero on the command line: the options of `play --latero` (played by
// display::play_anywhere), `devices --latero`, `emulate --latero`, `bench latero` (cmd_latero.cpp).

#include <CLI/CLI.hpp>

#include <string>

#include "tactile/display/latero_protocol.hpp"
#include "tactile/display/play_anywhere.hpp"

namespace tactile::cli {

// Checks HOST[:PORT] at parse time, so that a bad address is a usage error (exit 2).
CLI::Validator latero_address_check();

// Registers --latero HOST[:PORT] and the blade mapping's options on `play`; an empty address
// after parsing means no Latero was asked for.
void add_latero_play_options(CLI::App& play, display::LateroPlayTarget& target);
// Registers the blade mapping's options (--blade-centre-raw, ...) on `command`.
void add_blade_mapping_options(CLI::App& command, display::LateroBladeMapping& mapping);

// Probes the Latero at `address` and prints what it reports.
int print_latero_device(const std::string& address);

}  // namespace tactile::cli
