#pragma once
// Kogelnik's lossless closed forms (kogelnik.h) over arrays: the throughput path.
//
// Same formulas as kogelnik::losslessT, written branch-free over structure-of-arrays inputs so
// the compiler vectorises them (kogelnik_batch.cpp is built with -O3 -fno-math-errno
// -fno-trapping-math and cloned for AVX-512, AVX2 and baseline x86-64, picked at run time; GCC
// 12 vectorises the AVX-512 and AVX2 clones, the baseline lacks a vector rint). sin and sinh are
// evaluated with their own polynomial kernels (Cody-Waite reduction, minimax/Taylor
// polynomials); phases beyond the reduction's range (|u| > 1e6 rad, double; 1e4, float) are
// finished by the scalar path. Accuracy against the scalar double path
// (tests/model/tst_kogelnik_batch.cpp, docs/benchmarks.md):
//   double: |eta_batch - eta_scalar| <= 1e-15 over 2e5 random gratings of both branches;
//   float:  the error of float arithmetic itself (phase error ~ 1e-7 * phase): about 1e-6 on
//           the prototype's HOE, growing with nu and xi (thick films far off Bragg).

#include <cstddef>

namespace fovea::kogelnik {

// eta[i] = losslessT<T>(c_r[i], c_s[i], vartheta[i], kappa[i], d[i]).efficiency, for i < n.
void losslessBatch(const double* c_r, const double* c_s, const double* vartheta, const double* kappa, const double* d,
                   double* eta, std::size_t n);
// The same and zero_order[i] = losslessT<double>(...).zero_order (the power left in the probe,
// which the layers behind this one receive): |zero - zero_scalar| <= 1e-15 like eta.
void losslessBatch(const double* c_r, const double* c_s, const double* vartheta, const double* kappa, const double* d,
                   double* eta, double* zero_order, std::size_t n);
void losslessBatch(const float* c_r, const float* c_s, const float* vartheta, const float* kappa, const float* d,
                   float* eta, std::size_t n);

// The instruction set the dispatcher picked for this machine ("avx512f", "avx2" or "x86-64").
const char* batchInstructionSet();

}  // namespace fovea::kogelnik
