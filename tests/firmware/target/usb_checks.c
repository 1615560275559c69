/* USB glue: descriptors parsed back by their generic rules, vendor and HID requests, frame
 * assembly from packets and reports, NAK flow control, fill reports, all over a fake
 * device controller that records what the class logic asked of it. */
#include <string.h>

#include "check.h"
#include "device_config.h"
#include "tactile_fw/usb.h"

typedef struct {
  uint8_t last_ep;
  uint8_t data[256];
  uint16_t len;
  unsigned writes;
  unsigned stalls;
  int ready[3]; /* by OUT endpoint number */
  uint8_t fill[TFW_FILL_BYTES];
  unsigned fill_reports;
} fake_dcd;

static int fake_write(void* context, uint8_t ep, const uint8_t* data, uint16_t len) {
  fake_dcd* f = (fake_dcd*)context;
  if (ep == TFW_USB_EP_FILL_IN) {
    memcpy(f->fill, data, len < sizeof f->fill ? len : sizeof f->fill);
    f->fill_reports++;
    return 1;
  }
  if (ep != 0x80u) return 1;
  f->writes++;
  f->last_ep = ep;
  f->len = len;
  if (len > 0) memcpy(f->data, data, len);
  return 1;
}

static void fake_stall(void* context, uint8_t ep) {
  (void)ep;
  ((fake_dcd*)context)->stalls++;
}

static void fake_ready(void* context, uint8_t ep, int ready) {
  ((fake_dcd*)context)->ready[ep & 3u] = ready;
}

static void setup_packet(uint8_t* s, uint8_t type, uint8_t request, uint16_t value, uint16_t index,
                         uint16_t length) {
  s[0] = type;
  s[1] = request;
  s[2] = (uint8_t)value;
  s[3] = (uint8_t)(value >> 8);
  s[4] = (uint8_t)index;
  s[5] = (uint8_t)(index >> 8);
  s[6] = (uint8_t)length;
  s[7] = (uint8_t)(length >> 8);
}

static int request(tfw_usb* usb, uint8_t type, uint8_t req, uint16_t value, uint16_t index,
                   uint16_t length, const uint8_t* data) {
  uint8_t s[8];
  setup_packet(s, type, req, value, index, length);
  return tfw_usb_setup(usb, s, data, (type & 0x80u) ? 0u : length);
}

static size_t encode(uint32_t seq, int16_t value, uint8_t* out) {
  int16_t v[TFW_TEST_CONTACTORS];
  for (unsigned i = 0; i < TFW_TEST_CONTACTORS; ++i) v[i] = value;
  size_t len = 0;
  tfw_encode_frame(seq, 0, v, TFW_TEST_CONTACTORS, out, TFW_MAX_FRAME_BYTES, &len);
  return len;
}

/* Sends a frame as a bulk transfer: full packets, then the short one ending it. */
static void send_bulk(tfw_usb* usb, const uint8_t* frame, size_t len, uint16_t packet) {
  size_t at = 0;
  for (;;) {
    const size_t n = len - at < packet ? len - at : packet;
    tfw_usb_bulk_out(usb, frame + at, (uint16_t)n);
    at += n;
    if (n < packet) break;
  }
}

static void send_hid(tfw_usb* usb, const uint8_t* frame, size_t len) {
  for (size_t at = 0; at < len; at += TFW_HID_CHUNK_PAYLOAD) {
    uint8_t report[TFW_HID_REPORT_BYTES];
    memset(report, 0, sizeof report);
    const size_t n = len - at < TFW_HID_CHUNK_PAYLOAD ? len - at : TFW_HID_CHUNK_PAYLOAD;
    report[0] = TFW_HID_REPORT_FRAME;
    report[1] =
        (uint8_t)((at == 0 ? TFW_HID_CHUNK_FIRST : 0u) | (at + n == len ? TFW_HID_CHUNK_LAST : 0u));
    report[2] = (uint8_t)n;
    memcpy(report + 3, frame + at, n);
    tfw_usb_hid_out(usb, report, sizeof report);
  }
}

/* Walks a HID report descriptor's short items and returns the byte count declared for
 * `report_id` under main item `main_tag` (0x80 input, 0x90 output, 0xB0 feature). */
static unsigned hid_report_bytes(const uint8_t* d, uint16_t len, uint8_t main_tag,
                                 uint8_t report_id) {
  unsigned size_bits = 0, count = 0, id = 0;
  for (uint16_t i = 0; i < len;) {
    const uint8_t prefix = d[i];
    const unsigned n = (prefix & 3u) == 3u ? 4u : (prefix & 3u);
    unsigned value = 0;
    for (unsigned k = 0; k < n; ++k) value |= (unsigned)d[i + 1 + k] << (8 * k);
    const uint8_t tag = prefix & 0xFCu;
    if (tag == 0x74u) size_bits = value;
    if (tag == 0x94u) count = value;
    if (tag == 0x84u) id = value;
    if (tag == main_tag && id == report_id) return size_bits * count / 8u;
    i = (uint16_t)(i + 1u + n);
  }
  return 0;
}

