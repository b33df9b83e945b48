#!/usr/bin/env bash
# check_symbols.sh LIB.a -- fail if the real-time library references the heap,
# the C++ exception runtime or the C++ standard library, or exports anything
# but its public API.
#
# 1. Lists the undefined symbols of every object in the archive (nm -u) and
#    rejects: malloc & friends, operator new/delete (all overloads), the
#    exception/unwind runtime, RTTI, thread-safe-static guards and static
#    destructor registration, and anything in namespace std.
# 2. Every global symbol the archive defines starts with rtb_ (no name of
#    ours can clash with a host's).
# 3. The library is built with -fvisibility=hidden: the symbols with default
#    visibility (what a shared build would export) are exactly the RTB_API
#    functions declared in rt_bushing.h; the internal rtb_ functions the
#    offline half links statically are hidden.
# NM / READELF may name other tools (e.g. CMake's CMAKE_NM).
set -euo pipefail

if [ $# -ne 1 ]; then
  echo "usage: $0 path/to/librt_bushing.a" >&2
  exit 2
fi
lib=$1
nm_tool=${NM:-nm}
if [ ! -f "$lib" ]; then
  echo "check_symbols: no such file: $lib" >&2
  exit 2
fi

undef=$("$nm_tool" -u "$lib" | awk '$1 == "U" { print $2 }' | sed 's/@.*//' | sort -u)

forbidden='^(malloc|calloc|realloc|reallocarray|free|aligned_alloc|posix_memalign|memalign|valloc|pvalloc|strdup|strndup|alloca)$'
forbidden+='|^_Zn[wa]'                      # operator new / new[] (all overloads)
forbidden+='|^_Zd[la]'                      # operator delete / delete[]
forbidden+='|^__cxa_(throw|allocate_exception|free_exception|begin_catch|end_catch|rethrow|call_unexpected|bad_cast|bad_typeid|guard_acquire|guard_release|guard_abort|atexit)$'
forbidden+='|^__gxx_personality_'           # C++ exception personality
forbidden+='|^_Unwind_'                     # unwinder
forbidden+='|^_ZSt|^_ZNSt|^_ZNKSt'          # std:: functions and members
forbidden+='|^_ZT[IVS]'                    # typeinfo / vtables (RTTI; library is -fno-rtti)

bad=$(printf '%s\n' "$undef" | grep -E "$forbidden" || true)

if [ -n "$bad" ]; then
  echo "check_symbols: FAIL: $lib references forbidden symbols:"
  while IFS= read -r sym; do
    dem=$(printf '%s\n' "$sym" | c++filt 2>/dev/null || printf '%s\n' "$sym")
    if [ "$dem" != "$sym" ]; then echo "  $sym  ($dem)"; else echo "  $sym"; fi
  done <<< "$bad"
  echo "offending objects:"
  "$nm_tool" -u -A "$lib" | awk '$NF ~ /./ { print }' | grep -E "$(printf '%s\n' "$bad" | sed 's/[][\.*^$]/\\&/g' | paste -sd'|' -)" \
    | sed 's/^/  /' || true
  exit 1
fi

count=$(printf '%s\n' "$undef" | grep -c . || true)
echo "check_symbols: OK: $lib ($count undefined symbols, none forbidden)"

# ---- 2. defined global symbols carry the rtb_ prefix
header=${RTB_HEADER:-$(dirname "$0")/../rt_bushing/rt_bushing.h}
defined=$("$nm_tool" -g --defined-only "$lib" | awk 'NF >= 3 { print $3 }' | sort -u)
foreign=$(printf '%s\n' "$defined" | grep -v '^rtb_' | grep . || true)
if [ -n "$foreign" ]; then
  echo "check_symbols: FAIL: $lib defines global symbols without the rtb_ prefix:"
  printf '  %s\n' $foreign
  exit 1
fi

# ---- 3. default visibility = the RTB_API functions of the public header
readelf_tool=${READELF:-readelf}
exported=$("$readelf_tool" -sW "$lib" |
  awk '$5 == "GLOBAL" && $6 == "DEFAULT" && $7 != "UND" { print $8 }' | sort -u)
# declarations start a line with RTB_API and name the function on it
api=$(grep -E '^RTB_API ' "$header" | grep -oE '[A-Za-z_][A-Za-z0-9_]*[[:space:]]*\(' |
  sed -E 's/[[:space:]]*\($//' | grep '^rtb_' | sort -u)
if [ -z "$api" ]; then
  echo "check_symbols: FAIL: no RTB_API declarations found in $header" >&2
  exit 1
fi
if [ "$exported" != "$api" ]; then
  echo "check_symbols: FAIL: exported symbols differ from the RTB_API functions of $header"
  echo "  exported but not RTB_API:"; comm -23 <(printf '%s\n' "$exported") <(printf '%s\n' "$api") | sed 's/^/    /'
  echo "  RTB_API but not exported:"; comm -13 <(printf '%s\n' "$exported") <(printf '%s\n' "$api") | sed 's/^/    /'
  exit 1
fi
hidden=$(printf '%s\n' "$defined" | grep -c . || true)
echo "check_symbols: OK: $(printf '%s\n' "$api" | grep -c .) exported functions = RTB_API;" \
     "$((hidden - $(printf '%s\n' "$api" | grep -c .))) internal rtb_ symbols hidden"
