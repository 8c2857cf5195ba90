#!/usr/bin/env bash
# Builds rotord's Debian package (debian/) with dpkg-buildpackage from a copy
# of the source tree in $DEB_BUILD_DIR (default build-deb), since debhelper
# works inside the tree it builds and writes the .deb next to it:
# $DEB_BUILD_DIR/rotord_<version>_<arch>.deb. Unsigned (-us -uc), binary
# only (-b), for the build machine's architecture or, with DEB_HOST_ARCH
# (`make deb ARCH=arm64`), cross-built for another one with Debian's cross
# toolchain and the Build-Depends of that architecture (multiarch), which
# scripts/install-deps.sh --deb ARCH installs.
#   DEB_JOBS=N          parallel jobs (default: nproc)
#   DEB_HOST_ARCH=A     the package's architecture (arm64, armhf; default: this machine's)
#   ROTORD_PREBUILT=F   package the binary F instead of building one (CI)
#   DEB_CHROOT=1        build in scripts/deb-chroot.sh's Debian 12 chroot for
#                       DEB_HOST_ARCH instead of on this machine (the Makefile's
#                       default for armhf; docs/raspberry-pi.md says why)
set -euo pipefail
cd "$(dirname "$0")/.."
top=$(pwd)
out=$(realpath -m "${DEB_BUILD_DIR:-build-deb}")
src="$out/rotord"
rm -rf "$src" "$out"/rotord_* "$out"/rotord-dbgsym_*
mkdir -p "$src"
# The tracked files and new ones not ignored, as they are in the work tree
# (uncommitted changes included); no build directories, no .git.
git ls-files -z --cached --others --exclude-standard |
  grep -zv -e '^build' -e '^rotord_.*\.deb$' |
  xargs -0 -I{} sh -c '[ -e "{}" ] && printf "%s\0" "{}"' |
  tar --null -T - -cf - | tar -xf - -C "$src"
# The map's data (core/web/world_map.cmake): npm's, ignored by git, put in
# web/map/node_modules by scripts/install-deps.sh.
if [ -d web/map/node_modules/world-atlas ]; then
  mkdir -p "$src/web/map/node_modules"
  cp -a web/map/node_modules/world-atlas "$src/web/map/node_modules/"
fi
cd "$src"
export DEB_BUILD_OPTIONS="${DEB_BUILD_OPTIONS:+$DEB_BUILD_OPTIONS }parallel=${DEB_JOBS:-$(nproc)}"
if command -v ccache >/dev/null; then
  export CMAKE_CXX_COMPILER_LAUNCHER=ccache CMAKE_C_COMPILER_LAUNCHER=ccache
fi
arch_opts=()
if [ -n "${DEB_HOST_ARCH:-}" ] && [ "$DEB_HOST_ARCH" != "$(dpkg --print-architecture)" ]; then
  # nocheck: nothing to run on this machine; the cross suites run the
  # binaries under qemu-user instead (tests/cross).
  export DEB_BUILD_OPTIONS="$DEB_BUILD_OPTIONS nocheck"
  arch_opts=(-a "$DEB_HOST_ARCH")
fi
if [ "${DEB_CHROOT:-0}" = 1 ]; then
  [ ${#arch_opts[@]} -gt 0 ] || { echo "build-deb: DEB_CHROOT=1 needs a DEB_HOST_ARCH other than this machine's"; exit 1; }
  # The chroot sees $out at /build: a prebuilt binary goes there too.
  if [ -n "${ROTORD_PREBUILT:-}" ]; then
    cp "$ROTORD_PREBUILT" "$out/rotord.prebuilt"
    export ROTORD_PREBUILT=/build/rotord.prebuilt
  fi
  exec "$top/scripts/deb-chroot.sh" "$DEB_HOST_ARCH" "$out" dpkg-buildpackage -b -us -uc "${arch_opts[@]}"
fi
dpkg-buildpackage -b -us -uc "${arch_opts[@]}"
