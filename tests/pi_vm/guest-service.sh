# shellcheck shell=bash
# The service under systemd as PID 1 (guest.sh sources this): Type=notify,
# what `systemctl status` and the journal show, the user and the sandbox,
# Avahi's announcement.

# Type=notify: `systemctl start` returns when rotord said READY=1, which it
# says once every port listens; so at that moment each one listens.
log "before the start: $(ls -l /dev/gpiochip* | tr '\n' ';') $(id rotord)"
t0=$(now_ms)
systemctl start rotord || fail "systemctl start rotord: $(journalctl -u rotord -o cat -n 10)"
t_start=$(($(now_ms) - t0))
listening=$(ss -Hltn)
for port in 4533 1234 8080 4601 4602; do
  grep -qE "[:.]$port\b" <<<"$listening" ||
    fail "systemctl start returned, port $port not listening yet: $listening"
done
[ "$(systemctl show -p Type --value rotord)" = notify ] || fail "Type is not notify"
log "systemctl start rotord: active after $t_start ms, ports 4533 1234 8080 4601 4602 listening at that moment"
status=$(systemctl status rotord --no-pager -n 5 2>&1)
grep -q 'Active: active (running)' <<<"$status" || fail "systemctl status: $status"
grep -q 'Main PID: [0-9]* (rotord)' <<<"$status" || fail "systemctl status shows no Main PID: $status"
grep -q 'ready' <<<"$status" || fail "systemctl status shows no 'ready' line: $status"
log "systemctl status rotord: $(grep -o 'Active: [^;]*' <<<"$status"), $(grep -o 'Main PID: [0-9]* (rotord)' <<<"$status")"
# The journal has priorities: info lines stay out of -p warning.
journalctl -u rotord -o cat -p info | grep -q 'ready' || fail "journal: no 'ready' line at info"
journalctl -u rotord -o cat -p warning | grep -q 'ready' && fail "journalctl -p warning shows the info line 'ready'"

# The user and the sandbox the README lists, on the running process.
pid=$(main_pid)
[ "$(ps -o user= -p "$pid")" = rotord ] || fail "rotord runs as $(ps -o user= -p "$pid")"
grep -q '^NoNewPrivs:[[:space:]]*1' "/proc/$pid/status" || fail "NoNewPrivs is not set"
grep -q '^Seccomp:[[:space:]]*2' "/proc/$pid/status" || fail "no seccomp filter"
ns_root=$(nsenter -t "$pid" -m sh -c 'touch /usr/pi-vm-probe 2>&1; ls /home 2>&1; ls /tmp' 2>&1)
grep -q 'Read-only file system' <<<"$ns_root" || fail "ProtectSystem=strict: /usr writable: $ns_root"
for prop in ProtectSystem=strict ProtectHome=yes PrivateTmp=yes NoNewPrivileges=yes DevicePolicy=closed; do
  [ "$(systemctl show -p "${prop%%=*}" --value rotord)" = "${prop#*=}" ] || fail "$prop not in effect"
done
exposure=$(systemd-analyze security rotord --no-pager 2>/dev/null | tail -1)
log "user rotord, NoNewPrivs, seccomp, ProtectSystem=strict (/usr read-only inside); systemd-analyze security: $exposure"

# Avahi in the machine announces rotctld (avahi-browse, resolved).
t0=$(now_ms)
found=""
for _ in 1 2 3 4 5 6; do
  found=$(avahi-browse -rtp _rotctld._tcp 2>/dev/null | grep '^=' | grep ';4533;' | head -1)
  [ -n "$found" ] && break
  sleep 2
done
[ -n "$found" ] || fail "avahi-browse: no _rotctld._tcp on port 4533: $(avahi-browse -artp 2>&1 | head -5)"
log "avahi-browse -rt _rotctld._tcp: $(cut -d';' -f4,7-10 <<<"$found") ($(($(now_ms) - t0)) ms)"
