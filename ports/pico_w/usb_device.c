// The Pico W's USB device: descriptors, TinyUSB callbacks and the few CDC
// calls the protocol port needs (usb_device.h), in C because TinyUSB's
// descriptor macros and inline functions are C (old-style casts that our C++
// warning flags reject).
//
// Layout (two CDC ACM functions, each with an interface association):
//   interfaces 0-1  CDC 0 "rotord log": pico_stdio_usb (printf)
//   interface  2    the SDK's reset interface (picotool reboot), at the
//                   number the SDK's Microsoft OS 2.0 descriptor names
//   interfaces 3-4  CDC 1 "rotord <protocol>": usb.personality
// With usb.personality = off only CDC 0 and the reset interface are
// offered, exactly as the SDK's default descriptors do.
//
// Why two ports and not the protocol alone with the log on a UART: the
// UART pins are free for wiring (pins.i2c_sda/scl default to GPIO 0/1), and
// a Pico W in the shack has no other way to show what it is doing than its
// USB log; a second CDC interface costs 4 endpoints and ~600 bytes of RAM.
#include "usb_device.h"

#include <stddef.h>
#include <string.h>

#include "pico/bootrom.h"
#include "pico/stdio_usb.h"
#include "pico/stdio_usb/reset_interface.h"
#include "pico/unique_id.h"
#include "tusb.h"

#if !PICO_STDIO_USB_ENABLE_RESET_VIA_VENDOR_INTERFACE
#error "the reset interface at interface 2 is part of this layout"
#endif

#define USBD_VID (0x2E8A)  // Raspberry Pi
#define USBD_PID (0x000a)  // Raspberry Pi Pico SDK CDC (RP2040), as pico_stdio_usb

// The two layouts differ in bcdDevice, so a host that caches per VID, PID
// and revision (Windows) never applies one layout's records to the other.
#define USBD_BCD_LOG_ONLY (0x0100)
#define USBD_BCD_LOG_AND_PROTOCOL (0x0200)

enum {
  kItfLogCdc = 0,  // and 1
  kItfReset = 2,
  kItfProtocolCdc = 3,  // and 4
};

enum {
  kStrLangId = 0,
  kStrManufacturer,
  kStrProduct,
  kStrSerial,
  kStrLogCdc,
  kStrReset,
  kStrProtocolCdc,
  kStrCount,
};

#define EP_LOG_NOTIFY (0x81)
#define EP_LOG_OUT (0x02)
#define EP_LOG_IN (0x82)
#define EP_PROTOCOL_NOTIFY (0x83)
#define EP_PROTOCOL_OUT (0x04)
#define EP_PROTOCOL_IN (0x84)
#define CDC_NOTIFY_BYTES (8)
#define CDC_DATA_BYTES (64)

#define RESET_DESC_LEN (9)
#define LOG_ONLY_LEN (TUD_CONFIG_DESC_LEN + TUD_CDC_DESC_LEN + RESET_DESC_LEN)
#define LOG_AND_PROTOCOL_LEN (LOG_ONLY_LEN + TUD_CDC_DESC_LEN)

// Bus powered, 250 mA: the SDK's values.
#define CONFIG_ATTRIBUTES (0)
#define CONFIG_POWER_MA (250)

#define RESET_DESCRIPTOR(itf, str)                                                         \
  9, TUSB_DESC_INTERFACE, itf, 0, 0, TUSB_CLASS_VENDOR_SPECIFIC, RESET_INTERFACE_SUBCLASS, \
      RESET_INTERFACE_PROTOCOL, str

static const uint8_t config_log_only[LOG_ONLY_LEN] = {
    TUD_CONFIG_DESCRIPTOR(1, 3, 0, LOG_ONLY_LEN, CONFIG_ATTRIBUTES, CONFIG_POWER_MA),
    TUD_CDC_DESCRIPTOR(kItfLogCdc, kStrLogCdc, EP_LOG_NOTIFY, CDC_NOTIFY_BYTES, EP_LOG_OUT,
                       EP_LOG_IN, CDC_DATA_BYTES),
    RESET_DESCRIPTOR(kItfReset, kStrReset),
};

static const uint8_t config_log_and_protocol[LOG_AND_PROTOCOL_LEN] = {
    TUD_CONFIG_DESCRIPTOR(1, 5, 0, LOG_AND_PROTOCOL_LEN, CONFIG_ATTRIBUTES, CONFIG_POWER_MA),
    TUD_CDC_DESCRIPTOR(kItfLogCdc, kStrLogCdc, EP_LOG_NOTIFY, CDC_NOTIFY_BYTES, EP_LOG_OUT,
                       EP_LOG_IN, CDC_DATA_BYTES),
    RESET_DESCRIPTOR(kItfReset, kStrReset),
    TUD_CDC_DESCRIPTOR(kItfProtocolCdc, kStrProtocolCdc, EP_PROTOCOL_NOTIFY, CDC_NOTIFY_BYTES,
                       EP_PROTOCOL_OUT, EP_PROTOCOL_IN, CDC_DATA_BYTES),
};

