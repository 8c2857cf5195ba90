#!/bin/bash
# Usage: deb-chroot.sh ARCH DIR COMMAND...   (scripts/build-deb.sh, DEB_CHROOT=1)
#
# Runs COMMAND in DIR/rotord inside a Debian 12 chroot that cross-builds
# for ARCH: plain bookworm from this machine's Debian mirror, without the
# security suite, for amd64 and ARCH (multiarch), with the cross toolchain
# (crossbuild-essential-ARCH) and debian/control's Build-Depends of ARCH
# (apt-get build-dep -a ARCH), made by mmdebstrap into
# build/deb-chroot-ARCH (BUILD_DIR), never committed, kept between runs and
# made again only when its recipe (this script, debian/control) changes.
#
# Why a chroot: multiarch needs every shared library at the same version
# for both architectures, and this machine's amd64 libraries come from the
# security suite, whose ARCH index a mirror between two syncs can fail
# (apt-get update: "File has unexpected size ... Mirror sync in
# progress?"; seen for armhf on 2026-11-27, and libsasl2's armhf security
# build was in no pool at all): apt then refuses ARCH's libraries. One
# suite's index, read at one moment for both architectures, has matching
# versions. The package's Depends (shlibs) are those of bookworm's point
# release, which every later security update satisfies.
#
# DIR (the copy of the tree scripts/build-deb.sh made) is bound at
# /build, so the .deb lands in DIR as it does outside. The compiler cache
# (CCACHE_DIR) is bound at its own path. The mounts live in a private mount
# namespace (unshare): they end with the command, whatever happens.
# Root only (mmdebstrap --mode=root, chroot, mount), like tests/pi_vm.
# Prints each phase's wall and CPU time.
set -euo pipefail
arch=$1 dir=$(realpath "$2")
shift 2
here=$(cd "$(dirname "$0")/.." && pwd)
root=$(realpath -m "${BUILD_DIR:-$here/build}")/deb-chroot-$arch
r="$root/rootfs"
[ "$(id -u)" -eq 0 ] || { echo "deb-chroot: needs root (mmdebstrap --mode=root, chroot): sudo make deb ARCH=$arch, or DEB_CHROOT=0"; exit 1; }
missing=()
for tool in mmdebstrap unshare chroot; do
  command -v "$tool" >/dev/null || missing+=("$tool")