static void descriptor_checks(tfw_check_run* run, tfw_usb* usb) {
  const uint8_t* d = NULL;
  CHECK(run, tfw_usb_descriptor(usb, TFW_USB_DESC_DEVICE, 0, &d) == 18);
  CHECK(run, d[0] == 18 && d[1] == 1 && d[2] == 0x00 && d[3] == 0x02);
  CHECK(run, d[8] == 0x09 && d[9] == 0x12 && d[10] == 0x01 && d[11] == 0x00); /* 1209:0001 */

  const uint16_t total = tfw_usb_descriptor(usb, TFW_USB_DESC_CONFIGURATION, 0, &d);
  CHECK(run, total == (uint16_t)(d[2] | (d[3] << 8)));
  /* Walk by bLength: the pieces must add up, with the endpoints each interface announces. */
  unsigned interfaces = 0, endpoints = 0, announced = 0, bulk_out_packet = 0, hid_class = 0;
  uint16_t at = 0;
  uint16_t hid_report_len = 0;
  while (at < total && d[at] >= 2) {
    if (d[at + 1] == 4) {
      interfaces++;
      announced += d[at + 4];
      if (d[at + 5] == 3) hid_class = 1;
    }
    if (d[at + 1] == 5) {
      endpoints++;
      if (d[at + 2] == TFW_USB_EP_FRAMES_OUT && d[at + 3] == 2) {
        bulk_out_packet = (unsigned)(d[at + 4] | (d[at + 5] << 8));
      }
    }
    if (d[at + 1] == TFW_USB_DESC_HID) hid_report_len = (uint16_t)(d[at + 7] | (d[at + 8] << 8));
    at = (uint16_t)(at + d[at]);
  }
  CHECK(run, at == total && interfaces == 2 && d[4] == 2);
  CHECK(run, endpoints == 4 && announced == 4 && hid_class);
  CHECK(run, bulk_out_packet == (usb->speed == TFW_USB_HIGH_SPEED ? 512u : 64u));

  const uint8_t* report = NULL;
  CHECK(run, tfw_usb_descriptor(usb, TFW_USB_DESC_HID_REPORT, 0, &report) == hid_report_len);
  CHECK(run, hid_report_bytes(report, hid_report_len, 0x90, TFW_HID_REPORT_FRAME) == 63);
  CHECK(run, hid_report_bytes(report, hid_report_len, 0x80, TFW_HID_REPORT_FILL) == 16);
  CHECK(run, hid_report_bytes(report, hid_report_len, 0xB0, TFW_HID_REPORT_INFO) == 48);
  CHECK(run, hid_report_bytes(report, hid_report_len, 0xB0, TFW_HID_REPORT_STATUS) == 96);
  CHECK(run, hid_report_bytes(report, hid_report_len, 0xB0, TFW_HID_REPORT_COMMAND) == 12);

  CHECK(run, tfw_usb_descriptor(usb, TFW_USB_DESC_STRING, 2, &d) == 2 + 2 * 15);
  CHECK(run, d[2] == 'T' && d[3] == 0 && d[30] == 'y'); /* "Tactile display" in UTF-16LE */
  CHECK(run, tfw_usb_descriptor(usb, TFW_USB_DESC_STRING, 9, &d) == 0);
}

