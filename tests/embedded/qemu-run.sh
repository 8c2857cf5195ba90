#!/usr/bin/env bash
# Runs one bare-metal test image under qemu and returns its exit status.
#   tests/embedded/qemu-run.sh build-embedded/tests/embedded/m0_selftest [--gtest_filter=...]
# Output and the exit status travel over ARM semihosting (newlib's librdimon).
# Board: mps2-an385, see README.md. QEMU_TIMEOUT (seconds, default 300) bounds a
# run that hangs; ctest has its own timeout on top. QEMU_EXTRA_ARGS adds qemu
# options (m0_tracking_timing: "-icount shift=0", one instruction per virtual ns).
set -euo pipefail

if [ $# -lt 1 ]; then
  echo "usage: $0 IMAGE [ARGS...]" >&2
  exit 2
fi
qemu=${QEMU:-qemu-system-arm}
if ! command -v "$qemu" >/dev/null 2>&1; then
  echo "$0: $qemu not found: run scripts/install-deps.sh (Debian package qemu-system-arm)" >&2
  exit 2
fi

# The semihosting command line is argv[0] plus the arguments, joined by spaces
# (startup.cpp splits it again); qemu's option syntax escapes a comma as ",,".
semi="enable=on,target=native"
for arg in "$1" "${@:2}"; do
  semi+=",arg=${arg//,/,,}"
done

# The board's Ethernet controller gets an isolated backend only because qemu
# warns about a NIC without one; the tests use no network.
exec timeout --kill-after=10 "${QEMU_TIMEOUT:-300}" \
  "$qemu" -M mps2-an385 -nodefaults -nographic -monitor none -serial null -nic user,restrict=on \
  ${QEMU_EXTRA_ARGS:-} -semihosting-config "$semi" -kernel "$1"
