/* USB descriptors of the display; the layout is explained in docs/protocol.md ("USB"). */
#include <string.h>

#include "le_bytes.h"
#include "tactile_fw/usb.h"

static const uint8_t device_descriptor[18] = {18,
                                              TFW_USB_DESC_DEVICE,
                                              0x00,
                                              0x02, /* USB 2.0 */
                                              0x00,
                                              0x00,
                                              0x00, /* class per interface */
                                              TFW_USB_EP0_PACKET,
                                              TFW_USB_VENDOR_ID & 0xFF,
                                              TFW_USB_VENDOR_ID >> 8,
                                              TFW_USB_PRODUCT_ID & 0xFF,
                                              TFW_USB_PRODUCT_ID >> 8,
                                              TFW_USB_BCD_DEVICE & 0xFF,
                                              TFW_USB_BCD_DEVICE >> 8,
                                              1,
                                              2,
                                              3,  /* manufacturer, product, serial strings */
                                              1}; /* one configuration */

/* Required of a high-speed capable device: what it would look like at the other speed. */
static const uint8_t qualifier_descriptor[10] = {
    10, TFW_USB_DESC_DEVICE_QUALIFIER, 0x00, 0x02, 0x00, 0x00, 0x00, TFW_USB_EP0_PACKET, 1, 0};

/* Vendor-defined usage page; five reports, byte arrays: see usb.h for their layout. */
static const uint8_t hid_report_descriptor[] = {0x06, 0x00,
                                                0xFF,       /* usage page (vendor 0xFF00) */
                                                0x09, 0x01, /* usage 1 */
                                                0xA1, 0x01, /* collection (application) */
                                                0x15, 0x00,
                                                0x26, 0xFF,
                                                0x00, 0x75,
                                                0x08, /* bytes 0..255 */
                                                0x85, TFW_HID_REPORT_FRAME,
                                                0x95, TFW_HID_REPORT_BYTES - 1,
                                                0x09, 0x02,
                                                0x91, 0x02, /* output: frame chunk */
                                                0x85, TFW_HID_REPORT_FILL,
                                                0x95, TFW_FILL_BYTES,
                                                0x09, 0x03,
                                                0x81, 0x02, /* input: fill report */
                                                0x85, TFW_HID_REPORT_INFO,
                                                0x95, TFW_INFO_BYTES,
                                                0x09, 0x04,
                                                0xB1, 0x02, /* feature: device information */
                                                0x85, TFW_HID_REPORT_STATUS,
                                                0x95, TFW_STATUS_BYTES,
                                                0x09, 0x05,
                                                0xB1, 0x02, /* feature: status */
                                                0x85, TFW_HID_REPORT_COMMAND,
                                                0x95, TFW_HID_COMMAND_BYTES,
                                                0x09, 0x06,
                                                0xB1, 0x02, /* feature: command */
                                                0xC0};

#define HID_DESCRIPTOR_OFFSET 41u /* of the HID class descriptor inside the configuration */

/* Full-speed values; the high-speed packet sizes and intervals are patched in per speed. */
static const uint8_t configuration_template[TFW_USB_CONFIG_DESCRIPTOR_BYTES] = {
    9, TFW_USB_DESC_CONFIGURATION, TFW_USB_CONFIG_DESCRIPTOR_BYTES, 0, 2, 1, 0, 0x80,
    50, /* bus powered, 100 mA */
    /* interface 0: vendor, frames in on bulk, fill reports out on interrupt */
    9, 4, TFW_USB_VENDOR_INTERFACE, 0, 2, 0xFF, 0x00, 0x00, 0, 7, 5, TFW_USB_EP_FRAMES_OUT, 0x02,
    TFW_USB_BULK_PACKET_FS, 0, 0, 7, 5, TFW_USB_EP_FILL_IN, 0x03, TFW_FILL_BYTES, 0, 1,
    /* interface 1: HID */
    9, 4, TFW_USB_HID_INTERFACE, 0, 2, 0x03, 0x00, 0x00, 0, 9, TFW_USB_DESC_HID, 0x11, 0x01, 0, 1,
    TFW_USB_DESC_HID_REPORT, sizeof hid_report_descriptor, 0, 7, 5, TFW_USB_EP_HID_IN, 0x03,
    TFW_USB_HID_PACKET, 0, 1, 7, 5, TFW_USB_EP_HID_OUT, 0x03, TFW_USB_HID_PACKET, 0, 1};

/* Offsets of the speed-dependent fields in the configuration. */
#define BULK_PACKET_OFFSET 22u
#define FILL_INTERVAL_OFFSET 31u
#define HID_IN_INTERVAL_OFFSET 56u
#define HID_OUT_INTERVAL_OFFSET 63u

static uint16_t string_descriptor(tfw_usb* usb, uint8_t index, const uint8_t** out) {
  uint8_t* d = usb->ep0;
  if (index == 0) {
    const uint8_t langids[4] = {4, TFW_USB_DESC_STRING, 0x09, 0x04}; /* en-US */
    memcpy(d, langids, sizeof langids);
    *out = d;
    return 4;
  }
  const char* text = index == 1   ? "tactile-movies"
                     : index == 2 ? "Tactile display"
                     : index == 3 ? usb->serial
                                  : NULL;
  if (text == NULL) return 0;
  /* ASCII to UTF-16LE, cut to what the reply buffer holds. */
  size_t n = strlen(text);
  const size_t max_chars = (sizeof usb->ep0 - 2u) / 2u;
  if (n > max_chars) n = max_chars;
  d[0] = (uint8_t)(2u + 2u * n);
  d[1] = TFW_USB_DESC_STRING;
  for (size_t i = 0; i < n; ++i) {
    d[2 + 2 * i] = (uint8_t)text[i];
    d[3 + 2 * i] = 0;
  }
  *out = d;
  return d[0];
}

void tfw_usb_build_configuration(uint8_t speed, uint8_t* out) {
  memcpy(out, configuration_template, sizeof configuration_template);
  if (speed == TFW_USB_HIGH_SPEED) {
    tfw_put_u16(out + BULK_PACKET_OFFSET, TFW_USB_BULK_PACKET_HS);
    out[FILL_INTERVAL_OFFSET] = 4;   /* 2^(4-1) microframes = 1 ms */
    out[HID_IN_INTERVAL_OFFSET] = 1; /* every 125 us microframe */
    out[HID_OUT_INTERVAL_OFFSET] = 1;
  }
}

uint16_t tfw_usb_descriptor(tfw_usb* usb, uint8_t type, uint8_t index, const uint8_t** out) {
  switch (type) {
    case TFW_USB_DESC_DEVICE:
      *out = device_descriptor;
      return sizeof device_descriptor;
    case TFW_USB_DESC_CONFIGURATION:
      *out = usb->configuration;
      return TFW_USB_CONFIG_DESCRIPTOR_BYTES;
    case TFW_USB_DESC_DEVICE_QUALIFIER:
      *out = qualifier_descriptor;
      return sizeof qualifier_descriptor;
    case TFW_USB_DESC_STRING:
      return string_descriptor(usb, index, out);
    case TFW_USB_DESC_HID:
      *out = usb->configuration + HID_DESCRIPTOR_OFFSET;
      return 9;
    case TFW_USB_DESC_HID_REPORT:
      *out = hid_report_descriptor;
      return sizeof hid_report_descriptor;
    default:
      return 0;
  }
}
