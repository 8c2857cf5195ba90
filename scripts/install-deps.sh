#!/usr/bin/env bash
# Installs the Debian packages (and the npm packages of the web tests) that the
# build and the test suite need. Idempotent: does nothing when all are present.
# Used by `make run` and `make test`, so a fresh Debian 12 machine needs no
# manual step. `--deb` (`make deb`, e.g. on a Raspberry Pi): only what
# building the Debian package needs (debian/control's Build-Depends);
# `--deb ARCH` (`make deb ARCH=arm64`): the same to cross-build for ARCH
# (Debian's cross toolchain and ARCH's libraries, multiarch).
#
# The full set includes the Raspberry Pi path's (tests/cross, tests/pi_vm):
# arm64 and armhf cross toolchains and libraries, qemu-user to run their
# binaries, and qemu-system-arm, mmdebstrap and the arm64 kernel's build
# tools to boot a Debian 12 arm64 machine.
set -euo pipefail

# What `make deb` needs: debian/control's Build-Depends, dpkg-buildpackage, git.
deb_packages=(
  build-essential dpkg-dev debhelper cmake ninja-build pkg-config gzip git
  libasio-dev libcli11-dev libgpiod-dev libsystemd-dev libavahi-client-dev libmbedtls-dev
  libcurl4-openssl-dev libmosquitto-dev
)
# The Build-Depends that are libraries of the package's architecture (the
# rest run on the build machine).
deb_arch_libs=(
  libgpiod-dev libsystemd-dev libavahi-client-dev libmbedtls-dev libcurl4-openssl-dev
  libmosquitto-dev
)
# For ARCH: its cross toolchain, its libraries and, for the test suites, GoogleTest.
cross_packages() {
  local arch=$1 lib
  echo "crossbuild-essential-$arch"
  for lib in "${deb_arch_libs[@]}"; do echo "$lib:$arch"; done
}
# The Pi machine under qemu-system (tests/pi_vm): the image (mmdebstrap,
# e2fsprogs; kmod's depmod and cpio for the kernel's modules and initrd,
# made on this machine), running arm64 programs while it is built (qemu-user),
# and the gpio-sim module's build (make, bc; Kbuild's host tools come built
# in Debian's linux-kbuild package, the compiler from crossbuild-essential-arm64).
pi_vm_packages=(qemu-system-arm qemu-user-static binfmt-support mmdebstrap arch-test e2fsprogs kmod cpio bc
  make)
packages=(
  "${deb_packages[@]}"
  clang-format
  libgtest-dev libgmock-dev libbenchmark-dev
  libasio-dev libcli11-dev nlohmann-json3-dev
  libhamlib-utils socat netcat-openbsd python3
  valgrind
  gcc-arm-none-eabi libnewlib-arm-none-eabi libstdc++-arm-none-eabi-newlib qemu-system-arm
  liblwip-dev libgpiod-dev libcurl4-openssl-dev
  avahi-daemon avahi-utils dbus-daemon util-linux
  lintian systemd man-db
  prometheus
  libmosquitto-dev mosquitto mosquitto-clients python3-jsonschema openssl
  curl xz-utils
  clang libclang-rt-14-dev
  chromium
)
cross_arch=""
if [ "${1:-}" = "--deb" ]; then
  packages=("${deb_packages[@]}")
  cross_arch=${2:-}
  [ "$cross_arch" = "$(dpkg --print-architecture)" ] && cross_arch=""
fi
# `--deb-chroot ARCH` (`make deb ARCH=armhf`): the package is built in a
# Debian 12 chroot that has its own toolchain and libraries
# (scripts/deb-chroot.sh): here only mmdebstrap to make it, git to copy the
# tree, and node's npm (below) for the map's data.
if [ "${1:-}" = "--deb-chroot" ]; then
  packages=(mmdebstrap git)
fi
# node and npm build the map's data (and run the web tests): Debian's, unless
# the machine already has both (Debian's npm pulls in some 300 packages).
if ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

