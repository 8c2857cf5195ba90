#!/bin/bash
# rotord announced on the network through a real avahi-daemon: the web UI as
# _http._tcp, rotctld as _rotctld._tcp with the other ports as TXT records
# (the Pico W's mDNS records, core/net/dns_sd.hpp). The avahi-daemon runs on
# a private D-Bus system bus of this test (dbus-daemon with its own config,
# found by rotord and avahi-browse through DBUS_SYSTEM_BUS_ADDRESS), on the
# loopback interface only, in a mount namespace of its own (its pid file),
# so it disturbs no avahi-daemon of the machine. avahi-daemon needs root: as
# another user the test is skipped (exit 77), saying so. Also: without
# avahi-daemon rotord runs and says so; a restarted avahi-daemon is found
# again; a stopped rotord is withdrawn.
set -u
fail() { echo "FAIL: $*"; echo "--- rotord:"; cat "$dir/rotord.log" 2>/dev/null; exit 1; }
for tool in dbus-daemon avahi-daemon avahi-browse unshare; do
  command -v "$tool" >/dev/null || { echo "FAIL: $tool is missing (scripts/install-deps.sh)"; exit 1; }
done
if [ "$(id -u)" -ne 0 ]; then
  echo "SKIP: avahi-daemon runs only as root; not tested against a real avahi-daemon here"
  exit 77
fi
dir=$(mktemp -d)
rotord_pid= avahi_pid= bus_pid=
cleanup() {
  for p in $rotord_pid $avahi_pid $bus_pid; do kill "$p" 2>/dev/null; done
  wait 2>/dev/null
  rm -rf "$dir"
}
trap cleanup EXIT
export XDG_CONFIG_HOME="$dir"
unset STATE_DIRECTORY JOURNAL_STREAM
# retry TRIES PAUSE_S CMD...: runs CMD until it succeeds, at most TRIES
# times, PAUSE_S seconds apart. The test's one wall-clock wait: avahi-daemon,
# D-Bus and mDNS work on their own clocks, which no option of rotord's
# moves; TRIES bounds liveness only, never what the test asserts.
retry() {
  local tries=$1 pause_s=$2
  shift 2
  for _ in $(seq "$tries"); do
    "$@" && return 0
    sleep "$pause_s"
  done
  return 1
}
# holds FILE TEXT [COUNT]: FILE holds TEXT (COUNT times).
holds() { [ "$(grep -c -- "$2" "$1" 2>/dev/null)" -ge "${3:-1}" ]; }
# wait_for FILE TEXT [COUNT]: until FILE holds TEXT, at most 60 s.
wait_for() { retry 600 0.1 holds "$@"; }
# start_rotord: on random free ports (a port taken meanwhile: try others).
start_rotord() {
  for _ in 1 2 3 4 5; do
    web=$(shuf -i 20000-60000 -n1); rotctld=$((web + 1)); wrc=$((web + 2)); gs232=$((web + 3))
    : >"$dir/rotord.log"
    "$ROTORD" --bind 0.0.0.0 --web-port $web --rotctld-port $rotctld --wrc-port $wrc \
      --gs232-port $gs232 --easycomm-port 0 --seed-port 0 >"$dir/rotord.log" 2>&1 &
    rotord_pid=$!
    # The whole line: "already in use" holds the word "ready" too.
    wait_for "$dir/rotord.log" '^rotord: ready$\|Address already in use'
    grep -qx 'rotord: ready' "$dir/rotord.log" && return 0
    wait "$rotord_pid"; rotord_pid=
  done
  fail "rotord did not start"
}
start_avahi() {
  : >"$dir/avahi.log"
  unshare -m sh -c 'mount -t tmpfs none /run/avahi-daemon &&
    exec avahi-daemon -f "$1" --no-drop-root --no-chroot --no-rlimits --no-proc-title' \
    avahi "$dir/avahi.conf" >"$dir/avahi.log" 2>&1 &
  avahi_pid=$!
  wait_for "$dir/avahi.log" 'Server startup complete' || fail "avahi-daemon did not start: $(cat "$dir/avahi.log")"
}
browse() { timeout 30 avahi-browse --resolve --parsable --terminate "$1" 2>/dev/null | grep '^='; }
# browse_until TYPE PATTERN: browses until a resolved record matches PATTERN
# (grep), at most 30 tries, and prints the last result. One browse is not
# enough: --terminate ends at avahi's "all for now", which on a busy machine
# can come before the record is resolved (interop.avahi failed so once, at
# -j8 beside two busy loops); no sleep or timeout here decides the outcome.
browsed=
browse_finds() { browsed=$(browse "$1"); grep -q -- "$2" <<<"$browsed"; }
browse_until() {
  local rc=0
  retry 30 1 browse_finds "$@" || rc=1
  echo "$browsed"
  return $rc
}

