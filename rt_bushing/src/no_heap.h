/* no_heap.h -- compile-time guard against dynamic memory in the real-time
 * library. Include it LAST in every library source (rt_bushing/src/NAME.cpp), after all system
 * and project headers: from that point on any use of the identifiers below is
 * a hard compile error. (Macros from headers included earlier that expand to
 * them are exempt, as GCC documents for #pragma GCC poison, so system headers
 * are unaffected.) operator new/delete cannot be poisoned here because they
 * are keywords; tests/check_symbols.sh catches them at link level instead,
 * together with the C++ exception runtime.
 */
#ifndef RTB_NO_HEAP_H
#define RTB_NO_HEAP_H

#if defined(__GNUC__)
/* C heap */
#pragma GCC poison malloc calloc realloc free reallocarray
#pragma GCC poison aligned_alloc posix_memalign memalign valloc pvalloc
/* functions that return heap memory */
#pragma GCC poison strdup strndup
/* unbounded stack allocation: glibc's <stdlib.h> defines alloca as a macro
 * for __builtin_alloca, so drop the macro and poison both names. */
#ifdef alloca
#undef alloca
#endif
#pragma GCC poison alloca __builtin_alloca
#endif

#endif /* RTB_NO_HEAP_H */
