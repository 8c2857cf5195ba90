# shellcheck shell=bash
# The relays and switches on real kernel GPIO lines (guest.sh sources
# this): a go-to from the host's rotctl, a limit switch, the e-stop, and
# what the service does when rotord is killed or hangs.

# A go-to from Hamlib's rotctl on the host, through the forwarded port: the
# CW relay line goes high and is released on arrival.
before=$(wrc "AZ?")
out=$(host_rotctl P 130 0) || fail "rotctl -m 2 P 130 0 on the host: $out"
t=$(wait_level $CW 1 5000) || fail "rotctl P 130 0: the CW relay line stayed low (position $before)"
log "rotctl -m 2 (host) P 130 0 from '$before': CW relay line high after $t ms (gpio-sim sysfs)"
t=$(wait_level $CW 0 60000) || fail "the CW relay line still high 60 s after the go-to: $(wrc STATE)"
# Arrived: no relay on (under emulation the pot may run past the target,
# and a short CCW pulse corrects it).
n=0
until after=$(wrc STATE) && grep -q 'FLAGS=$' <<<"$after"; do
  sleep 0.5
  n=$((n + 1))
  [ $n -gt 60 ] && fail "no arrival 30 s after the CW relay released: $after"
done
[ "$(level $CW)$(level $CCW)" = 00 ] || fail "a relay line high after the arrival: $after"
fault=$(wrc "FAULT?")
pos=$(host_rotctl p) || fail "rotctl p: $pos"
az=$(head -1 <<<"$pos")
awk -v az="$az" 'BEGIN { exit !(az > 127 && az < 133) }' ||
  fail "arrived at $az, not 130: $after, $fault, pot $(cat /run/pi-vm-plant/iio:device0/in_voltage0_raw)"
log "CW relay line released after $t ms more; rotctl p: $az; $after; $fault"

# A limit switch: L2 (the CW end) closing cuts the CW relay.
start_cw >/dev/null
t0=$(now_ms)
switch_closed $L2
t=$(wait_level $CW 0 3000) || { switch_open $L2; fail "L2 closed, the CW relay line still high after 3 s"; }
limit_state=$(wrc STATE)
switch_open $L2
wrc STOP >/dev/null
grep -q "L2" <<<"$limit_state" || fail "STATE with L2 closed: $limit_state"
log "limit switch L2 closed (pull-down on line $L2): CW relay line low after $t ms; $limit_state"

# The e-stop: outputs off at once, ESTOP latched until released and RESET.
start_cw >/dev/null
switch_closed $ESTOP
t=$(wait_level $CW 0 3000) || { switch_open $ESTOP; fail "e-stop pressed, CW relay line still high after 3 s"; }
switch_open $ESTOP
sleep 0.3
f=$(wrc "FAULT?")
grep -q 'AZ=ESTOP' <<<"$f" || fail "e-stop released: FAULT? says $f, not ESTOP latched"
r=$(wrc "MOVE CW")
[ "$(level $CW)" = 0 ] || fail "a move after the e-stop energised the CW relay ($r)"
wrc RESET >/dev/null
f2=$(wrc "FAULT?")
grep -q 'AZ=NONE' <<<"$f2" || fail "after RESET: $f2"
log "e-stop (line $ESTOP): CW relay line low after $t ms; released: '$f', MOVE CW '$r', line stays low; RESET: '$f2'"

# kill -9 while the CW relay is energised: ExecStopPost drives it off
# within 2 s, Restart=on-failure starts rotord again.
start_cw >/dev/null
pid=$(main_pid) n=$(restarts)
kill -9 "$pid"
t=$(wait_level $CW 0 2000) || fail "kill -9: the CW relay line still high after 2 s"
wait_restarted "$pid" 20 || fail "kill -9: rotord not restarted within 20 s ($(systemctl is-active rotord))"
[ "$(restarts)" -gt "$n" ] || fail "kill -9: NRestarts did not grow"
[ "$(level $CW)" = 0 ] || fail "the restarted rotord energised the CW relay"
log "kill -9 with the CW relay line high: low again after $t ms (ExecStopPost), restarted (NRestarts $(restarts))"

# A hung control loop (SIGSTOP): the watchdog (WatchdogSec=10s) kills it,
# the outputs go off and the service restarts.
sleep 1
start_cw >/dev/null
pid=$(main_pid)
t0=$(now_ms)
kill -STOP "$pid"
t=$(wait_level $CW 0 30000) || fail "SIGSTOP: the CW relay line still high after 30 s"
wait_restarted "$pid" 30 || fail "SIGSTOP: not restarted within 30 s"
journalctl -u rotord -o cat | grep -qi 'watchdog timeout' || fail "SIGSTOP: no watchdog timeout in the journal"
log "SIGSTOP: watchdog timeout, CW relay line low after $t ms, restarted after $(($(now_ms) - t0)) ms"