sudo_cmd=()
[ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
export DEBIAN_FRONTEND=noninteractive
apt_updated=no
# Installs the packages named that are missing; fails as apt-get does.
install_missing() {
  local p missing=()
  for p in "$@"; do
    if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
      missing+=("$p")
    fi
  done
  [ ${#missing[@]} -eq 0 ] && return 0
  echo "install-deps: installing ${missing[*]}"
  if [ $apt_updated = no ]; then
    # A mirror caught mid-sync fails one index (often another architecture's):
    # the install below still fails, naming the package, if one is really missing.
    "${sudo_cmd[@]}" apt-get update -q || echo "install-deps: WARNING: apt-get update reported errors; installing anyway" >&2
    apt_updated=yes
  fi
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
}
# ARCH's packages: dpkg must know the architecture first (multiarch).
install_cross() {
  local arch=$1
  shift
  if ! dpkg --print-foreign-architectures | grep -qx "$arch"; then
    echo "install-deps: dpkg --add-architecture $arch"
    "${sudo_cmd[@]}" dpkg --add-architecture "$arch"
    apt_updated=no
  fi
  mapfile -t pkgs < <(cross_packages "$arch")
  install_missing "${pkgs[@]}" "$@"
}

install_missing "${packages[@]}"
if [ -n "$cross_arch" ]; then
  install_cross "$cross_arch"
elif [ "${1:-}" != "--deb" ] && [ "${1:-}" != "--deb-chroot" ]; then
  # The cross suites (tests/cross) and the Pi machine (tests/pi_vm): a
  # failure (a mirror whose foreign-architecture index is mid-sync, so
  # versions differ from this machine's) only warns here; those tests then
  # fail naming what is missing, the rest of the suite runs.
  install_cross arm64 libgtest-dev:arm64 libgmock-dev:arm64 ||
    echo "install-deps: WARNING: cannot install the arm64 cross packages: cross.arm64 and pi_vm will fail" >&2
  # armhf: the core's suites only (tests/cross), which need no library of
  # the daemon's, so none whose version must match this machine's.
  if ! dpkg --print-foreign-architectures | grep -qx armhf; then
    "${sudo_cmd[@]}" dpkg --add-architecture armhf
    apt_updated=no
  fi
  install_missing crossbuild-essential-armhf libgtest-dev:armhf libgmock-dev:armhf ||
    echo "install-deps: WARNING: cannot install the armhf cross packages: cross.armhf will fail" >&2
  install_missing "${pi_vm_packages[@]}" ||
    echo "install-deps: WARNING: cannot install ${pi_vm_packages[*]}: tests/pi_vm will fail" >&2
fi

# The map page's coastlines and borders (world-atlas, pinned in
# web/map/package-lock.json): converted into the web assets at build time
# (core/web/world_map.cmake), for the daemon and the Pico W image alike.
if [ -f web/map/package.json ] && [ ! -f web/map/node_modules/world-atlas/countries-110m.json ]; then
  (cd web/map && npm ci --no-audit --no-fund --loglevel=error)
fi

# Browser tests drive Debian's chromium with playwright-core (no browser download).
if [ "${1:-}" = "--with-web" ] && [ -f tests/web/package.json ]; then
  if [ ! -d tests/web/node_modules/playwright-core ]; then
    (cd tests/web && npm ci --no-audit --no-fund --loglevel=error)
  fi
fi

# lwIP's MQTT client source (src/apps/mqtt/mqtt.c) for the host test of the
# Pico W's MQTT glue (tests/lwip/lwip_mqtt_test.cpp): Debian's liblwip-dev
# ships its header but not its source. Debian's own source tarball of the
# same version, checksum-verified, unpacked into the build tree
# (BUILD_DIR, default build: <build>/_deps/lwip-2.1.3); never committed. A
# failed download only warns here: that test then fails, naming the file.
fetch_lwip_source() {
  local deps="${BUILD_DIR:-build}/_deps"
  local url="http://deb.debian.org/debian/pool/main/l/lwip/lwip_2.1.3+dfsg1.orig.tar.xz"
  local sha256="0a8276d09fc4e97bbba2f953d74af2388fc2195ea156be9d7589e297a68fde24"
  local tarball="$deps/lwip_2.1.3+dfsg1.orig.tar.xz"
  [ -f "$deps/lwip-2.1.3/src/apps/mqtt/mqtt.c" ] && return 0
  mkdir -p "$deps"
  if [ ! -f "$tarball" ]; then
    echo "install-deps: fetching lwIP 2.1.3's source (for its MQTT client) from Debian"
    curl -fsSL -o "$tarball.part" "$url" || { rm -f "$tarball.part"; return 1; }
    mv "$tarball.part" "$tarball"
  fi
  if ! echo "$sha256  $tarball" | sha256sum -c --quiet -; then
    echo "install-deps: $tarball has the wrong checksum; removed" >&2
    rm -f "$tarball"
    return 1
  fi
  tar -xJf "$tarball" -C "$deps" lwip-2.1.3/src/apps/mqtt lwip-2.1.3/COPYING
}
if [ "${1:-}" != "--deb" ] && [ "${1:-}" != "--deb-chroot" ]; then
  fetch_lwip_source || echo "install-deps: WARNING: no lwIP source: the Pico W's MQTT host test (lwip_mqtt_tests) will fail" >&2
fi

# The emulated-RP2040 harness (make hil, and its unit tests in make test):
# rp2040js, pinned in tests/hil/package-lock.json.
if [ "${1:-}" = "--with-web" ] && [ -f tests/hil/package.json ]; then
  if [ ! -d tests/hil/node_modules/rp2040js ]; then
    (cd tests/hil && npm ci --no-audit --no-fund --loglevel=error)
  fi
fi
