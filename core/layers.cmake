# The core's layers and what each may include: read by core/CMakeLists.txt
# (one static library per layer, linked to the layers below it) and by
# cmake/check_layers.cmake (run on every build: a wrong-way #include fails
# it, naming the file, the include and the rule). docs/architecture.md
# draws the same graph (tests/docs checks it against this file).
#
# ROTORD_LAYER_<name>: the layers <name> builds on directly. A layer may
# include its own headers and those of every layer it reaches through these
# lists; nothing else. Every directory below core/ is a layer and must be
# listed in ROTORD_LAYERS; the graph must have no cycle; every edge must be
# used: some file of the layer includes a header of the layer it names (an
# edge kept "just in case" would let a layer grow a dependency unseen).

# Bottom to top (the order the libraries are defined in).
set(ROTORD_LAYERS
    util hal motion access tracking sensors settings json storage input axis care net rotator
    command protocol metrics loop web mqtt)

# Errors, text, CRC-32, time, and the ids every layer shares (AxisId,
# Direction) and the ByteSink every writer streams into.
set(ROTORD_LAYER_util "")
# Small hardware interfaces a port implements: plain C++, on nothing.
set(ROTORD_LAYER_hal "")
# Angle arithmetic and overlap path choice: plain C++, on nothing.
set(ROTORD_LAYER_motion "")
# Credentials and who holds what: password hashes, tokens, web sessions, the
# login limit, the control lock, the peer a session talks to. Below settings,
# which checks the stored credentials with these formats (issue 11's graph had
# no access layer yet).
set(ROTORD_LAYER_access util)
# SGP4/SDP4, observer geometry, Sun and Moon, places, passes; the TLE store
# (saved through a hal::Storage).
set(ROTORD_LAYER_tracking hal util)
# Position decoding and calibration.
set(ROTORD_LAYER_sensors hal motion util)
# The one settings table. Also on sensors: the pot calibration rows are
# checked with PotCalibration's own rule (one rule, not a copy that could
# drift from what the sensor accepts); and on access: password-hash and
# token rows with access's own parsers.
set(ROTORD_LAYER_settings util access sensors)
# The JSON codec (reader, writer, the settings document and its load/save
# on a hal::Storage): under web and storage, which both speak it.
set(ROTORD_LAYER_json settings hal)
# Flash slots, the settings saver.
set(ROTORD_LAYER_storage json settings hal)
# Button debouncing, manual buttons (what a press wants; the command
# layer's Buttons turns it into commands).
set(ROTORD_LAYER_input hal util)
# Position tracking and the motion state machine of one axis.
set(ROTORD_LAYER_axis sensors motion settings)
# Looked after unattended (docs/care.md): the wear odometer counted from the
# axes' status, its record (the JSON codec) saved on a hal::Storage of its
# own, and the starts-per-hour ceiling. Under rotator, which ticks them.
set(ROTORD_LAYER_care axis json hal)
# Who may connect and who may control, from the settings' network lists.
set(ROTORD_LAYER_net access settings)
# The Controller: axes, park, tracks, the control lock.
set(ROTORD_LAYER_rotator axis care tracking settings access)
# The command layer: each command a client may send (go-to, move, stop,
# park, reset, speed, place, preset; settings writes, calibration,
# commissioning and set-up, with the one rule of who may write which key)
# once, with its argument checks (typed
# for the line protocols, read from JSON for REST and MQTT: the body and the
# payload are the same document), who may call it (the allow-list from net),
# the control lock, and its errors as values; the front ends above only
# translate bytes. On input: the manual buttons are a front end here
# (command/buttons.hpp), polled by the port before the controller's tick.
set(ROTORD_LAYER_command rotator net json input)
# Byte sessions of the line protocols and the UDP messages, over the command
# layer; the settings document's JSON codec for the console's export and
# import.
set(ROTORD_LAYER_protocol command json)
# Counters per protocol and the Prometheus writer. Above protocol: each
# protocol's error reply is recognised by that protocol's own constant.
set(ROTORD_LAYER_metrics protocol hal)
# The tick scheduler: the metrics' TickSource (metrics/tick_source.hpp), so
# the metrics report it without naming this layer.
set(ROTORD_LAYER_loop metrics)
# HTTP session, REST API, the metrics page, the embedded web UI.
# It reads the tick schedule and the settings saver's counters through the
# metrics::Registry, not from loop and storage themselves.
set(ROTORD_LAYER_web command protocol rotator json metrics)
# MQTT (docs/mqtt.md): state, commands straight to the command layer, Home
# Assistant discovery, the station table; above web, whose status document
# it publishes.
set(ROTORD_LAYER_mqtt web command)

# --- Outside the core (checked with -DSOURCE_DIR, as the build does) ---
# The simulator (sim/) models the plant behind the hal interfaces and the
# axis's drive outputs: it may use these layers (and what they reach), never
# a port.
set(ROTORD_SIM_BUILDS_ON axis)
# The ports assemble the whole core, so they may include every layer, but no
# other port; and the one file through which the Linux daemon uses the
# simulator (profiles and the simulated rotator): no other file of a port
# includes sim/. Paths are relative to the source tree.
set(ROTORD_SIM_SEAM ports/linux/simulator.hpp)
