#pragma once
// Mesa's software rasterizer (llvmpipe: the OpenGL of a machine or VM without a GPU, and of
// Xvfb) starts one rasterizer thread per *online* CPU, whatever CPUs the process may run on.
// Pinned to fewer (taskset, a container's cpuset), its threads then take turns on the same
// cores with the GUI thread: measured on one core, the drag's input-to-drawn-rays latency was
// ~53 ms median with two rasterizer threads and ~46 ms with one (docs/benchmarks.md).

namespace fovea::viz {

// Before the first OpenGL context: when LP_NUM_THREADS is unset and the process may run on
// fewer CPUs than are online, sets LP_NUM_THREADS to the number it may run on. Returns the
// value set, or 0 when it left the environment alone (set by the user, or no restriction).
int matchSoftwareRasterizerToAffinity();

}  // namespace fovea::viz
