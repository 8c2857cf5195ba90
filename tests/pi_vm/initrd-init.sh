#!/bin/busybox sh
# shellcheck shell=dash
# /init of the pi_vm machine's initrd (build-image.sh makes it on the host):
# Debian's arm64 kernel builds the virtio disk and ext4 as modules, so they
# are loaded here (in the order of the list beside this script), then the
# disk is mounted and systemd started on it. Debian's busybox-static:arm64
# runs it; mkinitramfs does the same, but under qemu-user it was a large
# share of the image's build time.
/bin/busybox mkdir -p /dev /proc /root
/bin/busybox mount -t devtmpfs devtmpfs /dev
/bin/busybox mount -t proc proc /proc
while read -r module; do
  /bin/busybox insmod "/modules/$module" || echo "initrd: insmod $module failed"
done </modules/order
# No udev here to say when the virtio disk appears: poll for it. The wait
# ends on the condition; its bound (60 s of emulated time) only ends a boot
# that went wrong, and is wide for a loaded host under plain emulation.
n=0
until [ -b /dev/vda ]; do
  n=$((n + 1))
  [ $n -gt 600 ] && { echo "initrd: no /dev/vda after 60 s"; exec /bin/busybox sh; }
  /bin/busybox sleep 0.1
done
/bin/busybox mount -t ext4 -o rw /dev/vda /root || { echo "initrd: cannot mount /dev/vda"; exec /bin/busybox sh; }
/bin/busybox umount /proc
/bin/busybox mount --move /dev /root/dev
exec /bin/busybox switch_root /root /sbin/init
