#!/bin/bash
# `rotord --outputs-off`, the systemd unit's ExecStopPost step, as the real
# binary runs it: it reads the settings file and drives every wired output
# off. This machine has no GPIO chip (the line path is tested on the fake
# chip in tests/linux/outputs_off_test.cpp), so the outputs here are
# H-bridge PWM channels in a fake sysfs tree (ROTORD_PWM_ROOT) left running
# at 80 %, as the kernel leaves them after kill -9, plus relay lines on a
# chip that does not exist: the channels still go off, the chip is named,
# exit 1.
set -u
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
unset STATE_DIRECTORY
mkdir -p "$dir/state"
# running: both channels at 80 %, as rotord's kill -9 leaves them.
running() {
  for ch in 0 1; do
    mkdir -p "$dir/pwm/pwmchip0/pwm$ch"
    echo 50000 >"$dir/pwm/pwmchip0/pwm$ch/period"
    echo 40000 >"$dir/pwm/pwmchip0/pwm$ch/duty_cycle"
    echo 1 >"$dir/pwm/pwmchip0/pwm$ch/enable"
  done
}
value() { tr -d '\n' <"$dir/pwm/pwmchip0/$1" | sed 's/^0*\([0-9]\)/\1/'; }
off() { [ "$(value pwm0/duty_cycle)" = 0 ] && [ "$(value pwm1/duty_cycle)" = 0 ] &&
  [ "$(value pwm0/enable)" = 0 ] && [ "$(value pwm1/enable)" = 0 ]; }

# outputs_off SETTINGS: with the channels running and SETTINGS as the
# service's settings file ($STATE_DIRECTORY/settings.json), rotord
# --outputs-off --hw gpiod; its output in $out, its exit code in $rc.
outputs_off() {
  running
  echo "$1" >"$dir/state/settings.json"
  out=$(STATE_DIRECTORY="$dir/state" ROTORD_PWM_ROOT="$dir/pwm" "$ROTORD" --outputs-off --hw gpiod 2>&1)
  rc=$?
  echo "$out"
}

# An H-bridge azimuth.
outputs_off '{"settings_version": 2, "az.drive": "hbridge", "pwm.chip": 0}'
[ "$rc" -eq 0 ] || fail "exit code $rc"
off || fail "a PWM channel is still on"
grep -q 'outputs off: pwm.az_cw PWM 0/0, pwm.az_ccw PWM 0/1' <<<"$out" || fail "not logged"

# Relays on a missing chip as well: the channels go off all the same, the chip is named.
outputs_off '{"settings_version": 2, "az.drive": "hbridge", "pwm.chip": 0, "el.enabled": true, "gpiod.chip": 31}'
[ "$rc" -eq 1 ] || fail "exit code $rc without the GPIO chip"
off || fail "a PWM channel is still on"
grep -q 'cannot open GPIO chip /dev/gpiochip31 (gpiod.chip = 31)' <<<"$out" || fail "chip not named"

# Under --hw sim there is nothing to drive: exit 0 (the unit may run it whatever the backend).
out=$("$ROTORD" --outputs-off --hw sim 2>&1)
[ $? -eq 0 ] || fail "--hw sim: exit code not 0"
echo PASS
