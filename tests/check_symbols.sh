#!/usr/bin/env bash
# check_symbols.sh LIB.a -- fail if the real-time library references the heap,
# the C++ exception runtime or the C++ standard library.
#
# Lists the undefined symbols of every object in the archive (nm -u) and
# rejects: malloc & friends, operator new/delete (all overloads), the
# exception/unwind runtime, RTTI, thread-safe-static guards and static
# destructor registration, and anything in namespace std.
# NM may name another nm (e.g. CMake's CMAKE_NM).
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
