#!/bin/sh
# pi-vm-gpio.service (tests/pi_vm): a gpio-sim chip of 32 lines through
# configfs, named as the rotator's wiring on a Pi's header (docs/gpiod.md's
# default BCM numbers, and an e-stop on 12). Inputs rest pulled up (switch
# open); the checks close a switch by pulling its line down.
set -e
# Debian builds configfs as a module, which gpio-sim needs.
modprobe configfs
[ -d /sys/module/gpio_sim ] || insmod /usr/local/lib/pi-vm/gpio-sim.ko
mountpoint -q /sys/kernel/config || mount -t configfs none /sys/kernel/config
d=/sys/kernel/config/gpio-sim/rotator
[ -d "$d" ] && exit 0
mkdir "$d" "$d/bank0"
echo 32 >"$d/bank0/num_lines"
echo rotator >"$d/bank0/label"
for l in 17:az_cw 27:az_ccw 22:az_speed 23:az_brake 16:az_t1 26:az_t2 5:az_l1 6:az_l2 \
  20:el_limit_up 21:el_limit_down 24:el_up 25:el_down 12:estop; do
  mkdir "$d/bank0/line${l%%:*}"
  echo "${l#*:}" >"$d/bank0/line${l%%:*}/name"
done
echo 1 >"$d/live"
