/* USB class logic: control requests and frame assembly; see tactile_fw/usb.h. */
#include <string.h>

#include "le_bytes.h"
#include "tactile_fw/usb.h"

#define REQ_TYPE_MASK 0x60u
#define REQ_TYPE_STANDARD 0x00u
#define REQ_TYPE_CLASS 0x20u
#define REQ_TYPE_VENDOR 0x40u
#define REQ_DEVICE_TO_HOST 0x80u

#define STD_GET_CONFIGURATION 8u
#define STD_GET_DESCRIPTOR 6u
#define STD_SET_CONFIGURATION 9u
#define STD_SET_INTERFACE 11u
#define HID_GET_REPORT 0x01u
#define HID_SET_REPORT 0x09u
#define HID_SET_IDLE 0x0Au
#define HID_REPORT_TYPE_INPUT 1u
#define HID_REPORT_TYPE_OUTPUT 2u
#define HID_REPORT_TYPE_FEATURE 3u

void tfw_usb_init(tfw_usb* usb, tfw_device* dev, const tfw_usb_dcd* dcd, tfw_usb_speed speed,
                  const char* serial) {
  memset(usb, 0, sizeof *usb);
  usb->dev = dev;
  usb->dcd = *dcd;
  usb->speed = (uint8_t)speed;
  usb->serial = serial != NULL ? serial : "0";
  tfw_usb_build_configuration(usb->speed, usb->configuration);
}

static uint16_t bulk_packet(const tfw_usb* usb) {
  return usb->speed == TFW_USB_HIGH_SPEED ? TFW_USB_BULK_PACKET_HS : TFW_USB_BULK_PACKET_FS;
}

/* NAK only while a stream waits for room: a stopped device keeps accepting (and counting as
 * not_started) so that a host sending to it gets answers instead of blocking forever. */
static void arm_out_endpoints(tfw_usb* usb) {
  if (!usb->configured) return;
  const int ready = usb->dev->state == TFW_STATE_STOPPED || tfw_device_can_receive(usb->dev);
  usb->dcd.set_out_ready(usb->dcd.context, TFW_USB_EP_FRAMES_OUT, ready);
  usb->dcd.set_out_ready(usb->dcd.context, TFW_USB_EP_HID_OUT, ready);
}

static int reply(tfw_usb* usb, const uint8_t* data, uint16_t len, uint16_t w_length) {
  usb->dcd.write(usb->dcd.context, 0x80u, data, len < w_length ? len : w_length);
  return 1;
}

static int acknowledge(tfw_usb* usb) {
  usb->dcd.write(usb->dcd.context, 0x80u, NULL, 0);
  return 1;
}

static int refuse(tfw_usb* usb) {
  usb->dcd.stall(usb->dcd.context, 0x00u);
  return 0;
}

/* START, STOP and SET_LIMITS, shared by the vendor requests and the HID command report. */
static int run_command(tfw_usb* usb, uint8_t request, uint16_t value, const uint8_t* data,
                       uint16_t len) {
  switch (request) {
    case TFW_USB_REQ_START:
      if (len != 0 && data == NULL) return 0;
      if (tfw_device_start(usb->dev, value) != TFW_CONFIG_OK) return 0;
      break;
    case TFW_USB_REQ_STOP:
      tfw_device_stop(usb->dev);
      break;
    case TFW_USB_REQ_SET_LIMITS:
      if (data == NULL || len != TFW_USB_LIMITS_BYTES) return 0;
      if (tfw_device_set_limits(usb->dev, tfw_get_i16(data), tfw_get_i16(data + 2),
                                tfw_get_u32(data + 4)) != TFW_CONFIG_OK) {
        return 0;
      }
      break;
    default:
      return 0;
  }
  /* A start or stop empties the FIFO and restarts frame assembly. */
  usb->bulk.length = 0;
  usb->bulk.discarding = 0;
  usb->hid.length = 0;
  usb->hid.discarding = 0;
  arm_out_endpoints(usb);
  return 1;
}

