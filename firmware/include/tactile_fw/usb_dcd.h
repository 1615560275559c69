#ifndef TACTILE_FW_USB_DCD_H
#define TACTILE_FW_USB_DCD_H
/*
 * The device-controller interface the USB class logic (usb.h) drives. As in TinyUSB, the class
 * logic knows descriptors and requests, the device-controller driver knows the silicon: a port
 * to a microcontroller implements these three calls and feeds received SETUP and OUT packets
 * to tfw_usb_*(); the host checks and the emulated device implement them in memory.
 */
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct {
  void* context;
  /* Queues `len` bytes on IN endpoint `ep` (0x80 | n); on 0x80 it is the data stage of the
   * current control-IN request (an OUT request completes with a zero-length status). Returns 0
   * when the endpoint is still busy with earlier data (the caller drops or retries). */
  int (*write)(void* context, uint8_t ep, const uint8_t* data, uint16_t len);
  /* Stalls `ep`; on endpoint 0 this refuses the current control request. */
  void (*stall)(void* context, uint8_t ep);
  /* 1: accept the next OUT packet on `ep`; 0: answer NAK until re-armed. This is how a full
   * FIFO makes the host wait instead of losing frames. */
  void (*set_out_ready)(void* context, uint8_t ep, int ready);
} tfw_usb_dcd;

#ifdef __cplusplus
}
#endif

#endif /* TACTILE_FW_USB_DCD_H */
