# shellcheck shell=bash
# Helpers of the checks inside the machine (guest.sh sources this).
# The lines are read and driven from outside rotord: gpio-sim's sysfs
# attributes (sim_gpioN/value: the level the consumer drives;
# sim_gpioN/pull: the level an input sees), never through rotord.
plant=/run/pi-vm-plant
# The wiring (docs/gpiod.md's default BCM numbers, gpio-chip.sh names them).
CW=17 CCW=27 L1=5 L2=6 ESTOP=12

log() { echo "pi_vm: $*" | tee -a "$share/guest.log"; }
now_ms() { echo $(($(date +%s%N) / 1000000)); }
fail() {
  log "FAIL: $*"
  {
    journalctl -u rotord --no-pager -n 30 -o short-precise
    # What the plant did meanwhile (plant.sh; times in ms of the epoch).
    echo "--- the plant's trace (last 40 lines)"
    tail -40 "$plant/trace"
    # rotord's own figures: how its ticks ran, the readings its gate refused.
    echo "--- rotord's /metrics (ticks, gate)"
    (exec 4<>/dev/tcp/127.0.0.1/8080 && printf 'GET /metrics HTTP/1.0\r\nHost: 127.0.0.1\r\n\r\n' >&4 &&
      timeout 10 cat <&4) |
      grep -E '^rotord_(tick_(interval|lateness)_seconds|tick_overruns|tick_rebases|axis_sensor_readings_rejected)'
  } >>"$share/guest.log" 2>&1
  echo 1 >"$share/result"
  systemctl poweroff
  exit 1
}
pass() {
  log "PASS"
  echo 0 >"$share/result"
  systemctl poweroff
  exit 0
}
# $chip (gpiochipN) and $lines (its gpio-sim sysfs directory), by the
# configfs chip gpio-chip.sh made (not a fixed number: the virt board's
# own GPIO controller is a chip too).
find_chip() {
  local cfg=/sys/kernel/config/gpio-sim/rotator
  chip=$(cat "$cfg/bank0/chip_name" 2>/dev/null) || fail "no gpio-sim chip (configfs $cfg)"
  lines=/sys/devices/platform/$(cat "$cfg/dev_name")/$chip
  [ -r "$lines/sim_gpio$CW/value" ] || fail "no $lines/sim_gpio$CW/value"
}
level() { cat "$lines/sim_gpio$1/value"; }
# The switch on line $1 closes to GND (pull-down) or opens (pull-up).
switch_closed() { echo pull-down >"$lines/sim_gpio$1/pull"; }
switch_open() { echo pull-up >"$lines/sim_gpio$1/pull"; }
# wait_level LINE LEVEL MS: until line LINE is at LEVEL, at most MS ms;
# prints the ms it took.
wait_level() {
  local t0 t
  t0=$(now_ms)
  while [ "$(level "$1")" != "$2" ]; do
    t=$(($(now_ms) - t0))
    [ $t -gt "$3" ] && { echo "timeout"; return 1; }
    sleep 0.02
  done
  echo $(($(now_ms) - t0))
}
# One WRC command over TCP (bash's /dev/tcp), its one-line reply.
wrc() {
  local reply
  exec 3<>/dev/tcp/127.0.0.1/1234 || return 1
  printf '%s\n' "$1" >&3
  IFS= read -r -t 10 reply <&3
  exec 3<&-
  printf '%s\n' "${reply%$'\r'}"
}
main_pid() { systemctl show -p MainPID --value rotord; }
restarts() { systemctl show -p NRestarts --value rotord; }
# Until rotord is active with a main process other than $1, at most $2 s.
wait_restarted() {
  local n=0
  while [ $n -lt $(($2 * 10)) ]; do
    if [ "$(systemctl is-active rotord)" = active ] && [ "$(main_pid)" != "$1" ] &&
      [ "$(main_pid)" != 0 ]; then
      return 0
    fi
    sleep 0.1
    n=$((n + 1))
  done
  return 1
}
# Asks the host to run Hamlib's rotctl against the forwarded rotctld port
# (run-vm.sh watches the share); prints rotctl's output.
host_rotctl() {
  rm -f "$share/rotctl.out" "$share/rotctl.rc"
  echo "$*" >"$share/rotctl.req.tmp"
  mv "$share/rotctl.req.tmp" "$share/rotctl.req"
  local n=0
  while [ ! -f "$share/rotctl.rc" ]; do
    sleep 0.2
    n=$((n + 1))
    [ $n -gt 300 ] && { echo "no answer from the host"; return 1; }
  done
  cat "$share/rotctl.out"
  return "$(cat "$share/rotctl.rc")"
}
# Starts a CW run by WRC and waits for the CW relay line; prints its ms.
start_cw() {
  local r t
  r=$(wrc "MOVE CW")
  [ "$r" = "OK MOVE CW" ] || fail "MOVE CW: $r"
  t=$(wait_level $CW 1 5000) || fail "the CW relay line stayed low after MOVE CW"
  echo "$t"
}
