#pragma once
/// How the process's heap returns memory to the system. A DEM run allocates its big arrays
/// (particle storage, cell lists, Verlet lists, message buffers) in a few large blocks, some
/// of them only for the set-up; what matters is the peak resident memory (run summary's
/// peak_rss_bytes), so a freed large block must leave the process at once.

namespace regolith::core {

/// Fixes glibc malloc's thresholds: blocks of 256 KiB and more are always mapped on their
/// own (mmap) and unmapped when freed, and free memory at the top of the main heap above
/// 1 MiB is returned. Without this, glibc raises its mmap threshold dynamically (up to 32 MiB)
/// after the first large free, so later arrays of up to 32 MiB come from the main heap and
/// stay resident after they are freed: set-up temporaries then add to the peak of the run.
/// No-op on other C libraries. Call once, early, before large allocations. Not collective.
void useReturningHeap();

} // namespace regolith::core
