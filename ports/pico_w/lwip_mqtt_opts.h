#pragma once
// The buffers of lwIP's MQTT client (apps/mqtt, lwip/apps/mqtt_opts.h), sized
// for rotord. Seen by the SDK's mqtt.c and by lwip_mqtt.cpp alike (the
// client's struct embeds them): included from config/lwipopts.h on the Pico
// W, forced into both on the host test (tests/lwip).
//
// The output ring buffer must hold one whole PUBLISH packet: the largest is
// the state (mqtt::Bridge::kMaxStateBytes, 3072, refused beyond; about
// 1.2-2 KB in practice) with its topic (<= 128) and header (<= 7). Discovery
// messages are under 1 KB (kMaxDiscoveryBytes) and go one per publish; what
// does not fit waits in the bridge for a later pass, never lost. The ring
// empties into TCP's send buffer (TCP_SND_BUF) as the connection allows.
#define MQTT_OUTPUT_RINGBUF_SIZE 3264
// An incoming PUBLISH's fixed header, topic and packet id must fit here, or
// lwIP closes the connection: our command topics are at most 128 bytes
// (mqtt::kMaxTopicBytes); longer ones are ignored by the glue. The payload
// streams past it in pieces.
#define MQTT_VAR_HEADER_BUFFER_LEN 160
// QoS 1 publishes and subscribes waiting for the broker's answer. A
// (re)connection sends 10 at once (subscribe, availability, six discovery
// configs, info, state); beyond this a publish is refused and retried.
#define MQTT_REQ_MAX_IN_FLIGHT 12
