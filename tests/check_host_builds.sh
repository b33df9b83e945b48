#!/usr/bin/env bash
# check_host_builds.sh -- the real-time library (double and float) must build
# warning-free (it compiles with -Werror) under the flags and compilers a
# host project uses, not only under this project's own Release flags:
#
# 1. GCC at -O3 -march=x86-64-v4 (AVX-512 code generation, what
#    -march=native gives on an AVX-512 host): GCC 12's -Wmaybe-uninitialized
#    saw paths there that -O3 alone does not (session 52: sts_return_map.cpp
#    failed to build with -march=native).
# 2. Clang at -O3, when clang++ is installed (it is not a dependency of
#    `make test`; the check says so and skips): Clang has no
#    -fsingle-precision-constant (session 52: the float library failed to
#    configure a build under Clang).
#
# Only the library targets are built (no tests, benchmarks, offline tool or
# FMU), each in its own temporary tree, removed afterwards.
set -euo pipefail

src=$(cd "$(dirname "$0")/.." && pwd)
cmake_tool=${CMAKE:-cmake}
jobs=${JOBS:-2}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

# build NAME CC CXX FLAGS: configure and build rt_bushing and rt_bushing_float.
build() {
  local name=$1 cc=$2 cxx=$3 flags=$4 tree="$work/$1"
  if ! CC=$cc CXX=$cxx "$cmake_tool" -S "$src" -B "$tree" -DCMAKE_BUILD_TYPE=Release \
         -DCMAKE_C_FLAGS_RELEASE="$flags" -DCMAKE_CXX_FLAGS_RELEASE="$flags" \
         -DRTB_BUILD_TESTS=OFF -DRTB_BUILD_BENCH=OFF -DRTB_BUILD_OFFLINE=OFF \
         -DRTB_BUILD_FMU=OFF > "$tree.log" 2>&1 ||
     ! "$cmake_tool" --build "$tree" --parallel "$jobs" --target rt_bushing rt_bushing_float \
         >> "$tree.log" 2>&1; then
    echo "check_host_builds: $name ($cxx $flags) FAILED:" >&2
    grep -E "error|warning" "$tree.log" | head -20 >&2 || tail -20 "$tree.log" >&2
    return 1
  fi
  echo "check_host_builds: $name ($cxx $flags): built, no warning"
}

status=0
build gcc-x86-64-v4 "${CC:-gcc}" "${CXX:-g++}" "-O3 -DNDEBUG -march=x86-64-v4" || status=1
if command -v clang++ > /dev/null && command -v clang > /dev/null; then
  build clang-O3 clang clang++ "-O3 -DNDEBUG" || status=1
else
  echo "check_host_builds: clang-O3 skipped: clang++ is not installed"
fi
exit $status
