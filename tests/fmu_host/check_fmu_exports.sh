#!/usr/bin/env bash
# check_fmu_exports.sh rt_bushing.so -- the FMU binary exports exactly the 44
# fmi2 functions of FMI 2.0 and nothing else, takes no memory from the C heap
# (all of it comes from the host's allocateMemory) and needs no C++ runtime.
set -euo pipefail
so=$1
defined=$(nm -D --defined-only "$so" | awk '{ print $3 }' | sort)
other=$(printf '%s\n' "$defined" | grep -v '^fmi2' || true)
count=$(printf '%s\n' "$defined" | grep -c '^fmi2' || true)
undef=$(nm -D --undefined-only "$so" | awk '{ print $2 }' | sed 's/@.*//')
heap=$(printf '%s\n' "$undef" | grep -E '^(malloc|calloc|realloc|free|posix_memalign|aligned_alloc|_Znw|_Zna)' || true)
needed=$(readelf -d "$so" | grep NEEDED | grep -E 'libstdc\+\+|libgcc_s' || true)
fail=0
if [ -n "$other" ]; then echo "check_fmu_exports: FAIL: non-fmi2 exports:"; echo "$other"; fail=1; fi
if [ "$count" -ne 44 ]; then echo "check_fmu_exports: FAIL: $count fmi2 exports, FMI 2.0 has 44"; fail=1; fi
if [ -n "$heap" ]; then echo "check_fmu_exports: FAIL: heap functions used:"; echo "$heap"; fail=1; fi
if [ -n "$needed" ]; then echo "check_fmu_exports: FAIL: $needed"; fail=1; fi
[ "$fail" -eq 0 ] && echo "check_fmu_exports: OK: $so exports the 44 fmi2 functions only"
exit "$fail"
