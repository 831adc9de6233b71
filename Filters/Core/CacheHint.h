// MeshLOD core: a hint to the processor to bring a memory line into its caches.
//
// The collapse loops read a few dozen scattered memory lines per collapse, each address known
// only from the one read before; hinting the next candidate's lines ahead of time lets those
// reads overlap with the current collapse's work (see CollapseMesh::Prefetch).
#ifndef meshlod_CacheHint_h
#define meshlod_CacheHint_h

#if defined(_MSC_VER) && !defined(__clang__) && (defined(_M_X64) || defined(_M_IX86))
#define MESHLOD_CACHE_HINT_SSE
#include <xmmintrin.h>
#endif

namespace meshlod
{
/// Start loading the line holding *p into the caches; no effect on the program's results (p
/// need not be dereferenceable). Compilers without such a hint get a no-op.
inline void CacheHint(const void* p)
{
#if defined(__GNUC__) || defined(__clang__)
  __builtin_prefetch(p);
#elif defined(MESHLOD_CACHE_HINT_SSE)
  _mm_prefetch(static_cast<const char*>(p), _MM_HINT_T0);
#else
  (void)p;
#endif
}
} // namespace meshlod

#endif
