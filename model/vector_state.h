#pragma once
// The AVX–SSE transition penalty, and its cure.
//
// The project is compiled for the x86-64 baseline: its floating-point code is legacy (non-VEX)
// SSE. On a thread whose upper YMM register halves are "dirty" (AVX code ran and returned
// without vzeroupper), every such instruction waits on the upper halves; measured in the
// studio (2026-12-03, Xeon with AVX-512): the preview's 1920 x 1080 test target took 4.7 s on
// its worker thread against 0.47 s after one vzeroupper, and the physics of a fit in the
// studio twice its time in fovea-cli. QApplication's construction and later Qt calls on the
// GUI thread leave the state dirty (XGETBV(1) bit 2 set), and every thread started from it
// inherits the state. fovea-cli never creates a QApplication and is not affected.
//
// clearUpperVectorState() executes vzeroupper on the calling thread (nothing without AVX);
// the studio calls it at the start of every job that runs model code on its own thread, and
// clearUpperVectorStateOnTbbThreads() makes every TBB worker do it when it joins the scheduler.

namespace fovea {

void clearUpperVectorState();

// Installs, once per process, an observer that clears the state of each thread entering TBB's
// default arena. Call it before the first parallel algorithm.
void clearUpperVectorStateOnTbbThreads();

}  // namespace fovea
