// The Pico W's USB device (usb_device.c): two CDC ACM ports, the log and the
// protocol port, driven from the main loop. A C interface, so the C++ code
// never includes TinyUSB's headers (usb_cdc_port.hpp wraps it).
#ifndef ROTORD_USB_DEVICE_H
#define ROTORD_USB_DEVICE_H

#include <stdbool.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/// CDC interface numbers as TinyUSB counts them (tud_cdc_n_*).
enum { ROTORD_USB_LOG_CDC = 0, ROTORD_USB_PROTOCOL_CDC = 1 };

/// Starts TinyUSB. `protocol_name` (e.g. "Yaesu GS-232") adds the protocol
/// port, named "rotord <protocol_name>"; NULL offers the log port only.
/// Call once, before stdio_init_all() (pico_stdio_usb expects TinyUSB up).
void rotord_usb_init(const char* protocol_name);
/// TinyUSB's device task; call on every pass of the main loop. Never blocks.
void rotord_usb_task(void);

bool rotord_usb_cdc_ready(uint8_t itf);
bool rotord_usb_cdc_dtr(uint8_t itf);
uint32_t rotord_usb_cdc_opens(uint8_t itf);
uint32_t rotord_usb_cdc_read(uint8_t itf, void* buffer, uint32_t max_bytes);
uint32_t rotord_usb_cdc_write_available(uint8_t itf);
uint32_t rotord_usb_cdc_write(uint8_t itf, const void* data, uint32_t bytes);
void rotord_usb_cdc_flush(uint8_t itf);
void rotord_usb_cdc_discard_output(uint8_t itf);
void rotord_usb_cdc_discard_input(uint8_t itf);

#ifdef __cplusplus
}
#endif

#endif
