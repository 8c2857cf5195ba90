// TinyUSB configuration of the Pico W firmware: two CDC ACM interfaces, the
// log (pico_stdio_usb, CDC 0) and the protocol port (usb.personality, CDC 1),
// plus the SDK's reset interface for picotool (usb_device.c).
//
// The firmware links tinyusb_device itself, so pico_stdio_usb leaves TinyUSB
// to it: tusb_init() before stdio_init_all(), tud_task() from the main loop
// (no background interrupt task, so TinyUSB never runs while the loop is in
// the middle of a CDC call) and our own descriptors. The SDK's own
// tusb_config.h (pico_stdio_usb) is bypassed; what it sets is repeated here.
#ifndef ROTORD_TUSB_CONFIG_H
#define ROTORD_TUSB_CONFIG_H

// The PICO_STDIO_USB_* defaults (reset interface features), which the SDK's
// reset_interface.c reads through this file, as with the SDK's own config.
#include "pico/stdio_usb.h"

#define CFG_TUSB_RHPORT0_MODE (OPT_MODE_DEVICE)

#define CFG_TUD_CDC (2)

// FIFO sizes per CDC interface. 256 bytes of TX take a GS-232 or WRC reply
// several times over while the loop is busy; the link (usb_cdc_link.hpp)
// buffers what does not fit. RX: what the host may send ahead of the loop
// before TinyUSB NAKs it (USB's own flow control).
#define CFG_TUD_CDC_RX_BUFSIZE (256)
#define CFG_TUD_CDC_TX_BUFSIZE (256)
// One full-speed bulk packet.
#define CFG_TUD_CDC_EP_BUFSIZE (64)

// As in the SDK's pico_stdio_usb: the vendor driver only serves the
// Microsoft OS 2.0 descriptor of the reset interface (driverless picotool
// on Windows).
#define CFG_TUD_VENDOR (1)
#define CFG_TUD_VENDOR_RX_BUFSIZE (256)
#define CFG_TUD_VENDOR_TX_BUFSIZE (256)

#endif
