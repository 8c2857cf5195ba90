#pragma once
// lwIP configuration of the Pico W firmware (pico_cyw43_arch_lwip_poll).
// Modelled on pico-examples' lwipopts_examples_common.h, sized for rotord:
// a handful of protocol ports with a few clients each, static pools only.

// Poll mode: lwIP runs only from cyw43_arch_poll() in the main loop, the
// same loop that ticks the controller, so no locks are needed anywhere.
#define NO_SYS 1
#define LWIP_SOCKET 0
#define LWIP_NETCONN 0

// Static memory: no malloc after start-up.
#define MEM_LIBC_MALLOC 0
#define MEM_ALIGNMENT 4
#define MEM_SIZE 16000
#define MEMP_NUM_TCP_SEG 32
#define MEMP_NUM_ARP_QUEUE 10
// Receive buffers (about 1.5 KB each): two full TCP windows and more. 21, not
// the SDK examples' 24: the wind stow's settings and state took the RAM of
// three (ports/pico_w/README.md, "RAM").
#define PBUF_POOL_SIZE 21
// Pbufs that reference data in flash: the web UI's files go out without a
// copy (lwip_transport.hpp, ServerConfig::is_immutable).
#define MEMP_NUM_PBUF 32

// Connections: the static slots of network_services.cpp (web 4, WRC 4,
// rotctld 3, GS-232 2, Easycomm 2, seed 2: 17), the MQTT broker's (1), plus 5
// for refused clients, pcbs in TIME_WAIT and the line ports' one shared
// STOP-only exchange (network_services.cpp; when they run out, lwIP reuses the
// oldest TIME_WAIT pcb). Listeners: one per protocol port (web, WRC, rotctld,
// GS-232, Easycomm, seed: 6).
#define MEMP_NUM_TCP_PCB 23
#define MEMP_NUM_TCP_PCB_LISTEN 6
// UDP: DHCP client and server, DNS, SNTP, mDNS, and the two rotor
// message ports (N1MM+, PstRotator; docs/protocols/udp.md).
#define MEMP_NUM_UDP_PCB 8

#define LWIP_ARP 1
#define LWIP_ETHERNET 1
#define LWIP_ICMP 1
#define LWIP_RAW 1
#define LWIP_IPV4 1
#define LWIP_TCP 1
#define LWIP_UDP 1
#define LWIP_DNS 1
#define LWIP_DHCP 1
#define LWIP_TCP_KEEPALIVE 1
// mDNS (rotord.local, _http._tcp and _rotctld._tcp): multicast needs IGMP, the responder keeps
// per-netif data and runs a few timers of its own (probing, announcing).
#define LWIP_MDNS_RESPONDER 1
#define LWIP_IGMP 1
#define LWIP_NUM_NETIF_CLIENT_DATA 1
#define MDNS_MAX_SERVICES 2
// SNTP (apps/sntp, time.sntp_server): one server, by name through DNS. The
// time goes to sntp_clock.cpp, kept as an offset to the monotonic clock; no
// RTC is set (GET /api/status time_utc reads it).
#include <stdint.h>
#ifdef __cplusplus
extern "C" {
#endif
void rotord_sntp_set_time_us(uint32_t sec, uint32_t us);
#ifdef __cplusplus
}
#endif
#define SNTP_SERVER_DNS 1
#define SNTP_SET_SYSTEM_TIME_US(sec, us) rotord_sntp_set_time_us((uint32_t)(sec), (uint32_t)(us))
#define MEMP_NUM_SYS_TIMEOUT (LWIP_NUM_SYS_TIMEOUT_INTERNAL + 8)
#define TCP_MSS 1460
#define TCP_WND (8 * TCP_MSS)
#define TCP_SND_BUF (8 * TCP_MSS)
#define TCP_SND_QUEUELEN ((4 * (TCP_SND_BUF) + (TCP_MSS - 1)) / (TCP_MSS))
#define LWIP_NETIF_STATUS_CALLBACK 1
#define LWIP_NETIF_LINK_CALLBACK 1
#define LWIP_NETIF_HOSTNAME 1
#define LWIP_NETIF_TX_SINGLE_PBUF 1
#define DHCP_DOES_ARP_CHECK 0
#define LWIP_DHCP_DOES_ACD_CHECK 0
// The RP2040 has no hardware checksum; this is lwIP's fastest portable one.
#define LWIP_CHKSUM_ALGORITHM 3

// lwIP's MQTT client (apps/mqtt): its buffers, sized for rotord's messages.
#include "../lwip_mqtt_opts.h"

#define MEM_STATS 0
#define SYS_STATS 0
#define MEMP_STATS 0
#define LINK_STATS 0
