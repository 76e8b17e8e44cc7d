// The allocator setting of the splinecal tool (splinecal/memory_reuse.h, set first thing in its
// main) for the test executable that includes this header: freed memory is kept for reuse, so a
// calibration's rounds fault their Jacobians' pages in once instead of once per solve.
//
// Why in the tests: the slow tests call the library in-process (gtest's own main), where glibc's
// defaults serve every Jacobian and factorisation above the mmap threshold fresh from the system
// and trim the heap, so a test paid page faults and the zeroing of fresh pages that the tool
// and the benchmarks do not (figures: docs/performance.md, "The slow tests' CPU time"). Only
// where freed memory goes changes, not what is computed.
//
// One setting per process, made while the executable's statics initialise (before gtest's main
// starts any thread); an inline variable, so any number of the executable's files may include it.
#ifndef SPLINECAL_TESTS_TESTING_TOOL_ALLOCATOR_H_
#define SPLINECAL_TESTS_TESTING_TOOL_ALLOCATOR_H_

#include "splinecal/memory_reuse.h"

namespace splinecal {
namespace testing {

inline const bool kToolAllocator = (KeepFreedMemoryForReuse(), true);

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_TOOL_ALLOCATOR_H_
