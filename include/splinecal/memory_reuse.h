// Freed memory kept for reuse: a process-wide allocator setting for programs that own their
// process (the splinecal tool, the benchmarks), never set by the library on its own.
//
// Why: a calibration allocates and frees hundreds of megabytes per solver round (Jacobians,
// normal equations, factorisations). glibc's malloc serves blocks above 128 KB to 32 MB by mmap
// and returns them to the system when freed, and trims its heap, so every round faults the same
// memory in again. A page fault costs about 10 us per 4 KB page on the 2-core VMs the targets are
// measured on (0.69 s to touch 256 MB, docs/performance.md "Calibrate at Kalibr's knot density in
// under 20 s"), a few seconds of a calibration; with the memory kept, the heap's pages are faulted
// once. Peak memory stays what the program holds at once (freed blocks are reused), plus
// fragmentation.
#ifndef SPLINECAL_MEMORY_REUSE_H_
#define SPLINECAL_MEMORY_REUSE_H_

namespace splinecal {

// Serve every allocation from the heap and never shrink it (glibc mallopt: M_MMAP_MAX 0,
// M_TRIM_THRESHOLD at its maximum); malloc_trim still returns memory when called. Call once,
// first thing in main, before any thread starts. A no-op without glibc.
void KeepFreedMemoryForReuse();

// Returns the heap's free pages to the system now (glibc malloc_trim), where a program is about
// to reach its peak memory with less already freed. A no-op without glibc.
void ReturnFreedMemoryToSystem();

}  // namespace splinecal

#endif  // SPLINECAL_MEMORY_REUSE_H_
