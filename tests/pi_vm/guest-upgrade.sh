# shellcheck shell=bash
# Settings survive an upgrade of the package (guest.sh sources this); the
# reboot after it is checked by guest-reboot.sh.
r=$(wrc "AZOFFSET 7")
[ "$r" = "OK AZOFFSET 7.00" ] || fail "AZOFFSET 7: $r"
# Saved a few seconds after the change (the settings saver's delay).
n=0
until grep -q '"az.offset_deg": *7' /var/lib/rotord/settings.json 2>/dev/null; do
  sleep 0.5
  n=$((n + 1))
  [ $n -gt 40 ] && fail "AZOFFSET 7 not saved in 20 s: $(cat /var/lib/rotord/settings.json)"
done
newer=$(ls "$share"/newer/rotord_*_arm64.deb)
t0=$(now_ms)
(cd "$share/newer" && apt-get install -y -q "./$(basename "$newer")") >"$share/apt-upgrade.log" 2>&1
rc=$?
[ $rc -eq 0 ] || fail "apt install ./$(basename "$newer"): exit $rc: $(tail -5 "$share/apt-upgrade.log")"
t_apt=$(($(now_ms) - t0))
systemctl restart rotord || fail "restart after the upgrade: $(journalctl -u rotord -o cat -n 10)"
r=$(wrc "AZOFFSET?")
[ "$r" = "OK AZOFFSET 7.00" ] || [ "$r" = "OK AZOFFSET 7" ] || fail "after the upgrade AZOFFSET? says $r"
log "apt install ./$(basename "$newer") ($t_apt ms), restart: AZOFFSET? '$r', version $(dpkg-query -W -f='${Version}' rotord)"
out=$(systemctl enable rotord 2>&1) || fail "systemctl enable rotord: $out"
