#ifndef TACTILE_FW_USB_H
#define TACTILE_FW_USB_H
/*
 * USB glue of the display (docs/protocol.md, "USB"): descriptors, control requests and the
 * two ways frames arrive.
 *
 *   interface 0, vendor class 0xFF: EP 0x01 bulk OUT frames (one frame per transfer, ended by
 *     a short or zero-length packet), EP 0x81 interrupt IN fill reports (control.h).
 *   interface 1, HID (for hosts without a driver): EP 0x02 interrupt OUT output report 1
 *     (frame chunks), EP 0x82 interrupt IN input report 2 (fill report); feature reports
 *     3 (device information), 4 (status) and 5 (command, the vendor requests' equivalent).
 *
 * Vendor requests, bmRequestType 0x41 (host to device) / 0xC1 (device to host), recipient
 * interface 0, wIndex 0:
 *   0x01 GET_INFO    IN  48 bytes (control.h)
 *   0x02 START       OUT wValue = rate_hz (0: the configured rate), no data
 *   0x03 STOP        OUT no data
 *   0x04 SET_LIMITS  OUT 8 bytes: i16 deflection_min, i16 deflection_max, u32 max_slew_per_s
 *   0x05 GET_STATUS  IN  96 bytes (control.h)
 * A refused request (bad rate, limits wider than the hardware's, wrong length) stalls EP0.
 *
 * All state is in tfw_usb (no heap, no globals); the frame assembly buffers are in it too.
 */
#include <stddef.h>
#include <stdint.h>

#include "tactile_fw/control.h"
#include "tactile_fw/device.h"
#include "tactile_fw/usb_dcd.h"

#ifdef __cplusplus
extern "C" {
#endif

#define TFW_USB_VENDOR_ID 0x1209u  /* pid.codes */
#define TFW_USB_PRODUCT_ID 0x0001u /* pid.codes test PID until the project has its own */
#define TFW_USB_BCD_DEVICE 0x0100u

#define TFW_USB_VENDOR_INTERFACE 0u
#define TFW_USB_HID_INTERFACE 1u
#define TFW_USB_EP_FRAMES_OUT 0x01u
#define TFW_USB_EP_FILL_IN 0x81u
#define TFW_USB_EP_HID_OUT 0x02u
#define TFW_USB_EP_HID_IN 0x82u

#define TFW_USB_EP0_PACKET 64u
#define TFW_USB_BULK_PACKET_FS 64u
#define TFW_USB_BULK_PACKET_HS 512u
#define TFW_USB_HID_PACKET 64u

#define TFW_USB_REQ_GET_INFO 0x01u
#define TFW_USB_REQ_START 0x02u
#define TFW_USB_REQ_STOP 0x03u
#define TFW_USB_REQ_SET_LIMITS 0x04u
#define TFW_USB_REQ_GET_STATUS 0x05u
#define TFW_USB_LIMITS_BYTES 8u

/* HID reports. Output report 1 carries a chunk of a frame:
 *   0 u8 report id (1)   1 u8 flags: bit 0 first chunk, bit 1 last chunk   2 u8 length 1..61
 *   3.. payload (61 bytes, zero-padded)
 * A frame is its chunks' payloads joined, first to last; a chunk out of place (a middle chunk
 * with no first, a new first before the last) drops the partial frame as bad_length. */
#define TFW_HID_REPORT_FRAME 1u
#define TFW_HID_REPORT_FILL 2u
#define TFW_HID_REPORT_INFO 3u
#define TFW_HID_REPORT_STATUS 4u
#define TFW_HID_REPORT_COMMAND 5u
#define TFW_HID_REPORT_BYTES 64u /* output/input reports, report id included */
#define TFW_HID_CHUNK_PAYLOAD 61u
#define TFW_HID_CHUNK_FIRST 0x01u
#define TFW_HID_CHUNK_LAST 0x02u
/* Feature report 5: u8 request code (0x02..0x04), u8 reserved, u16 wValue, 8 data bytes. */
#define TFW_HID_COMMAND_BYTES 12u

/* Standard requests and descriptor types the class logic answers (USB 2.0 chapter 9). */
#define TFW_USB_DESC_DEVICE 1u
#define TFW_USB_DESC_CONFIGURATION 2u
#define TFW_USB_DESC_STRING 3u
#define TFW_USB_DESC_DEVICE_QUALIFIER 6u
#define TFW_USB_DESC_HID 0x21u
#define TFW_USB_DESC_HID_REPORT 0x22u
#define TFW_USB_CONFIG_DESCRIPTOR_BYTES 64u

typedef enum { TFW_USB_FULL_SPEED = 0, TFW_USB_HIGH_SPEED = 1 } tfw_usb_speed;

typedef struct {
  uint8_t buffer[TFW_MAX_FRAME_BYTES];
  uint16_t length;
  uint8_t discarding; /* too long or out of place: skip to the end of this transfer */
} tfw_usb_assembly;

typedef struct {
  tfw_device* dev;
  tfw_usb_dcd dcd;
  uint8_t speed; /* tfw_usb_speed, from the bus reset */
  uint8_t configured;
  const char* serial;
  uint8_t configuration[TFW_USB_CONFIG_DESCRIPTOR_BYTES]; /* for this speed */
  tfw_usb_assembly bulk;
  tfw_usb_assembly hid;
  uint8_t ep0[TFW_USB_EP0_PACKET * 2]; /* replies built here (strings, status) */
} tfw_usb;

void tfw_usb_init(tfw_usb* usb, tfw_device* dev, const tfw_usb_dcd* dcd, tfw_usb_speed speed,
                  const char* serial);

/* The configuration descriptor for `speed` (tfw_usb_init does this; exposed for tests). */
void tfw_usb_build_configuration(uint8_t speed, uint8_t* out);

/* Descriptors: returns the length and sets *out, or 0 when there is no such descriptor. */
uint16_t tfw_usb_descriptor(tfw_usb* usb, uint8_t type, uint8_t index, const uint8_t** out);

/* One SETUP packet (8 bytes) with its OUT data stage, if any. Answers through the DCD (data or
 * zero-length status on 0x80, or a stall of endpoint 0). Returns 1 when handled, 0 stalled. */
int tfw_usb_setup(tfw_usb* usb, const uint8_t setup[8], const uint8_t* data, uint16_t data_len);

/* One packet received on the bulk OUT endpoint (`len` up to the bulk packet size). */
void tfw_usb_bulk_out(tfw_usb* usb, const uint8_t* packet, uint16_t len);

/* One HID output report received on EP 0x02 (report id first). */
void tfw_usb_hid_out(tfw_usb* usb, const uint8_t* report, uint16_t len);

/* The playout timer's tick: plays a frame, re-arms the OUT endpoints when the FIFO has room
 * again and offers the fill report to both IN endpoints (dropped when still busy). */
void tfw_usb_tick(tfw_usb* usb);

#ifdef __cplusplus
}
#endif

#endif /* TACTILE_FW_USB_H */