static int standard_request(tfw_usb* usb, const uint8_t* setup, uint16_t w_length) {
  const uint8_t request = setup[1];
  const uint16_t value = tfw_get_u16(setup + 2);
  if (request == STD_GET_DESCRIPTOR && (setup[0] & REQ_DEVICE_TO_HOST)) {
    const uint8_t* d = NULL;
    const uint16_t len = tfw_usb_descriptor(usb, (uint8_t)(value >> 8), (uint8_t)value, &d);
    return len == 0 ? refuse(usb) : reply(usb, d, len, w_length);
  }
  if (request == STD_SET_CONFIGURATION && value <= 1u) {
    usb->configured = (uint8_t)value;
    arm_out_endpoints(usb);
    return acknowledge(usb);
  }
  if (request == STD_GET_CONFIGURATION) return reply(usb, &usb->configured, 1, w_length);
  if (request == STD_SET_INTERFACE && value == 0u) return acknowledge(usb);
  return refuse(usb);
}

static int hid_request(tfw_usb* usb, const uint8_t* setup, const uint8_t* data, uint16_t len,
                       uint16_t w_length) {
  const uint8_t request = setup[1];
  const uint8_t report_type = setup[3];
  const uint8_t report_id = setup[2];
  uint8_t* out = usb->ep0;
  if (request == HID_SET_IDLE) return acknowledge(usb);
  if (request == HID_GET_REPORT) {
    size_t n = 0;
    out[0] = report_id;
    if (report_type == HID_REPORT_TYPE_FEATURE && report_id == TFW_HID_REPORT_INFO) {
      n = tfw_encode_info(usb->dev, out + 1, sizeof usb->ep0 - 1u);
    } else if (report_type == HID_REPORT_TYPE_FEATURE && report_id == TFW_HID_REPORT_STATUS) {
      n = tfw_encode_status(usb->dev, out + 1, sizeof usb->ep0 - 1u);
    } else if (report_type == HID_REPORT_TYPE_INPUT && report_id == TFW_HID_REPORT_FILL) {
      n = tfw_encode_fill(usb->dev, out + 1, sizeof usb->ep0 - 1u);
    }
    return n == 0 ? refuse(usb) : reply(usb, out, (uint16_t)(n + 1u), w_length);
  }
  if (request == HID_SET_REPORT && report_type == HID_REPORT_TYPE_FEATURE &&
      report_id == TFW_HID_REPORT_COMMAND && len == TFW_HID_COMMAND_BYTES + 1u && data != NULL &&
      data[0] == TFW_HID_REPORT_COMMAND) {
    const uint8_t* c = data + 1;
    const uint8_t code = c[0];
    const uint16_t data_len = code == TFW_USB_REQ_SET_LIMITS ? TFW_USB_LIMITS_BYTES : 0u;
    return run_command(usb, code, tfw_get_u16(c + 2), c + 4, data_len) ? acknowledge(usb)
                                                                       : refuse(usb);
  }
  if (request == HID_SET_REPORT && report_type == HID_REPORT_TYPE_OUTPUT && data != NULL) {
    /* Hosts without an interrupt OUT pipe send output reports on the control pipe. */
    tfw_usb_hid_out(usb, data, len);
    return acknowledge(usb);
  }
  return refuse(usb);
}

static int vendor_request(tfw_usb* usb, const uint8_t* setup, const uint8_t* data, uint16_t len,
                          uint16_t w_length) {
  const uint8_t request = setup[1];
  const uint16_t value = tfw_get_u16(setup + 2);
  if (setup[0] & REQ_DEVICE_TO_HOST) {
    size_t n = 0;
    if (request == TFW_USB_REQ_GET_INFO) {
      n = tfw_encode_info(usb->dev, usb->ep0, sizeof usb->ep0);
    } else if (request == TFW_USB_REQ_GET_STATUS) {
      n = tfw_encode_status(usb->dev, usb->ep0, sizeof usb->ep0);
    }
    return n == 0 ? refuse(usb) : reply(usb, usb->ep0, (uint16_t)n, w_length);
  }
  return run_command(usb, request, value, data, len) ? acknowledge(usb) : refuse(usb);
}

