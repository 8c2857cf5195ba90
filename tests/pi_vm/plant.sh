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
trace="$root/trace"
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
# A real pot turns continuously: rotord, reading it every 10 ms tick, sees
# it move by a few hundredths of a degree a tick. This file only moves when
# a pass of this loop writes it, and under emulation on a busy host a pass
# that should take 20 ms took 150 to 200 ms with a forked `sleep`, and now
# and then 1 to 2 s: the pot then stood still while the relay was on and
# jumped 9 deg in one write, which rotord rightly latched as SENSOR_JUMP
# (its gate lets a reading move at most about 0.5 deg plus the rated speed
# times the time since the last reading). So: no process forked per pass
# (the wait is a builtin read with a timeout on a FIFO nobody writes), the
# unit runs the plant at a real-time priority (guest.sh), and one pass
# moves the pot by at most max_step counts (0.44 deg, below the gate's
# 0.5 deg floor): a plant starved of CPU is a slower motor, never a jump.
# The trace (relay changes, each write while driven, passes slower than
# 250 ms) is what a failed check prints (guest-lib.sh).
rate_counts_s=40 max_step=4
mkfifo "$root/wait" 2>/dev/null
exec 9<>"$root/wait"
: >"$trace"
t=${EPOCHREALTIME/./}
last_ms=$((t / 1000)) pass_ms=$last_ms was=00
while :; do
  t=${EPOCHREALTIME/./}
  now_ms=$((t / 1000))
  [ $((now_ms - pass_ms)) -gt 250 ] && printf '%d slow pass %d ms\n' "$now_ms" $((now_ms - pass_ms)) >>"$trace"
  pass_ms=$now_ms
  step=$(((now_ms - last_ms) * rate_counts_s / 1000))
  if [ $step -gt $max_step ]; then
    step=$max_step last_ms=$now_ms
  elif [ $step -gt 0 ]; then
    last_ms=$((last_ms + step * 1000 / rate_counts_s))
  fi
  read -r cw <"$lines/sim_gpio17/value"
  read -r ccw <"$lines/sim_gpio27/value"
  if [ "$cw" != "$ccw" ] && [ $step -gt 0 ]; then
    [ "$cw" = 1 ] && counts=$((counts + step))
    [ "$ccw" = 1 ] && counts=$((counts - step))
    [ "$counts" -gt 4095 ] && counts=4095
    [ "$counts" -lt 0 ] && counts=0
    write
    echo "$counts" >"$saved"
  elif [ "$cw" = "$ccw" ]; then
    last_ms=$now_ms
  fi
  [ "$cw$ccw" != "$was" ] || [ "$cw" != "$ccw" ] && printf '%d relays %s%s pot %d\n' "$now_ms" "$cw" "$ccw" "$counts" >>"$trace"
  was=$cw$ccw
  read -r -t 0.02 -u 9
done
