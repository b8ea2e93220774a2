#include "core/memory/HeapPolicy.hpp"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace regolith::core {

void useReturningHeap() {
#if defined(__GLIBC__)
    // Setting either threshold explicitly also turns off glibc's dynamic adjustment of both.
    constexpr int kMmapThreshold = 256 * 1024;
    constexpr int kTrimThreshold = 1024 * 1024;
    (void)mallopt(M_MMAP_THRESHOLD, kMmapThreshold);
    (void)mallopt(M_TRIM_THRESHOLD, kTrimThreshold);
#endif
}

} // namespace regolith::core