int tfw_usb_setup(tfw_usb* usb, const uint8_t setup[8], const uint8_t* data, uint16_t data_len) {
  const uint16_t index = tfw_get_u16(setup + 4);
  const uint16_t w_length = tfw_get_u16(setup + 6);
  /* An OUT data stage must be exactly as long as announced. */
  if (!(setup[0] & REQ_DEVICE_TO_HOST) && data_len != w_length) return refuse(usb);
  switch (setup[0] & REQ_TYPE_MASK) {
    case REQ_TYPE_STANDARD:
      return standard_request(usb, setup, w_length);
    case REQ_TYPE_CLASS:
      if (index != TFW_USB_HID_INTERFACE) return refuse(usb);
      return hid_request(usb, setup, data, data_len, w_length);
    case REQ_TYPE_VENDOR:
      if (index != TFW_USB_VENDOR_INTERFACE) return refuse(usb);
      return vendor_request(usb, setup, data, data_len, w_length);
    default:
      return refuse(usb);
  }
}

/* Hands a complete transfer to the device, or counts a discarded one as bad_length (the
 * device classifies a zero-length frame as such). */
static void finish_frame(tfw_usb* usb, tfw_usb_assembly* a) {
  tfw_device_receive(usb->dev, a->buffer, a->discarding ? 0u : a->length);
  a->length = 0;
  a->discarding = 0;
  arm_out_endpoints(usb);
}

static void append(tfw_usb_assembly* a, const uint8_t* bytes, uint16_t len) {
  if (a->discarding) return;
  if ((size_t)a->length + len > sizeof a->buffer) {
    a->discarding = 1;
    return;
  }
  memcpy(a->buffer + a->length, bytes, len);
  a->length = (uint16_t)(a->length + len);
}

void tfw_usb_bulk_out(tfw_usb* usb, const uint8_t* packet, uint16_t len) {
  const uint16_t max_packet = bulk_packet(usb);
  if (len > max_packet) len = max_packet; /* a controller never delivers more */
  append(&usb->bulk, packet, len);
  /* A short (or zero-length) packet ends the transfer, and with it the frame. */
  if (len < max_packet) finish_frame(usb, &usb->bulk);
}

void tfw_usb_hid_out(tfw_usb* usb, const uint8_t* report, uint16_t len) {
  tfw_usb_assembly* a = &usb->hid;
  const int well_formed = len >= 3u && report[0] == TFW_HID_REPORT_FRAME && report[2] >= 1u &&
                          report[2] <= TFW_HID_CHUNK_PAYLOAD && report[2] <= len - 3u;
  if (!well_formed) {
    a->discarding = 1;
    finish_frame(usb, a);
    return;
  }
  const uint8_t flags = report[1];
  if (flags & TFW_HID_CHUNK_FIRST) {
    /* A new frame before the last one ended: the partial one is lost. */
    if (a->length != 0 || a->discarding) {
      a->discarding = 1;
      finish_frame(usb, a);
    }
  } else if (a->length == 0) {
    a->discarding = 1; /* a continuation of nothing */
  }
  append(a, report + 3, report[2]);
  if (flags & TFW_HID_CHUNK_LAST) finish_frame(usb, a);
}

void tfw_usb_tick(tfw_usb* usb) {
  tfw_device_tick(usb->dev);
  if (!usb->configured) return;
  arm_out_endpoints(usb);
  uint8_t report[1 + TFW_FILL_BYTES];
  report[0] = TFW_HID_REPORT_FILL;
  tfw_encode_fill(usb->dev, report + 1, TFW_FILL_BYTES);
  usb->dcd.write(usb->dcd.context, TFW_USB_EP_FILL_IN, report + 1, TFW_FILL_BYTES);
  usb->dcd.write(usb->dcd.context, TFW_USB_EP_HID_IN, report, sizeof report);
}