static tusb_desc_device_t device_descriptor = {
    .bLength = sizeof(tusb_desc_device_t),
    .bDescriptorType = TUSB_DESC_DEVICE,
    // 2.1: the reset interface's Microsoft OS 2.0 descriptor (in the SDK's
    // reset_interface.c) is found through the BOS descriptor.
    .bcdUSB = 0x0210,
    .bDeviceClass = TUSB_CLASS_MISC,
    .bDeviceSubClass = MISC_SUBCLASS_COMMON,
    .bDeviceProtocol = MISC_PROTOCOL_IAD,
    .bMaxPacketSize0 = CFG_TUD_ENDPOINT0_SIZE,
    .idVendor = USBD_VID,
    .idProduct = USBD_PID,
    .bcdDevice = USBD_BCD_LOG_ONLY,
    .iManufacturer = kStrManufacturer,
    .iProduct = kStrProduct,
    .iSerialNumber = kStrSerial,
    .bNumConfigurations = 1,
};

static bool protocol_port = false;
static char serial_string[PICO_UNIQUE_BOARD_ID_SIZE_BYTES * 2 + 1];
static char protocol_string[40] = "rotord protocol";
static const char* strings[kStrCount] = {
    [kStrManufacturer] = "Raspberry Pi",
    [kStrProduct] = "rotord",
    [kStrSerial] = serial_string,
    [kStrLogCdc] = "rotord log",
    [kStrReset] = "Reset",
    [kStrProtocolCdc] = protocol_string,
};

// DTR rising edges per CDC interface (tud_cdc_line_state_cb): lets the link
// see a program that closed and reopened the port between two loop passes.
static volatile uint32_t cdc_opens[CFG_TUD_CDC];
static bool cdc_dtr[CFG_TUD_CDC];

void rotord_usb_init(const char* protocol_name) {
  protocol_port = protocol_name != NULL;
  if (protocol_port) {
    strcpy(protocol_string, "rotord ");
    strncat(protocol_string, protocol_name, sizeof protocol_string - strlen(protocol_string) - 1);
    device_descriptor.bcdDevice = USBD_BCD_LOG_AND_PROTOCOL;
  }
  pico_get_unique_board_id_string(serial_string, sizeof serial_string);
  tusb_init();
}

void rotord_usb_task(void) {
  tud_task();
}

bool rotord_usb_cdc_ready(uint8_t itf) {
  return tud_cdc_n_ready(itf);
}

bool rotord_usb_cdc_dtr(uint8_t itf) {
  return tud_cdc_n_connected(itf);
}

uint32_t rotord_usb_cdc_opens(uint8_t itf) {
  return itf < CFG_TUD_CDC ? cdc_opens[itf] : 0;
}

uint32_t rotord_usb_cdc_read(uint8_t itf, void* buffer, uint32_t max_bytes) {
  return tud_cdc_n_available(itf) > 0 ? tud_cdc_n_read(itf, buffer, max_bytes) : 0;
}

uint32_t rotord_usb_cdc_write_available(uint8_t itf) {
  return tud_cdc_n_write_available(itf);
}

uint32_t rotord_usb_cdc_write(uint8_t itf, const void* data, uint32_t bytes) {
  return tud_cdc_n_write(itf, data, bytes);
}

void rotord_usb_cdc_flush(uint8_t itf) {
  tud_cdc_n_write_flush(itf);
}

void rotord_usb_cdc_discard_output(uint8_t itf) {
  tud_cdc_n_write_clear(itf);
}

void rotord_usb_cdc_discard_input(uint8_t itf) {
  tud_cdc_n_read_flush(itf);
}

// --- TinyUSB callbacks (run inside tud_task(), i.e. in the main loop) -----

const uint8_t* tud_descriptor_device_cb(void) {
  return (const uint8_t*)&device_descriptor;
}

const uint8_t* tud_descriptor_configuration_cb(uint8_t index) {
  (void)index;
  return protocol_port ? config_log_and_protocol : config_log_only;
}

const uint16_t* tud_descriptor_string_cb(uint8_t index, uint16_t langid) {
  (void)langid;
  static uint16_t utf16[1 + 40];
  size_t chars = 0;
  if (index == kStrLangId) {
    utf16[1] = 0x0409;  // English (US)
    chars = 1;
  } else {
    if (index >= kStrCount || strings[index] == NULL) return NULL;
    const char* text = strings[index];
    while (chars < sizeof utf16 / sizeof utf16[0] - 1 && text[chars] != '\0') {
      utf16[1 + chars] = (uint8_t)text[chars];
      ++chars;
    }
  }
  utf16[0] = (uint16_t)((TUSB_DESC_STRING << 8) | (2 * chars + 2));
  return utf16;
}

void tud_cdc_line_state_cb(uint8_t itf, bool dtr, bool rts) {
  (void)rts;
  if (itf >= CFG_TUD_CDC) return;
  if (dtr && !cdc_dtr[itf]) ++cdc_opens[itf];
  cdc_dtr[itf] = dtr;
}

// The SDK's "1200 baud resets into BOOTSEL" convention, on the log port
// only: a GS-232 program may well open the protocol port at 1200 baud.
void tud_cdc_line_coding_cb(uint8_t itf, const cdc_line_coding_t* coding) {
  if (itf == 0 && coding->bit_rate == PICO_STDIO_USB_RESET_MAGIC_BAUD_RATE)
    rom_reset_usb_boot_extra(-1, PICO_STDIO_USB_RESET_BOOTSEL_INTERFACE_DISABLE_MASK, false);
}

// A bus reset or an unplug clears TinyUSB's line state without a line
// state callback; the next configuration starts with DTR low.
void tud_mount_cb(void) {
  memset(cdc_dtr, 0, sizeof cdc_dtr);
}

void tud_umount_cb(void) {
  memset(cdc_dtr, 0, sizeof cdc_dtr);
}