done
[ ${#missing[@]} -eq 0 ] || { echo "deb-chroot: missing ${missing[*]} (scripts/install-deps.sh --deb-chroot)"; exit 1; }

# CPU seconds (user + sys) of the finished child processes so far: what a
# phase costs on a free machine, whatever else loads this one.
# (times runs in this shell, not in a subshell, which would count none.)
cpu_file=$(mktemp)
trap 'rm -f "$cpu_file"' EXIT
cpu_now() {
  times >"$cpu_file"
  cpu=$(awk 'NR == 2 { split($1, u, "m"); split($2, s, "m"); printf "%.0f", u[1] * 60 + u[2] + s[1] * 60 + s[2] }' "$cpu_file")
}
start=$EPOCHSECONDS

recipe=$(cat "$0" "$here/debian/control" | sha256sum | cut -c1-16)
if [ -f "$root/recipe" ] && [ "$(cat "$root/recipe")" = "$recipe" ] && [ -x "$r/usr/bin/dpkg-buildpackage" ]; then
  echo "deb-chroot: cached ($root, recipe $recipe)"
else
  if grep -q " $(realpath -m "$root")/" /proc/mounts; then
    echo "deb-chroot: file systems are still mounted under $root (an interrupted mmdebstrap): unmount them"
    exit 1
  fi
  # This machine's Debian mirror (its apt sources), the main archive only.
  mirror=${ROTORD_DEBIAN_MIRROR:-}
  if [ -z "$mirror" ]; then
    mirror=$(cat /etc/apt/sources.list /etc/apt/sources.list.d/* 2>/dev/null |
      grep -v '^\s*#' | grep -oE 'https?://[^ ]+/debian/?( |$)' | head -1 | tr -d ' ' || true)
  fi
  mirror=${mirror:-http://deb.debian.org/debian}
  echo "deb-chroot: making the $arch build chroot in $root (mmdebstrap, bookworm from $mirror)"
  rm -rf "$root"
  mkdir -p "$root/tmp"
  # Each line of mmdebstrap's log with the seconds since the start.
  stamp() { while IFS= read -r line; do echo "$((EPOCHSECONDS - start)) $line"; done; }
  deps=/tmp/rotord-build-deps
  # In a private mount namespace too: the file systems mmdebstrap mounts
  # in the chroot end with it even if it is killed, and no `rm -rf build`
  # can reach this machine's /dev through them.
  TMPDIR="$root/tmp" unshare --mount --propagation private -- mmdebstrap --verbose --variant=buildd --mode=root \
    --architectures="$(dpkg --print-architecture),$arch" \
    --include="crossbuild-essential-$arch,ccache" \
    --dpkgopt='path-exclude=/usr/share/doc/*' --dpkgopt='path-exclude=/usr/share/man/*' \
    --dpkgopt='path-exclude=/usr/share/locale/*' --dpkgopt='path-exclude=/usr/share/info/*' \
    --customize-hook="mkdir -p \"\$1$deps/debian\"" \
    --customize-hook="copy-in $here/debian/control $deps/debian" \
    --customize-hook="chroot \"\$1\" env DEBIAN_FRONTEND=noninteractive apt-get build-dep -y -q --no-install-recommends -a $arch $deps" \
    --customize-hook="rm -rf \"\$1$deps\"" \
    bookworm "$r" "deb $mirror bookworm main" 2>&1 | stamp >"$root/mmdebstrap.log" ||
    { tail -30 "$root/mmdebstrap.log"; echo "deb-chroot: mmdebstrap failed ($root/mmdebstrap.log)"; exit 1; }
  rm -rf "$root/tmp"
  echo "$recipe" >"$root/recipe"
  cpu_now
  echo "deb-chroot: made in $((EPOCHSECONDS - start)) s, CPU $cpu s ($(du -sm "$r" | cut -f1) MB)"
fi

# The command, in a private mount namespace: /proc, /dev, DIR at /build,
# the compiler cache; this machine's environment, less what names its paths.
t_build=$EPOCHSECONDS
cpu_now
c_build=$cpu
binds=("$dir:/build")
if [ -n "${CCACHE_DIR:-}" ] && [ -d "$CCACHE_DIR" ]; then
  binds+=("$CCACHE_DIR:$CCACHE_DIR")
fi
env_args=(HOME=/root PATH=/usr/sbin:/usr/bin:/sbin:/bin LANG=C.UTF-8)
for var in $(compgen -e); do
  case $var in
    DEB_* | CCACHE_* | CMAKE_*_COMPILER_LAUNCHER | ROTORD_PREBUILT | SOURCE_DATE_EPOCH) env_args+=("$var=${!var}") ;;
  esac
done
# shellcheck disable=SC2016 # expanded by the inner shell
unshare --mount --propagation private -- bash -c '
  set -e
  r=$1 n=$2
  shift 2
  mount -t proc proc "$r/proc"
  mount --rbind /dev "$r/dev"
  for ((i = 0; i < n; i++)); do
    from=${1%%:*} to=${1#*:}
    shift
    mkdir -p "$r$to"
    mount --bind "$from" "$r$to"
  done
  exec chroot "$r" "$@"
' bash "$r" ${#binds[@]} "${binds[@]}" env -i "${env_args[@]}" \
  bash -c 'cd /build/rotord && exec "$@"' bash "$@"
cpu_now
echo "deb-chroot: $1 in the chroot: $((EPOCHSECONDS - t_build)) s, CPU $((cpu - c_build)) s"
