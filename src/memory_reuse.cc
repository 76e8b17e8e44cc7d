#include "splinecal/memory_reuse.h"

#ifdef __GLIBC__
#include <malloc.h>

#include <climits>
#endif

namespace splinecal {

void KeepFreedMemoryForReuse() {
#ifdef __GLIBC__
  mallopt(M_MMAP_MAX, 0);
  mallopt(M_TRIM_THRESHOLD, INT_MAX);
#endif
}

void ReturnFreedMemoryToSystem() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

}  // namespace splinecal
