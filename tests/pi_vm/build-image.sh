#!/bin/bash
# Builds the Debian 12 arm64 machine that tests/pi_vm boots, into $1
# (build/pi_vm/image): a root file system made by mmdebstrap from Debian's
# packages (this machine's apt sources), with systemd, Debian's arm64 kernel
# and the rotord package's dependencies, so `apt install ./rotord_*_arm64.deb`
# needs no network inside; the kernel and initrd beside it for a direct
# boot; and the kernel headers packages that match it (for the gpio-sim
# module, build-gpio-sim.sh). Cached: nothing happens when the image of this
# recipe (this script's checksum) is there. Never committed.
set -euo pipefail
out=$1
recipe=$(cat "$0" "$(dirname "$0")/initrd-init.sh" | sha256sum | cut -c1-16)
if [ -f "$out/recipe" ] && [ "$(cat "$out/recipe")" = "$recipe" ] && [ -f "$out/rootfs.img" ]; then
  echo "pi_vm image: cached ($out, recipe $recipe)"
  exit 0
fi
missing=()
for tool in mmdebstrap mkfs.ext4 qemu-aarch64-static apt-get depmod cpio; do
  command -v "$tool" >/dev/null || missing+=("$tool")
done
[ ${#missing[@]} -eq 0 ] || { echo "pi_vm image: missing ${missing[*]} (scripts/install-deps.sh)"; exit 1; }
# mmdebstrap runs arm64 maintainer scripts through binfmt_misc.
if [ ! -e /proc/sys/fs/binfmt_misc/qemu-aarch64 ]; then
  [ -e /proc/sys/fs/binfmt_misc/register ] ||
    mount -t binfmt_misc binfmt_misc /proc/sys/fs/binfmt_misc 2>/dev/null || true
  update-binfmts --enable qemu-aarch64 2>/dev/null || true
fi
grep -qx enabled /proc/sys/fs/binfmt_misc/qemu-aarch64 2>/dev/null ||
  { echo "pi_vm image: no binfmt_misc entry for qemu-aarch64 (binfmt-support, qemu-user-static; root)"; exit 1; }

if grep -q " $(realpath -m "$out")/" /proc/mounts; then
  echo "pi_vm image: file systems are still mounted under $out (an interrupted mmdebstrap): unmount them"
  exit 1
fi
# CPU seconds (user + sys) of the finished child processes so far: what a
# phase costs on a free machine, whatever else loads this one.
# (times runs in this shell, not in a subshell, which would count none.)
cpu_now() {
  times >"$cpu_file"
  cpu=$(awk 'NR == 2 { split($1, u, "m"); split($2, s, "m"); printf "%.0f", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "$cpu_file")
}
# Each line of mmdebstrap's log with the seconds since the start.
stamp() { while IFS= read -r line; do echo "$((EPOCHSECONDS - start)) $line"; done; }
start=$(date +%s)
rm -rf "$out"
mkdir -p "$out"
tmp="$out/tmp"
mkdir -p "$tmp"
cpu_file="$tmp/cpu.times"
# The machine: systemd as PID 1, udev, the GPIO tools (gpiod) that read the
# lines from inside, Avahi and its browser, and the rotord package's
# Depends (shlibs) and Recommends, so its install needs nothing from a mirror.
# Not the kernel: its package is unpacked on this machine below (dpkg and
# mkinitramfs under qemu-user took half of the build). No documentation,
# manual pages or translations (fewer files for the emulated dpkg).
packages=(systemd systemd-sysv udev kmod iproute2 procps gpiod
  dbus avahi-daemon avahi-utils libnss-mdns
  passwd libgpiod2 libsystemd0 libavahi-client3 libmbedcrypto7 libcurl4 libmosquitto1 libstdc++6)
sources=()
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*; do
  [ -f "$f" ] || continue
  grep -q 'deb.debian.org' "$f" && sources+=("$f")
done
[ ${#sources[@]} -gt 0 ] || { echo "pi_vm image: no Debian apt source in /etc/apt"; exit 1; }
TMPDIR=$tmp mmdebstrap --verbose --arch=arm64 --variant=minbase --mode=root \
  --include="$(IFS=,; echo "${packages[*]}")" \
  --dpkgopt='path-exclude=/usr/share/doc/*' --dpkgopt='path-exclude=/usr/share/man/*' \
  --dpkgopt='path-exclude=/usr/share/locale/*' --dpkgopt='path-exclude=/usr/share/info/*' \
  bookworm "$out/rootfs" "${sources[@]}" 2>&1 | stamp >"$out/mmdebstrap.log" ||
  { tail -30 "$out/mmdebstrap.log"; echo "pi_vm image: mmdebstrap failed ($out/mmdebstrap.log)"; exit 1; }
t_debootstrap=$(($(date +%s) - start))
cpu_now
c_debootstrap=$cpu
r="$out/rootfs"
# A fixed machine-id (no "first boot" each time), a host name to announce,
# root without a password on the serial console.
echo 5e1f0c0a9d6b4b6f8f3c2a1b0d9e8f7a >"$r/etc/machine-id"
echo pi-vm >"$r/etc/hostname"
sed -i 's/^root:[^:]*:/root::/' "$r/etc/shadow"
# The network: user-mode networking's DHCP, through systemd-networkd.
printf '[Match]\nName=en* eth*\n[Network]\nDHCP=ipv4\n' >"$r/etc/systemd/network/10-wired.network"
# The runner: mounts the host's 9p share and runs the checks it holds
# (guest.sh), so changing them needs no new image. Type=simple: a oneshot
# unit waiting for the boot inside the boot deadlocks.
mkdir -p "$r/mnt/share"
cat >"$r/etc/systemd/system/pi-vm-runner.service" <<'UNIT'
[Unit]
Description=tests/pi_vm checks from the host's share
After=multi-user.target
[Service]
Type=simple
ExecStart=/bin/sh -c 'mount -t 9p -o trans=virtio,version=9p2000.L,cache=none share /mnt/share && exec /bin/bash /mnt/share/guest.sh'
StandardOutput=journal+console
StandardError=journal+console
[Install]
WantedBy=multi-user.target
UNIT
systemctl --root="$r" enable systemd-networkd.service pi-vm-runner.service >/dev/null 2>&1
# No apt or file system housekeeping in the middle of the checks.
systemctl --root="$r" mask apt-daily.timer apt-daily-upgrade.timer e2scrub_all.timer fstrim.timer \
  dpkg-db-backup.timer >/dev/null 2>&1
[ -L "$r/etc/systemd/system/multi-user.target.wants/pi-vm-runner.service" ] ||
  { echo "pi_vm image: cannot enable the runner"; exit 1; }
# Debian's arm64 kernel (the version linux-image-arm64 names on this
# machine's mirror), unpacked here: its modules into the root file system
# (depmod run here too), the kernel beside the image for a direct boot.
kname=$(apt-cache depends linux-image-arm64:arm64 |
  awk '$1 == "Depends:" && $2 ~ /^linux-image-/ { sub(/:arm64$/, "", $2); print $2; exit }')
[ -n "$kname" ] || { echo "pi_vm image: no linux-image-arm64:arm64 in this machine's apt lists (apt-get update)"; exit 1; }
kver=${kname#linux-image-}
k="$tmp/kernel"
mkdir -p "$k/x" "$k/busybox"
(cd "$k" && apt-get download -q "$kname:arm64" busybox-static:arm64 >/dev/null) ||
  { echo "pi_vm image: cannot download $kname:arm64, busybox-static:arm64"; exit 1; }
kpkg=$(dpkg-deb -f "$k/${kname}"_*_arm64.deb Version)
dpkg-deb -x "$k/${kname}"_*_arm64.deb "$k/x"
dpkg-deb -x "$k"/busybox-static_*_arm64.deb "$k/busybox"
mods="$r/usr/lib/modules/$kver"
mkdir -p "$r/usr/lib/modules"
cp -a "$k/x/lib/modules/$kver" "$mods"
depmod -b "$r" "$kver"
cp "$k/x/boot/vmlinuz-$kver" "$out/vmlinuz"
# The initrd: Debian's busybox-static and initrd-init.sh load the modules
# the root file system needs (the virtio disk, ext4 and what they depend
# on, by modules.dep; ext4 asks for crc32c at mount time) and start systemd.
ird="$k/initrd"
mkdir -p "$ird/bin" "$ird/modules"
cp "$k/busybox/bin/busybox" "$ird/bin/busybox"
install -m 0755 "$(dirname "$0")/initrd-init.sh" "$ird/init"
add_module() {
  local path dep
  path=$(grep -o "^[^:]*/$1\.ko:" "$mods/modules.dep" | tr -d :) || true
  [ -n "$path" ] || { echo "pi_vm image: no module $1 in $kver"; exit 1; }
  for dep in $(grep "^$path:" "$mods/modules.dep" | cut -d: -f2); do
    add_module "$(basename "$dep" .ko)"
  done
  grep -qx "$1.ko" "$ird/modules/order" 2>/dev/null && return 0
  cp "$mods/$path" "$ird/modules/"
  echo "$1.ko" >>"$ird/modules/order"
}
for module in virtio_mmio virtio_blk crc32c_generic ext4; do
  add_module "$module"
done
(cd "$ird" && find . | cpio -o -H newc -R 0:0 --quiet) >"$out/initrd.img"
echo "$kver" >"$out/kernel-release"
echo "$kpkg" >"$out/kernel-version"
# The headers of exactly this kernel, and Kbuild's host tools (amd64).
mkdir -p "$out/headers-debs"
(cd "$out/headers-debs" && apt-get download -q "linux-headers-$kver:arm64=$kpkg" \
  "linux-headers-${kver%-arm64}-common=$kpkg" "linux-kbuild-6.1:amd64=$kpkg" \
  "linux-source-6.1=$kpkg" >/dev/null) ||
  { echo "pi_vm image: cannot download the headers of $kver ($kpkg)"; exit 1; }
t_headers=$(($(date +%s) - start))
cpu_now
c_headers=$cpu
truncate -s 2G "$out/rootfs.img"
mkfs.ext4 -q -F -L pi-vm -d "$out/rootfs" "$out/rootfs.img"
echo "$recipe" >"$out/recipe"
cpu_now
echo "pi_vm image: built in $(($(date +%s) - start)) s, CPU $cpu s (mmdebstrap $t_debootstrap s, CPU $c_debootstrap s;" \
  "the kernel, initrd and headers $((t_headers - t_debootstrap)) s, CPU $((c_headers - c_debootstrap)) s;" \
  "the file system $(($(date +%s) - start - t_headers)) s, CPU $((cpu - c_headers)) s): kernel $kver ($kpkg)"
rm -rf "$out/rootfs" "$tmp"
