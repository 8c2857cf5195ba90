#!/bin/bash
# cross.ARCH (tests/cross/CMakeLists.txt): configure, build and test the
# cross-ARCH preset; prints the time of each phase.
set -uo pipefail
arch=$1 cmake=$2 ctest=$3
triplet=$([ "$arch" = arm64 ] && echo aarch64-linux-gnu || echo arm-linux-gnueabihf)
missing=()
command -v "$triplet-g++" >/dev/null || missing+=("crossbuild-essential-$arch")
command -v "qemu-$([ "$arch" = arm64 ] && echo aarch64 || echo arm)-static" >/dev/null ||
  missing+=(qemu-user-static)
libs=(libgtest-dev libgmock-dev)
[ "$arch" = arm64 ] && libs+=(libgpiod-dev libsystemd-dev libavahi-client-dev libmbedtls-dev
  libcurl4-openssl-dev libmosquitto-dev)
for lib in "${libs[@]}"; do
  dpkg-query -W -f='${Status}' "$lib:$arch" 2>/dev/null | grep -q "install ok installed" ||
    missing+=("$lib:$arch")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "FAIL: cross.$arch: missing ${missing[*]} (scripts/install-deps.sh; dpkg --add-architecture $arch)"
  exit 1
fi
t0=$(date +%s)
"$cmake" --preset "cross-$arch" >/dev/null || { echo "FAIL: configure cross-$arch"; exit 1; }
t1=$(date +%s)
"$cmake" --build --preset "cross-$arch" -j 2 || { echo "FAIL: build cross-$arch"; exit 1; }
t2=$(date +%s)
"$ctest" --preset "cross-$arch" -j 2 --no-tests=error
rc=$?
t3=$(date +%s)
echo "cross.$arch: configure $((t1 - t0)) s, build $((t2 - t1)) s, tests under qemu-user $((t3 - t2)) s"
exit $rc
