#!/bin/bash
# `rotord --print-config` on the real binary: every setting with the layer it
# comes from (default, the --sim profile, the settings file), the options
# with given/default, secrets masked; the service's default file
# ($STATE_DIRECTORY/settings.json) and the one by hand ($XDG_CONFIG_HOME).
set -u
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
unset STATE_DIRECTORY
export XDG_CONFIG_HOME="$dir/xdg"
mkdir -p "$dir/xdg/rotord" "$dir/state"
printf '{"settings_version": 2, "park.az_deg": 180, "wifi.password": "sesame123"}\n' \
  >"$dir/xdg/rotord/settings.json"
# line KEY: the --print-config line of KEY, spaces squeezed.
line() { grep "^$1 " <<<"$out" | tr -s ' '; }

out=$("$ROTORD" --print-config --sim ham4 --web-port 9999)
rc=$?
echo "$out" | head -24
[ "$rc" -eq 0 ] || fail "exit code $rc"
grep -q "^# settings file $dir/xdg/rotord/settings.json (from \$XDG_CONFIG_HOME): loaded" <<<"$out" ||
  fail "the XDG file is not the one read by hand"
[ "$(line park.az_deg)" = "park.az_deg 180 # file" ] || fail "park.az_deg: $(line park.az_deg)"
[ "$(line az.max_deg)" = "az.max_deg 360 # profile ham4" ] || fail "az.max_deg: $(line az.max_deg)"
[ "$(line az.has_brake)" = "az.has_brake true # profile ham4" ] || fail "az.has_brake: $(line az.has_brake)"
[ "$(line rotator.speed_pct)" = "rotator.speed_pct 100 # default" ] || fail "rotator.speed_pct"
[ "$(line wifi.password)" = 'wifi.password "********" # file' ] || fail "secret: $(line wifi.password)"
grep -q sesame <<<"$out" && fail "the secret was printed"
[ "$(line --web-port)" = "--web-port 9999 # given" ] || fail "--web-port: $(line --web-port)"
[ "$(line --rotctld-port)" = "--rotctld-port 4533 # default" ] || fail "--rotctld-port"
# IPv6 and IPv4 by default (one dual-stack socket per port, issue 29).
[ "$(line --bind)" = "--bind :: # default" ] || fail "--bind: $(line --bind)"
# Every row of the settings table is listed (one line per key).
[ "$(grep -c ' # \(default\|file\|profile ham4\)$' <<<"$out")" -gt 100 ] || fail "too few settings"

# Under the service (systemd sets STATE_DIRECTORY): /var/lib/rotord/settings.json there.
out=$(STATE_DIRECTORY="$dir/state" "$ROTORD" --print-config --hw gpiod)
rc=$?
[ "$rc" -eq 0 ] || fail "exit code $rc under STATE_DIRECTORY"
grep -q "^# settings file $dir/state/settings.json (from \$STATE_DIRECTORY (systemd)): not there yet" \
  <<<"$out" || fail "STATE_DIRECTORY not used: $(grep '^# settings file' <<<"$out")"
[ "$(line park.az_deg)" = "park.az_deg 0 # default" ] || fail "the XDG file leaked in"
[ "$(line az.max_deg)" = "az.max_deg 450 # default" ] || fail "a profile under --hw gpiod"

# --config wins; a file with a bad value: exit 1, the value named and
# dropped, every valid value kept.
printf '{"park.az_deg": 9999, "park.el_deg": 30}\n' >"$dir/bad.json"
out=$(STATE_DIRECTORY="$dir/state" "$ROTORD" --print-config --config "$dir/bad.json")
rc=$?
[ "$rc" -eq 1 ] || fail "exit code $rc for an invalid file"
grep -q "^# settings file $dir/bad.json (from --config): DAMAGED" <<<"$out" ||
  fail "the damaged file is not named: $(grep '^# settings file' <<<"$out")"
grep -q "^#   park.az_deg: outside the allowed range" <<<"$out" || fail "the bad value is not named"
[ "$(line park.az_deg)" = "park.az_deg 0 # default" ] || fail "invalid value shown"
[ "$(line park.el_deg)" = "park.el_deg 30 # file" ] ||
  fail "a valid value was lost: $(line park.el_deg)"

# A file cut short: what reads is kept, and the access settings count as
# unreadable (rotord fails closed).
printf '{"park.el_deg": 30,\n "web.password": "pbkdf2' >"$dir/torn.json"
out=$("$ROTORD" --print-config --config "$dir/torn.json")
grep -q "the access settings cannot be read" <<<"$out" || fail "a torn file does not fail closed"
[ "$(line park.el_deg)" = "park.el_deg 30 # file" ] || fail "a torn file lost its start"

# A FIFO: refused like the daemon refuses it (exit 2), without blocking.
mkfifo "$dir/fifo"
out=$(timeout 10 "$ROTORD" --print-config --config "$dir/fifo")
rc=$?
[ "$rc" -eq 2 ] || fail "exit code $rc for a FIFO"
echo PASS