void usb_checks(tfw_check_run* run) {
  static tfw_device dev;
  static tfw_usb usb;
  static fake_dcd fake;
  static uint8_t frame[TFW_MAX_FRAME_BYTES];
  const tfw_config config = tfw_test_stress_config();
  tfw_device_init(&dev, &config, NULL);
  memset(&fake, 0, sizeof fake);
  const tfw_usb_dcd dcd = {&fake, fake_write, fake_stall, fake_ready};

  tfw_usb_init(&usb, &dev, &dcd, TFW_USB_HIGH_SPEED, "SN1");
  descriptor_checks(run, &usb);
  tfw_usb_init(&usb, &dev, &dcd, TFW_USB_FULL_SPEED, "SN1");
  descriptor_checks(run, &usb);

  /* Standard requests: descriptor cut to wLength, configuration, unknown request stalls. */
  CHECK(run, request(&usb, 0x80, 6, 0x0100, 0, 8, NULL) && fake.len == 8);
  CHECK(run, request(&usb, 0x00, 9, 1, 0, 0, NULL) && usb.configured == 1);
  CHECK(run, fake.ready[1] == 1 && fake.ready[2] == 1);
  CHECK(run, !request(&usb, 0x00, 0x33, 0, 0, 0, NULL) && fake.stalls == 1);

  /* Vendor requests. */
  CHECK(run, request(&usb, 0xC1, TFW_USB_REQ_GET_INFO, 0, 0, 64, NULL) && fake.len == 48);
  CHECK(run, fake.data[2] == 10 && fake.data[10] == 0xE8);                /* rows, max rate 1000 */
  CHECK(run, !request(&usb, 0xC1, TFW_USB_REQ_GET_INFO, 0, 1, 64, NULL)); /* wrong interface */
  CHECK(run, !request(&usb, 0x41, TFW_USB_REQ_START, 2000, 0, 0, NULL));  /* above 1 kHz */
  CHECK(run, request(&usb, 0x41, TFW_USB_REQ_START, 500, 0, 0, NULL));
  CHECK(run, dev.state == TFW_STATE_IDLE && dev.config.rate_hz == 500);
  const uint8_t narrower[8] = {0x38, 0xFF, 0xC8, 0x00, 0x50, 0xC3, 0x00, 0x00}; /* -200 200 50000 */
  const uint8_t wider[8] = {0x00, 0xF0, 0xC8, 0x00, 0x50, 0xC3, 0x00, 0x00};    /* -4096 */
  CHECK(run, request(&usb, 0x41, TFW_USB_REQ_SET_LIMITS, 0, 0, 8, narrower));
  CHECK(run, dev.config.deflection_min == -200 && dev.config.max_slew_per_s == 50000);
  CHECK(run, !request(&usb, 0x41, TFW_USB_REQ_SET_LIMITS, 0, 0, 8, wider));
  CHECK(run, !request(&usb, 0x41, TFW_USB_REQ_SET_LIMITS, 0, 0, 7, narrower));
  CHECK(run, dev.config.deflection_min == -200);

  /* Bulk frames: one transfer per frame; an overlong transfer is one bad_length. */
  size_t len = encode(1, 10, frame);
  send_bulk(&usb, frame, len, 64);
  tfw_status s;
  tfw_device_status(&dev, &s);
  CHECK(run, s.frames_received == 1 && s.malformed_total == 0);
  uint8_t junk[64];
  memset(junk, 0x11, sizeof junk);
  for (int i = 0; i < 9; ++i) tfw_usb_bulk_out(&usb, junk, 64); /* 576 > 528 bytes */
  tfw_usb_bulk_out(&usb, junk, 3);
  tfw_device_status(&dev, &s);
  CHECK(run, s.rejected[TFW_ERR_BAD_LENGTH] == 1 && s.frames_received == 1);

  /* Flow control: a full FIFO NAKs the OUT endpoints until a tick makes room. */
  for (uint32_t seq = 2; seq <= TFW_FIFO_CAPACITY; ++seq) {
    len = encode(seq, 10, frame);
    send_bulk(&usb, frame, len, 64);
  }
  CHECK(run, fake.ready[1] == 0 && fake.ready[2] == 0);
  tfw_usb_tick(&usb);
  CHECK(run, fake.ready[1] == 1 && fake.fill_reports == 1);
  /* Fill report: 63 frames left of 64, one played. */
  CHECK(run, fake.fill[2] == TFW_FIFO_CAPACITY - 1u && fake.fill[4] == TFW_FIFO_CAPACITY);
  CHECK(run, fake.fill[8] == 1);

  /* HID: the same frames in chunks; a chunk out of place is dropped and counted. */
  CHECK(run,
        request(&usb, 0x21, 0x09, 0x0305, 1, 13,
                (const uint8_t[]){5, TFW_USB_REQ_START, 0, 0xE8, 0x03, 0, 0, 0, 0, 0, 0, 0, 0}));
  CHECK(run, dev.config.rate_hz == 1000 && tfw_fifo_count(&dev.fifo) == 0);
  len = encode(1, 20, frame);
  send_hid(&usb, frame, len);
  tfw_device_status(&dev, &s);
  CHECK(run, s.frames_received == 1 && s.malformed_total == 0);
  uint8_t middle[TFW_HID_REPORT_BYTES] = {TFW_HID_REPORT_FRAME, 0, 10};
  tfw_usb_hid_out(&usb, middle, sizeof middle);
  middle[1] = TFW_HID_CHUNK_LAST;
  tfw_usb_hid_out(&usb, middle, sizeof middle);
  uint8_t bad_id[TFW_HID_REPORT_BYTES] = {7, TFW_HID_CHUNK_FIRST | TFW_HID_CHUNK_LAST, 10};
  tfw_usb_hid_out(&usb, bad_id, sizeof bad_id);
  len = encode(2, 30, frame);
  send_hid(&usb, frame, len);
  tfw_device_status(&dev, &s);
  CHECK(run, s.frames_received == 2 && s.rejected[TFW_ERR_BAD_LENGTH] == 2);
  CHECK(run, request(&usb, 0xA1, 0x01, 0x0304, 1, 200, NULL) && fake.len == 97);
  CHECK(run, fake.data[0] == TFW_HID_REPORT_STATUS && fake.data[1 + 8] == 2); /* received */
  CHECK(run, !request(&usb, 0xA1, 0x01, 0x0309, 1, 200, NULL));               /* no report 9 */

  /* Stopped: frames are still taken (and counted as not_started), never NAKed forever. */
  CHECK(run, request(&usb, 0x41, TFW_USB_REQ_STOP, 0, 0, 0, NULL));
  len = encode(3, 30, frame);
  send_bulk(&usb, frame, len, 64);
  tfw_device_status(&dev, &s);
  CHECK(run, s.rejected[TFW_ERR_NOT_STARTED] == 1 && fake.ready[1] == 1);
}