# 1. No D-Bus, no avahi-daemon: rotord runs and says it is not announced yet.
export DBUS_SYSTEM_BUS_ADDRESS="unix:path=$dir/bus"
start_rotord
wait_for "$dir/rotord.log" 'avahi-daemon is not reachable' || fail "the absence is not logged"
kill -TERM "$rotord_pid"; wait "$rotord_pid" || fail "rotord did not exit 0"; rotord_pid=

# 2. A private system bus and avahi-daemon on the loopback interface.
mkdir -p /run/avahi-daemon
cat >"$dir/bus.conf" <<CONF
<!DOCTYPE busconfig PUBLIC "-//freedesktop//DTD D-Bus Bus Configuration 1.0//EN"
 "http://www.freedesktop.org/standards/dbus/1.0/busconfig.dtd">
<busconfig>
  <type>system</type>
  <listen>unix:path=$dir/bus</listen>
  <auth>EXTERNAL</auth>
  <policy context="default">
    <allow user="*"/> <allow own="*"/>
    <allow send_destination="*"/> <allow receive_sender="*"/>
  </policy>
</busconfig>
CONF
cat >"$dir/avahi.conf" <<CONF
[server]
use-ipv4=yes
use-ipv6=no
allow-interfaces=lo
enable-dbus=yes
[publish]
publish-hinfo=no
publish-workstation=no
CONF
dbus-daemon --config-file="$dir/bus.conf" --nofork >"$dir/bus.log" 2>&1 &
bus_pid=$!
retry 100 0.1 test -S "$dir/bus" || fail "dbus-daemon did not listen: $(cat "$dir/bus.log")"
start_avahi
start_rotord
wait_for "$dir/rotord.log" "avahi: announced as 'rotord on " || fail "not announced"
out=$(browse_until _rotctld._tcp ";$rotctld;")
echo "$out"
grep -q ";_rotctld._tcp;local;.*;$rotctld;\"txtvers=1\" \"version=[0-9.]*\" \"web=$web\" \"wrc=$wrc\" \"gs232=$gs232\"\$" <<<"$out" ||
  fail "no _rotctld._tcp with the ports as TXT records"
grep -q 'rotord\\032on\\032' <<<"$out" || fail "the instance name is not 'rotord on <host>'"
out=$(browse_until _http._tcp ";$web;")
echo "$out"
grep -q ";$web;\"path=/\"\$" <<<"$out" || fail "no _http._tcp on the web port"

# 3. avahi-daemon restarts: rotord finds it again and announces once more.
kill "$avahi_pid"; wait "$avahi_pid" 2>/dev/null; avahi_pid=
wait_for "$dir/rotord.log" 'avahi-daemon went away' || fail "the daemon's loss is not logged"
start_avahi
wait_for "$dir/rotord.log" "avahi: announced as" 2 || fail "not announced again"
browse_until _rotctld._tcp ";$rotctld;" >/dev/null || fail "not browsable after the restart"

# 4. rotord stops: its services are withdrawn.
kill -TERM "$rotord_pid"; wait "$rotord_pid" || fail "rotord did not exit 0"; rotord_pid=
# The goodbye records take a moment to leave the daemon's cache (mDNS
# gives them a TTL of 1 s): look again until they are gone, at most 20 s.
withdrawn() { ! browse_finds _rotctld._tcp ";$rotctld;"; }
retry 20 1 withdrawn || fail "still announced after rotord stopped"
echo PASS
