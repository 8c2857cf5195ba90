#!/bin/bash
# Builds the gpio-sim kernel module for the pi_vm image's kernel into $2
# (build/pi_vm/gpio-sim/gpio-sim.ko), from $1 (the image directory,
# build-image.sh): Debian's 6.1 arm64 kernel builds neither CONFIG_GPIO_SIM
# nor the IRQ simulator it needs (CONFIG_IRQ_SIM), so both are compiled out
# of tree from Debian's linux-source-6.1 of the same version, against the
# image's kernel headers, with Debian's cross compiler. The kernel source
# (GPL-2.0) is extracted here at build time and never committed. Cached
# per kernel version.
set -euo pipefail
img=$(realpath "$1") out=$(realpath -m "$2")
kver=$(cat "$img/kernel-release") kpkg=$(cat "$img/kernel-version")
if [ -f "$out/gpio-sim.ko" ] && [ "$(cat "$out/kernel-version" 2>/dev/null)" = "$kpkg" ]; then
  echo "gpio-sim: cached ($out/gpio-sim.ko, $kver $kpkg)"
  exit 0
fi
command -v aarch64-linux-gnu-gcc >/dev/null ||
  { echo "gpio-sim: aarch64-linux-gnu-gcc missing (crossbuild-essential-arm64)"; exit 1; }
command -v bc >/dev/null || { echo "gpio-sim: bc missing"; exit 1; }
start=$(date +%s)
rm -rf "$out/root" "$out/module" "$out/gpio-sim.ko"
mkdir -p "$out/root"
# CPU seconds (user + sys) of the finished child processes so far (times
# runs in this shell: a subshell would count none).
cpu_file="$out/cpu.times"
cpu_now() {
  times >"$cpu_file"
  cpu=$(awk 'NR == 2 { split($1, u, "m"); split($2, s, "m"); printf "%.0f", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "$cpu_file")
}
for deb in "$img"/headers-debs/linux-headers-*.deb "$img"/headers-debs/linux-kbuild-*.deb; do
  dpkg-deb -x "$deb" "$out/root"
done
# Three files of the source: the driver, gpiolib's private header and the
# IRQ simulator. Only these members are written to disk (kept, per version).
if [ "$(cat "$out/src/version" 2>/dev/null)" != "$kpkg" ]; then
  rm -rf "$out/src"
  mkdir -p "$out/src"
  # --occurrence: tar stops reading once it has the three (kernel/irq is
  # about half way through the tree), so the rest is never decompressed;
  # the processes feeding it then end on a broken pipe, hence no pipefail.
  files=(drivers/gpio/gpio-sim.c drivers/gpio/gpiolib.h kernel/irq/irq_sim.c)
  set +o pipefail
  dpkg-deb --fsys-tarfile "$img"/headers-debs/linux-source-6.1_*.deb 2>/dev/null |
    tar -xO --occurrence ./usr/src/linux-source-6.1.tar.xz 2>/dev/null |
    tar -xJ --occurrence -C "$out/src" --strip-components=1 "${files[@]/#/linux-source-6.1/}"
  set -o pipefail
  for f in "${files[@]}"; do
    [ -s "$out/src/$f" ] || { echo "gpio-sim: $f not in linux-source-6.1 ($kpkg)"; exit 1; }
  done
  echo "$kpkg" >"$out/src/version"
fi
t_src=$(($(date +%s) - start))
cpu_now
c_src=$cpu
m="$out/module"
mkdir -p "$m"
cp "$out/src/drivers/gpio/gpio-sim.c" "$m/gpio-sim-core.c"
cp "$out/src/drivers/gpio/gpiolib.h" "$m/gpiolib.h"
# irq_to_desc() is not exported to modules; generic_handle_irq() does the
# same lookup and handling. The simulator is private to this module.
sed -e 's/handle_simple_irq(irq_to_desc(\([a-z_>.-]*\)))/generic_handle_irq(\1)/' \
  -e '/^EXPORT_SYMBOL_GPL/d' "$out/src/kernel/irq/irq_sim.c" >"$m/irq_sim.c"
grep -q 'generic_handle_irq' "$m/irq_sim.c" || { echo "gpio-sim: irq_sim.c changed upstream"; exit 1; }
printf 'obj-m := gpio-sim.o\ngpio-sim-y := gpio-sim-core.o irq_sim.o\n' >"$m/Kbuild"
hdr="$out/root/usr/src/linux-headers-$kver"
common="$out/root/usr/src/linux-headers-${kver%-arm64}-common"
# The headers' Makefile includes the common tree's by its installed path.
sed -i "s|/usr/src/linux-headers-${kver%-arm64}-common|$common|g" "$hdr/Makefile"
# Kbuild's host tools (fixdep, modpost) come from the amd64 linux-kbuild
# package, linked from the headers; an absolute link is made to point into
# the extracted tree.
for link in "$hdr/scripts" "$hdr/tools"; do
  if [ -L "$link" ] && [[ "$(readlink "$link")" = /* ]]; then
    ln -sfn "$out/root$(readlink "$link")" "$link"
  fi
done
make -s -C "$hdr" M="$m" ARCH=arm64 CROSS_COMPILE=aarch64-linux-gnu- modules >"$out/build.log" 2>&1 ||
  { tail -30 "$out/build.log"; echo "gpio-sim: module build failed ($out/build.log)"; exit 1; }
cp "$m/gpio-sim.ko" "$out/gpio-sim.ko"
echo "$kpkg" >"$out/kernel-version"
rm -rf "$out/root"
cpu_now
echo "gpio-sim: built in $(($(date +%s) - start)) s, CPU $cpu s (the headers and 3 files of the source extracted" \
  "in $t_src s, CPU $c_src s) for $kver ($kpkg)"
