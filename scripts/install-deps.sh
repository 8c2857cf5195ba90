#!/usr/bin/env bash
# Installs the Debian packages (and the npm packages of the web tests) that the
# build and the test suite need. Idempotent: does nothing when all are present.
# Used by `make run` and `make test`, so a fresh Debian 12 machine needs no
# manual step. `--deb` (`make deb`, e.g. on a Raspberry Pi): only what
# building the Debian package needs (debian/control's Build-Depends).
set -euo pipefail

# What `make deb` needs: debian/control's Build-Depends, dpkg-buildpackage, git.
deb_packages=(
  build-essential dpkg-dev debhelper cmake ninja-build pkg-config gzip git
  libasio-dev libcli11-dev libgpiod-dev libsystemd-dev libavahi-client-dev libmbedtls-dev
  libcurl4-openssl-dev
)
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
  libmosquitto-dev mosquitto mosquitto-clients python3-jsonschema
  clang libclang-rt-14-dev
  chromium
)
if [ "${1:-}" = "--deb" ]; then
  packages=("${deb_packages[@]}")
elif ! command -v node >/dev/null 2>&1 || ! command -v npm >/dev/null 2>&1; then
  packages+=(nodejs npm)
fi

missing=()
for p in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$p")
  fi
done

if [ ${#missing[@]} -gt 0 ]; then
  echo "install-deps: installing ${missing[*]}"
  sudo_cmd=()
  [ "$(id -u)" -ne 0 ] && sudo_cmd=(sudo)
  export DEBIAN_FRONTEND=noninteractive
  "${sudo_cmd[@]}" apt-get update -q
  "${sudo_cmd[@]}" apt-get install -y -q --no-install-recommends "${missing[@]}"
fi

# Browser tests drive Debian's chromium with playwright-core (no browser download).
if [ "${1:-}" = "--with-web" ] && [ -f tests/web/package.json ]; then
  if [ ! -d tests/web/node_modules/playwright-core ]; then
    (cd tests/web && npm ci --no-audit --no-fund --loglevel=error)
  fi
fi
# The emulated-RP2040 harness (make hil, and its unit tests in make test):
# rp2040js, pinned in tests/hil/package-lock.json.
if [ "${1:-}" = "--with-web" ] && [ -f tests/hil/package.json ]; then
  if [ ! -d tests/hil/node_modules/rp2040js ]; then
    (cd tests/hil && npm ci --no-audit --no-fund --loglevel=error)
  fi
fi
