#!/usr/bin/env bash
# Builds every libFuzzer target (tests/fuzz/fuzz_*.cpp) with clang, ASan and
# UBSan against the core sources, and runs each for a bounded number of
# inputs. Used by ctest; `FUZZ_RUNS=1000000 tests/fuzz/run_fuzz.sh` digs deeper.
set -euo pipefail
src="$(cd "$(dirname "$0")/../.." && pwd)"
out="${FUZZ_BUILD_DIR:-$src/build/fuzz}"
runs="${FUZZ_RUNS:-20000}"
mkdir -p "$out"
core_sources=$(find "$src/core" -name '*.cpp' | sort)
# The web UI is compiled into the core from a generated source; make it here
# the same way core/web/assets.cmake does, so the core links on its own.
cmake -DGZIP="$(command -v gzip)" -DWEB_DIR="$src/web" -DOUT="$out/web_assets.cpp" \
  -P "$src/core/web/embed_assets.cmake"
core_sources="$core_sources $out/web_assets.cpp"
common=(-std=c++20 -O1 -g1 -fno-exceptions -fno-rtti -fno-sanitize-recover=undefined
        -I"$src/core" -I"$src/tests/unit" -DROTORD_VERSION='"fuzz"')
# The core is compiled once (instrumented for coverage, not linked with the
# fuzzer's main) and archived; each target then compiles only itself.
objdir="$out/core-objects"
rm -rf "$objdir"
mkdir -p "$objdir"
echo "== core: build"
printf '%s\n' $core_sources | xargs -P "$(nproc)" -I{} sh -c '
  source="$1"; shift
  clang++ "$@" -c "$source" -o "$0/$(echo "$source" | md5sum | cut -c1-16).o"' "$objdir" {} \
  "${common[@]}" -fsanitize=fuzzer-no-link,address,undefined
rm -f "$out/libcore_fuzz.a"
ar rcs "$out/libcore_fuzz.a" "$objdir"/*.o
for target in "$src"/tests/fuzz/fuzz_*.cpp; do
  name=$(basename "$target" .cpp)
  echo "== $name: build"
  clang++ "${common[@]}" -fsanitize=fuzzer,address,undefined "$target" "$out/libcore_fuzz.a" \
    -o "$out/$name"
  echo "== $name: $runs runs"
  mkdir -p "$out/$name.corpus"
  # Seed inputs (tests/fuzz/seeds/<target>/) start the search from real
  # documents; new inputs go to the first, writable, corpus directory.
  seeds=()
  [ -d "$src/tests/fuzz/seeds/$name" ] && seeds=("$src/tests/fuzz/seeds/$name")
  "$out/$name" -runs="$runs" -max_len=4096 -len_control=0 -seed=1 "$out/$name.corpus" \
    "${seeds[@]}" 2>&1 | tail -n 3
done
echo "fuzz: all targets ran clean"
