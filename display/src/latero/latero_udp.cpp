// UDP socket plumbing for the Latero; see latero_udp.hpp.
#include "latero/latero_udp.hpp"

#include <netdb.h>
#include <sys/socket.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>

namespace tactile::display::detail {

int open_udp_socket(const std::string& host, std::uint16_t port, UdpRole role, bool numeric_host,
                    int extra_flags, std::string& why) {
  addrinfo hints{};
  hints.ai_socktype = SOCK_DGRAM;
  hints.ai_flags = AI_NUMERICSERV | (numeric_host ? AI_NUMERICHOST : 0) |
                   (role == UdpRole::bind ? AI_PASSIVE : 0);
  addrinfo* found = nullptr;
  if (const int e = getaddrinfo(host.c_str(), std::to_string(port).c_str(), &hints, &found);
      e != 0) {
    why = std::string("cannot resolve '") + host + "': " + gai_strerror(e);
    return -1;
  }
  int socket = -1;
  why = "no address";
  for (addrinfo* ai = found; ai != nullptr && socket < 0; ai = ai->ai_next) {
    const int s = ::socket(ai->ai_family, SOCK_DGRAM | SOCK_CLOEXEC | extra_flags, 0);
    if (s < 0) {
      why = std::strerror(errno);
      continue;
    }
    const int r = role == UdpRole::bind ? ::bind(s, ai->ai_addr, ai->ai_addrlen)
                                        : ::connect(s, ai->ai_addr, ai->ai_addrlen);
    if (r != 0) {
      why = std::strerror(errno);
      ::close(s);
      continue;
    }
    socket = s;
  }
  freeaddrinfo(found);
  return socket;
}

timespec to_timespec(std::chrono::nanoseconds duration) {
  const auto ns = std::max<std::int64_t>(0, duration.count());
  return timespec{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
}

}  // namespace tactile::display::detail
