#!/bin/bash
# pi_vm (tests/pi_vm/CMakeLists.txt, `make pi-vm`): boots Debian 12 arm64
# under qemu-system-aarch64 (plain emulation, no KVM) with the arm64 rotord
# package and real kernel GPIO lines (gpio-sim), and runs guest.sh inside.
#   $1  the arm64 package (rotord_<version>_arm64.deb), or the directory
#       that holds it
#   $2  the work directory (build/pi_vm): the cached image, the module, a
#       share for this run
# Prints the time of each phase. Fails naming what is missing.
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
deb=$1 work=$2
fail() { echo "FAIL: pi_vm: $*"; exit 1; }
# CPU seconds (user + sys) of the finished child processes so far: what a
# phase costs on a free machine, whatever else loads this one.
# (times runs in this shell, not in a subshell, which would count none.)
cpu_now() {
  times >"$cpu_file"
  cpu=$(awk 'NR == 2 { split($1, u, "m"); split($2, s, "m"); printf "%.0f", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "$cpu_file")
}
missing=()
for tool in qemu-system-aarch64 rotctl dpkg-deb; do
  command -v "$tool" >/dev/null || missing+=("$tool")
done
[ ${#missing[@]} -eq 0 ] || fail "missing ${missing[*]} (scripts/install-deps.sh: qemu-system-arm, libhamlib-utils)"
[ -d "$deb" ] && deb=$(ls "$deb"/rotord_*_arm64.deb 2>/dev/null | head -1)
[ -f "$deb" ] || fail "no package $deb (packaging.deb_arm64 makes it)"
t_all=$(date +%s)
mkdir -p "$work"
cpu_file="$work/cpu.times"

t=$(date +%s)
"$here/build-image.sh" "$work/image" || fail "the image (build-image.sh)"
cpu_now
echo "pi_vm: image ready in $(($(date +%s) - t)) s (CPU $cpu s)"
t=$(date +%s) c=$cpu
"$here/build-gpio-sim.sh" "$work/image" "$work/gpio-sim" || fail "the gpio-sim module (build-gpio-sim.sh)"
cpu_now
echo "pi_vm: gpio-sim module ready in $(($(date +%s) - t)) s (CPU $((cpu - c)) s)"

# The share: the package, a newer one for the upgrade (the same files,
# version +pivm1), the module and the checks.
share="$work/share"
rm -rf "$share"
mkdir -p "$share"
cp "$deb" "$share/"
v=$(dpkg-deb -f "$deb" Version)
x="$work/repack"
rm -rf "$x"
mkdir -p "$share/newer"
dpkg-deb -R "$deb" "$x" && sed -i "s/^Version: .*/Version: $v+pivm1/" "$x/DEBIAN/control" &&
  dpkg-deb -b "$x" "$share/newer/rotord_$v+pivm1_arm64.deb" >/dev/null || fail "cannot make the newer package"
rm -rf "$x"
cp "$work/gpio-sim/gpio-sim.ko" "$here"/guest*.sh "$here/gpio-chip.sh" "$here/plant.sh" "$share/"

# The rotctld port, forwarded from a free port of this machine.
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
serial="$work/serial.log"
cpu_now
t=$(date +%s) c=$cpu
# -snapshot: the cached image stays as built; the guest's reboot keeps the
# changes (one qemu process). Two CPUs, as a Pi has at least. On a
# 2-core host busy with other builds the machine ran 20 minutes and was
# cut off in its second boot: 40 minutes at most.
timeout 2400 qemu-system-aarch64 -M virt -cpu cortex-a57 -smp 2 -m 1024 \
  -display none -monitor none -serial "file:$serial" \
  -kernel "$work/image/vmlinuz" -initrd "$work/image/initrd.img" \
  -append "root=/dev/vda rw console=ttyAMA0 quiet" \
  -drive "file=$work/image/rootfs.img,if=none,id=hd,format=raw,snapshot=on" \
  -device virtio-blk-device,drive=hd \
  -netdev "user,id=net,hostfwd=tcp:127.0.0.1:$port-:4533" -device virtio-net-device,netdev=net \
  -fsdev "local,id=fs,path=$share,security_model=none" -device virtio-9p-device,fsdev=fs,mount_tag=share \
  >"$work/qemu.log" 2>&1 &
qemu=$!
# Serve the guest's requests to run rotctl here, until the machine is off.
seen_boot=no
while kill -0 $qemu 2>/dev/null; do
  if [ -f "$share/rotctl.req" ]; then
    req=$(cat "$share/rotctl.req")
    rm -f "$share/rotctl.req"
    # shellcheck disable=SC2086
    timeout 30 rotctl -m 2 -r "127.0.0.1:$port" $req >"$share/rotctl.out" 2>&1
    echo $? >"$share/rotctl.rc.tmp" && mv "$share/rotctl.rc.tmp" "$share/rotctl.rc"
    echo "pi_vm: host: rotctl -m 2 -r 127.0.0.1:$port $req -> $(tr '\n' ' ' <"$share/rotctl.out")"
  fi
  if [ $seen_boot = no ] && [ -f "$share/guest.log" ]; then
    seen_boot=yes
    echo "pi_vm: the machine's checks started $(($(date +%s) - t)) s after power-on"
  fi
  sleep 0.2
done
wait $qemu
qrc=$?
cpu_now
echo "pi_vm: the machine ran $(($(date +%s) - t)) s, CPU $((cpu - c)) s (qemu exit $qrc)"
cat "$share/guest.log" 2>/dev/null
result=$(cat "$share/result" 2>/dev/null)
if [ "$result" != 0 ]; then
  echo "--- serial console (last 40 lines) ---"
  tail -40 "$serial"
  tail -5 "$work/qemu.log"
  fail "the checks in the machine failed or did not finish (result '${result:-none}', qemu $qrc)"
fi
cpu_now
echo "pi_vm: PASS in $(($(date +%s) - t_all)) s, CPU $cpu s"
