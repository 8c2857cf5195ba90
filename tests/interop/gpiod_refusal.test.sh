#!/bin/bash
# `rotord --hw gpiod` refuses to start, with a message naming the chip and a
# non-zero exit code, when its GPIO chip is missing; and with a message
# naming the setting and the file when the pot's IIO ADC is missing. The real
# binary, as a user runs it. gpiod.chip 31 is set in the settings file so
# the test does not depend on what chips this machine has (on a Pi, chip 0
# exists); the IIO case needs a chip and so only runs where gpiochip0 exists.
set -u
fail() { echo "FAIL: $*"; exit 1; }
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mkdir -p "$dir/rotord"
# rotord --hw gpiod on the settings file in $dir, no ports; its output.
rotord_gpiod() {
  XDG_CONFIG_HOME="$dir" timeout 20 "$ROTORD" --hw gpiod --web-port 0 --wrc-port 0 \
    --rotctld-port 0 --gs232-port 0 --easycomm-port 0 2>&1
}
printf '{"gpiod.chip": 31}\n' > "$dir/rotord/settings.json"

out=$(rotord_gpiod)
rc=$?
echo "$out"
[ "$rc" -ne 0 ] || fail "exit code 0 without a GPIO chip"
[ "$rc" -ne 124 ] || fail "rotord did not exit (timeout)"
grep -q 'settings loaded' <<<"$out" || fail "the settings file was not used"
grep -q 'cannot open GPIO chip /dev/gpiochip31 (gpiod.chip = 31)' <<<"$out" ||
  fail "the message does not name the chip"
grep -Eqx '(rotord: |<6>)ready' <<<"$out" && fail "it said ready"

# A conflicting line assignment in the file is refused as a whole (the
# defaults are used, the file kept), like every other invalid setting. Only
# where the default chip 0 is absent: on a Pi the defaults would open it.
if [ ! -e /dev/gpiochip0 ]; then
printf '{"gpiod.chip": 31, "gpiod.btn_cw": 17}\n' > "$dir/rotord/settings.json"
out=$(rotord_gpiod)
rc=$?
echo "$out"
[ "$rc" -ne 0 ] || fail "exit code 0"
grep -q 'gpiod.az_cw and gpiod.btn_cw both use line 17' <<<"$out" ||
  fail "the conflict does not name both keys"
fi

if [ -e /dev/gpiochip0 ]; then
  printf '{"gpiod.chip": 0, "iio.az_device": 31}\n' > "$dir/rotord/settings.json"
  out=$(ROTORD_IIO_ROOT="$dir/iio" rotord_gpiod)
  rc=$?
  echo "$out"
  [ "$rc" -ne 0 ] || fail "exit code 0 without the ADC"
  grep -q "iio.az_device.*$dir/iio/iio:device31/in_voltage0_raw" <<<"$out" ||
    fail "the message does not name the IIO file"
else
  echo "no /dev/gpiochip0 here: the missing-ADC case was not run"
fi
echo PASS
