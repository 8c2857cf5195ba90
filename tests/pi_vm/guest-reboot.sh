# shellcheck shell=bash
# After the reboot (guest.sh sources this): the enabled service came up by
# itself on the gpio-sim chip, with the settings of before.
n=0
until [ "$(systemctl is-active rotord)" = active ]; do
  sleep 0.5
  n=$((n + 1))
  [ $n -gt 60 ] && fail "after the reboot rotord is $(systemctl is-active rotord): $(journalctl -b -u rotord -o cat -n 10)"
done
r=$(wrc "AZOFFSET?")
[ "$r" = "OK AZOFFSET 7.00" ] || [ "$r" = "OK AZOFFSET 7" ] || fail "after the reboot AZOFFSET? says $r"
[ "$(stat -c '%U %a' /var/lib/rotord/settings.json)" = "rotord 600" ] ||
  fail "settings.json is $(stat -c '%U %a' /var/lib/rotord/settings.json)"
log "reboot: rotord $(dpkg-query -W -f='${Version}' rotord) active at boot, AZOFFSET? '$r', settings.json rotord 600"
