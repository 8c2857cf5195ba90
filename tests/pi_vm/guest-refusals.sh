# shellcheck shell=bash
# Bad input on the machine (guest.sh sources this): a wrong gpiod.* line,
# a line another process holds, an unreadable settings file. Each leaves
# the service failed or reported, with the reason in the journal and every
# output off; the settings file is never overwritten.
settings=/var/lib/rotord/settings.json
cp -p "$settings" "$state/settings.good"
# Starts rotord on the settings file as it is now; rotord must fail to
# start, naming $1 in the journal (this start only).
expect_refused() {
  local since
  since=$(date '+%Y-%m-%d %H:%M:%S')
  systemctl reset-failed rotord 2>/dev/null
  systemctl start rotord 2>/dev/null && fail "rotord started with $2"
  # The start failed (rotord exited before READY=1); no retries of
  # Restart=on-failure for this check.
  systemctl stop rotord 2>/dev/null
  journalctl -u rotord -o cat --since "$since" | grep -q -- "$1" ||
    fail "$2: the journal does not say '$1': $(journalctl -u rotord -o cat --since "$since" | tail -5)"
  for l in $CW $CCW; do
    [ "$(level $l)" = 0 ] || fail "$2: relay line $l high"
  done
  log "$2: refused, journal: '$(journalctl -u rotord -o cat --since "$since" -p err | grep -m1 -- "$1")'; relay lines low"
}
systemctl stop rotord

# A line the chip does not have.
sed -i 's/^{/{"gpiod.az_cw": 40, /' "$settings"
expect_refused "gpiod.az_cw = 40" "gpiod.az_cw = 40 (the chip has 32 lines)"
cp -p "$state/settings.good" "$settings"

# A line another process holds (gpioset keeps requesting it).
gpioset --mode=signal "$chip" $CCW=0 &
holder=$!
sleep 1
expect_refused "busy" "line $CCW held by gpioset"
kill "$holder"
wait "$holder" 2>/dev/null

# A settings file its owner cannot read: reported, left as it is.
sum=$(sha256sum "$settings")
chmod 000 "$settings"
since=$(date '+%Y-%m-%d %H:%M:%S')
systemctl reset-failed rotord 2>/dev/null
systemctl start rotord 2>/dev/null
sleep 5
systemctl stop rotord 2>/dev/null
journalctl -u rotord -o cat --since "$since" | grep -q "$settings.*Permission denied" ||
  fail "unreadable settings: not reported: $(journalctl -u rotord -o cat --since "$since" | tail -5)"
[ "$(stat -c %a "$settings")" = 0 ] && [ "$(sha256sum "$settings")" = "$sum" ] ||
  fail "the unreadable settings file was changed: $(stat -c %a "$settings")"
log "unreadable settings.json: '$(journalctl -u rotord -o cat --since "$since" | grep -m1 'Permission denied')'; the file left as it was"
cp -p "$state/settings.good" "$settings"
systemctl reset-failed rotord 2>/dev/null
systemctl start rotord || fail "rotord does not start again on the good settings"
