#!/bin/bash
# Runs inside the booted Debian 12 arm64 machine (tests/pi_vm, run-vm.sh),
# started by the image's pi-vm-runner.service from the host's 9p share
# (/mnt/share): installs the rotord package and checks the service with
# systemd as PID 1 and real kernel GPIO lines (gpio-sim) as the wiring.
# Two boots: the second checks what must survive a reboot. Writes its
# verdict to /mnt/share/result (0 = pass) and powers off.
set -u
# systemctl waits 25 s for systemd's answer by default; the emulated
# machine on a busy host took longer (`systemctl enable` failed with a
# time-out once), so it may wait 5 minutes.
export SYSTEMD_BUS_TIMEOUT=300
share=/mnt/share
state=/var/lib/pi-vm
mkdir -p "$state"
. "$share/guest-lib.sh"

if [ ! -f "$state/phase2" ]; then
  log "boot 1: $(systemd-analyze 2>/dev/null | head -1)"
  # The wiring's chip before rotord, at every boot (as a Pi's device tree).
  install -D -m 0644 "$share/gpio-sim.ko" /usr/local/lib/pi-vm/gpio-sim.ko
  install -D -m 0755 "$share/gpio-chip.sh" /usr/local/sbin/pi-vm-gpio-chip
  cat >/etc/systemd/system/pi-vm-gpio.service <<'UNIT'
[Unit]
Description=gpio-sim lines wired as the rotator's relays and switches
Before=rotord.service
[Service]
Type=oneshot
RemainAfterExit=yes
ExecStart=/usr/local/sbin/pi-vm-gpio-chip
[Install]
WantedBy=multi-user.target
UNIT
  systemctl enable --now pi-vm-gpio.service >/dev/null 2>&1 || fail "gpio-sim: $(journalctl -u pi-vm-gpio -o cat | tail -3)"
  find_chip
  log "gpio-sim: $(gpiodetect | grep "^$chip ") (gpiodetect), lines in $lines"

  t0=$(now_ms)
  (cd "$share" && apt-get install -y -q ./rotord_*_arm64.deb) >"$state/apt1.log" 2>&1 ||
    fail "apt install ./rotord_*_arm64.deb: $(tail -5 "$state/apt1.log")"
  log "apt install ./$(basename "$share"/rotord_*_arm64.deb): $(($(now_ms) - t0)) ms"
  id rotord >/dev/null || fail "no rotord user"
  systemctl is-enabled rotord >/dev/null 2>&1 && fail "the package enabled rotord.service"
  systemctl is-active rotord >/dev/null 2>&1 && fail "the package started rotord.service"

  # The wiring: the chip found above; an e-stop button (normally open, so
  # the pulled-up idle line is "released"); a pot on an IIO ADC, here a
  # file tree the plant below writes (ROTORD_IIO_ROOT: the ADC is the one
  # thing not proven here, docs/raspberry-pi.md). A long stall time: the
  # emulated machine on a busy host can stop for seconds, the plant with it.
  # A tolerance of 2 deg: the reading gate's floor is half of it, and the
  # plant (plant.sh), starved for 150 ms while rotord is not, leaves the pot
  # 0.6 deg behind the motion rotord measured, which the default 1 deg
  # tolerance's 0.5 deg floor took for a SENSOR_JUMP (seen once in a full
  # `make test`). A real pot turns on while its reader waits.
  install -d -o rotord -g rotord -m 0700 /var/lib/rotord
  cat >/var/lib/rotord/settings.json <<JSON
{"gpiod.chip": ${chip#gpiochip}, "gpiod.estop": 12, "estop.normally_closed": false,
 "iio.az_device": 0, "iio.az_channel": 0, "iio.full_scale_counts": 4095,
 "az.pot_cal_lo_counts": 0, "az.pot_cal_lo_deg": 0,
 "az.pot_cal_hi_counts": 4095, "az.pot_cal_hi_deg": 450, "az.stall_ms": 30000,
 "az.tolerance_deg": 2}
JSON
  chown rotord:rotord /var/lib/rotord/settings.json
  chmod 0600 /var/lib/rotord/settings.json
  mkdir -p /etc/systemd/system/rotord.service.d
  printf '[Service]\nEnvironment=ROTORD_IIO_ROOT=%s\n' "$plant" >/etc/systemd/system/rotord.service.d/pi-vm.conf
  install -D -m 0755 "$share/plant.sh" /usr/local/sbin/pi-vm-plant
  cat >/etc/systemd/system/pi-vm-plant.service <<'UNIT'
[Unit]
Description=the rotator's motor and pot behind the gpio-sim relay lines
Requires=pi-vm-gpio.service
After=pi-vm-gpio.service
Before=rotord.service
[Service]
ExecStartPre=/usr/local/sbin/pi-vm-plant init
ExecStart=/usr/local/sbin/pi-vm-plant
# Ahead of everything else in the machine, as a motor does not wait for
# the CPU (plant.sh); it sleeps 20 ms a pass.
CPUSchedulingPolicy=fifo
CPUSchedulingPriority=50
[Install]
WantedBy=multi-user.target
UNIT
  systemctl daemon-reload
  systemctl enable --now pi-vm-plant.service >/dev/null 2>&1 || fail "the plant: $(journalctl -u pi-vm-plant -o cat | tail -3)"

  . "$share/guest-service.sh"
  . "$share/guest-motion.sh"
  . "$share/guest-upgrade.sh"
  touch "$state/phase2"
  log "rebooting"
  systemctl reboot
  exit 0
fi

log "boot 2: $(systemd-analyze 2>/dev/null | head -1)"
find_chip
. "$share/guest-reboot.sh"
. "$share/guest-refusals.sh"
pass
