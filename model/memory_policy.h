#pragma once
// Freed memory kept for reuse, and why.
//
// glibc returns every large block (above its mmap threshold, at most 32 MB by default) to the
// kernel when it is freed, and trims the heap's free top beyond its trim threshold. The next
// allocation of that size then takes a page fault for every 4 KiB page it touches. On the
// virtual machines the project runs on, a page fault is costly (a paravirtualised exception):
// measured 2026-12-05 on the 2-core CI-class VM, a 1920 x 1080 retinal image with a new gaze
// (BM_RetinaImage1080pNewGaze) took 1.27-1.60 s, of which page faults of its freshly allocated
// planes were 30-40 % of the samples (perf), and 0.28-0.35 s with freed memory kept.
//
// keepFreedMemoryForReuse() raises both thresholds (mallopt M_MMAP_THRESHOLD, M_TRIM_THRESHOLD,
// glibc <malloc.h>) so that large blocks come from the heap and stay mapped after free: the
// process keeps its high-water mark of memory instead of giving it back between renders. The
// executables (fovea-cli, fovea-studio, the benchmarks, the tests) and the Python module call
// it once at start; a library user who prefers a small resident set does not. It reports
// whether the C library took the setting (false elsewhere than glibc, and under ASan, whose
// allocator replaces glibc's and ignores mallopt).

namespace fovea {

// The thresholds set: blocks up to this size come from (and return to) the heap.
inline constexpr long kKeptBlockBytes = 1L << 30;  // 1 GiB

bool keepFreedMemoryForReuse();

}  // namespace fovea
