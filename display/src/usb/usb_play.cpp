// Displays on USB as play_anywhere's back end; see usb_transports.hpp.
#include "tactile/display/play_anywhere.hpp"
#include "tactile/display/usb_transports.hpp"

namespace tactile::display {

PlayBackends usb_play_backends() {
  PlayBackends backends;
  backends.list_devices = list_usb_devices;
  // open_usb_transport's options have a default the std::function cannot carry.
  backends.open_device = [](const DeviceDescription& device) { return open_usb_transport(device); };
  return backends;
}

}  // namespace tactile::display
