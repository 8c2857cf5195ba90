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
recipe=$(sha256sum "$0" | cut -c1-16)
if [ -f "$out/recipe" ] && [ "$(cat "$out/recipe")" = "$recipe" ] && [ -f "$out/rootfs.img" ]; then
  echo "pi_vm image: cached ($out, recipe $recipe)"
  exit 0
fi
missing=()
for tool in mmdebstrap mkfs.ext4 qemu-aarch64-static apt-get; do
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
start=$(date +%s)
rm -rf "$out"
mkdir -p "$out"
tmp="$out/tmp"
mkdir -p "$tmp"
# The machine: systemd as PID 1, udev, the GPIO tools (gpiod) that read the
# lines from inside, Avahi and its browser, and the rotord package's
# Depends (shlibs) and Recommends, so its install needs nothing from a mirror.
packages=(systemd systemd-sysv udev kmod iproute2 procps gpiod initramfs-tools zstd linux-image-arm64
  dbus avahi-daemon avahi-utils libnss-mdns
  passwd libgpiod2 libsystemd0 libavahi-client3 libmbedcrypto7 libcurl4 libmosquitto1 libstdc++6)
# Only the modules the direct boot needs in the initrd: MODULES=most made
# mkinitramfs under qemu-user take most of the build's time.
# (/usr/share/initramfs-tools/modules.d: not a conffile, unlike .../modules.)
setup_hook='mkdir -p "$1/etc/initramfs-tools/conf.d" "$1/usr/share/initramfs-tools/modules.d" && echo MODULES=list >"$1/etc/initramfs-tools/conf.d/pi_vm" && printf "virtio_mmio\nvirtio_blk\next4\n" >"$1/usr/share/initramfs-tools/modules.d/pi_vm"'
sources=()
for f in /etc/apt/sources.list /etc/apt/sources.list.d/*; do
  [ -f "$f" ] || continue
  grep -q 'deb.debian.org' "$f" && sources+=("$f")
done
[ ${#sources[@]} -gt 0 ] || { echo "pi_vm image: no Debian apt source in /etc/apt"; exit 1; }
TMPDIR=$tmp mmdebstrap --arch=arm64 --variant=minbase --mode=root \
  --include="$(IFS=,; echo "${packages[*]}")" \
  --setup-hook="$setup_hook" \
  bookworm "$out/rootfs" "${sources[@]}" >"$out/mmdebstrap.log" 2>&1 ||
  { tail -30 "$out/mmdebstrap.log"; echo "pi_vm image: mmdebstrap failed ($out/mmdebstrap.log)"; exit 1; }
t_debootstrap=$(($(date +%s) - start))
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
[ -L "$r/etc/systemd/system/multi-user.target.wants/pi-vm-runner.service" ] ||
  { echo "pi_vm image: cannot enable the runner"; exit 1; }
kver=$(ls "$out/rootfs/lib/modules" | head -1)
cp "$out/rootfs/boot/vmlinuz-$kver" "$out/vmlinuz"
cp "$out/rootfs/boot/initrd.img-$kver" "$out/initrd.img"
echo "$kver" >"$out/kernel-release"
chroot "$out/rootfs" dpkg-query -W -f='${Version}' "linux-image-$kver" >"$out/kernel-version"
# The headers of exactly this kernel, and Kbuild's host tools (amd64).
kpkg=$(cat "$out/kernel-version")
mkdir -p "$out/headers-debs"
(cd "$out/headers-debs" && apt-get download -q "linux-headers-$kver:arm64=$kpkg" \
  "linux-headers-${kver%-arm64}-common=$kpkg" "linux-kbuild-6.1:amd64=$kpkg" \
  "linux-source-6.1=$kpkg" >/dev/null) ||
  { echo "pi_vm image: cannot download the headers of $kver ($kpkg)"; exit 1; }
t_headers=$(($(date +%s) - start))
truncate -s 2G "$out/rootfs.img"
mkfs.ext4 -q -F -L pi-vm -d "$out/rootfs" "$out/rootfs.img"
rm -rf "$out/rootfs" "$tmp"
echo "$recipe" >"$out/recipe"
echo "pi_vm image: built in $(($(date +%s) - start)) s (mmdebstrap $t_debootstrap s, headers $((t_headers - t_debootstrap)) s): kernel $kver ($kpkg)"
