#pragma once
// UDP socket plumbing shared by the Latero transport and the emulated Latero.

#include <time.h>

#include <chrono>
#include <cstdint>
#include <string>

namespace tactile::display::detail {

enum class UdpRole { connect, bind };

// Resolves `host` (a name only when `numeric_host` is false) and `port`, then opens a UDP
// socket (close-on-exec, plus `extra_flags` such as SOCK_NONBLOCK) connected or bound to the
// first address that accepts it. Returns the descriptor, or -1 with the reason in `why`.
int open_udp_socket(const std::string& host, std::uint16_t port, UdpRole role, bool numeric_host,
                    int extra_flags, std::string& why);

timespec to_timespec(std::chrono::nanoseconds duration);

}  // namespace tactile::display::detail
