#!/bin/bash
# pi-vm-plant.service (tests/pi_vm): the rotator's motor and pot behind the
# relays. Reads the CW and CCW relay lines from outside rotord (gpio-sim's
# sysfs) and turns a pot reading in an IIO-shaped file tree that rotord
# reads (ROTORD_IIO_ROOT), at 4.4 deg/s (40 counts/s; 4095 counts = 450 deg). The
# position is kept across reboots, as a real pot keeps it; it starts at
# 100 deg. `pi-vm-plant init` only writes the first reading (before rotord
# starts, which refuses a missing ADC file).
root=/run/pi-vm-plant
dev="$root/iio:device0"
saved=/var/lib/pi-vm/pot_counts
cfg=/sys/kernel/config/gpio-sim/rotator
lines=/sys/devices/platform/$(cat "$cfg/dev_name")/$(cat "$cfg/bank0/chip_name")
counts=$(cat "$saved" 2>/dev/null || echo 910)
# rotord keeps the file open and reads it from offset 0 each tick, as a
# sysfs attribute: rewrite it in place (1<> opens it without truncating),
# always 5 bytes in one write() of printf, so a read sees the old reading
# or the new one.
write() {
  printf '%4d\n' "$counts" 1<>"$dev/in_voltage0_raw"
}
mkdir -p "$dev"
write
[ "${1:-}" = init ] && exit 0
# Turned by the time that passed, not per pass: under emulation on a busy
# machine a pass of this loop may take a second. The loop forks nothing but
# its sleep (bash builtins: read, printf, EPOCHREALTIME): with a process or
# two per pass, as it had, a pass took up to a second under emulation and
# the pot moved in steps of 4 deg a second, which rotord's sensor gate
# took for a jump (SENSOR_JUMP): no real pot does that.
rate_counts_s=40
ms_now() { local t=${EPOCHREALTIME/./}; echo $((t / 1000)); }
last_ms=$(ms_now)
while :; do
  t=${EPOCHREALTIME/./}
  now_ms=$((t / 1000))
  step=$(((now_ms - last_ms) * rate_counts_s / 1000))
  [ $step -gt 0 ] && last_ms=$((last_ms + step * 1000 / rate_counts_s))
  read -r cw <"$lines/sim_gpio17/value"
  read -r ccw <"$lines/sim_gpio27/value"
  if [ "$cw" != "$ccw" ] && [ $step -gt 0 ]; then
    [ "$cw" = 1 ] && counts=$((counts + step))
    [ "$ccw" = 1 ] && counts=$((counts - step))
    [ $counts -gt 4095 ] && counts=4095
    [ $counts -lt 0 ] && counts=0
    write
    echo "$counts" >"$saved"
  elif [ "$cw" = "$ccw" ]; then
    last_ms=$now_ms
  fi
  sleep 0.02
done
