// RCWA cost (orders, slices, thick films) and the Kogelnik-vs-RCWA error map
// (docs/benchmarks.md, "Run time against error"). Set FOVEA_BENCH_OUT=<dir> to also write the map as
// <dir>/kogelnik_vs_rcwa.md (the tables of docs/benchmarks.md).
#include <benchmark/benchmark.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "model/rigorous/kogelnik_vs_rcwa.h"
#include "model/rigorous/rcwa.h"
#include "tests/model/rcwa_cases.h"

using namespace fovea::rigorous;
using fovea::testing::strongSlanted;  // the case tests/model/tst_rcwa.cpp checks

// Cost against retained orders N (2N+1 harmonics: one (2N+1)² eigenproblem + log2 M star products).
static void BM_RcwaOrders(benchmark::State& state) {
  const RcwaProblem p = strongSlanted(state.range(1) ? RcwaPolarization::TM : RcwaPolarization::TE);
  const int n = int(state.range(0));
  double eta = 0;
  for (auto _ : state) benchmark::DoNotOptimize(eta = solveRcwa(p, {n, 256, false}).efficiency(1, false));
  state.counters["eta_plus1_T"] = eta;
}
BENCHMARK(BM_RcwaOrders)->ArgsProduct({{2, 5, 10, 20, 40}, {0, 1}})->Unit(benchmark::kMicrosecond);

// Cost against slices M: O(log M) thanks to the D-conjugation doubling.
static void BM_RcwaSlices(benchmark::State& state) {
  const RcwaProblem p = strongSlanted(RcwaPolarization::TE);
  const int m = int(state.range(0));
  double eta = 0;
  for (auto _ : state) benchmark::DoNotOptimize(eta = solveRcwa(p, {8, m, false}).efficiency(1, false));
  state.counters["eta_plus1_T"] = eta;
}
BENCHMARK(BM_RcwaSlices)->RangeMultiplier(8)->Range(8, 1 << 17)->Unit(benchmark::kMicrosecond);

// The same with every slice decomposed separately (what the doubling saves).
static void BM_RcwaSlicesExplicit(benchmark::State& state) {
  const RcwaProblem p = strongSlanted(RcwaPolarization::TE);
  const int m = int(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(solveRcwa(p, {8, m, true}).total_efficiency);
}
BENCHMARK(BM_RcwaSlicesExplicit)->RangeMultiplier(8)->Range(8, 512)->Unit(benchmark::kMicrosecond);

// A 1 mm slanted film, converged to 1e-4 on the diffracted order.
static void BM_RcwaConverged1mm(benchmark::State& state) {
  RcwaProblem p = strongSlanted(RcwaPolarization::TE);
  p.thickness_um = 1000.0;
  p.n1 = 0.001;
  RcwaConvergence c;
  c.min_slices = 1 << 14;
  RcwaConvergedResult r;
  for (auto _ : state) benchmark::DoNotOptimize((r = solveRcwaConverged(p, c)).result.total_efficiency);
  state.counters["orders"] = r.orders;
  state.counters["slices"] = r.slices;
  state.counters["total_minus_1"] = r.result.total_efficiency - 1.0;
}
BENCHMARK(BM_RcwaConverged1mm)->Unit(benchmark::kMillisecond);

static void BM_KogelnikClosedForm(benchmark::State& state) {
  PlanarCase c;
  c.n1 = 0.01;
  c.thickness_um = 20;
  c.period_nm = 520;
  c.probe_deg = 20;
  double s = 0;
  for (auto _ : state) {
    c.probe_deg += 1e-9;
    benchmark::DoNotOptimize(s += kogelnikClosedForm(c).efficiency);
  }
}
BENCHMARK(BM_KogelnikClosedForm);

// The whole map (geometries × d × n1 × ξ), once: counters give the worst error per ρ regime.
static void BM_KogelnikVsRcwaMap(benchmark::State& state) {
  const KogelnikRcwaGrid grid = state.range(0) ? KogelnikRcwaGrid{} : KogelnikRcwaGrid::quick();
  std::vector<KogelnikRcwaPoint> pts;
  for (auto _ : state) pts = kogelnikVsRcwa(grid);
  for (const RhoBinSummary& s : summariseByRho(pts)) {
    const std::string tag = "rho_" + std::to_string(int(s.rho_min)) + "+";
    state.counters["max_err_" + tag] = s.max_error;
    state.counters["points_" + tag] = s.points;
  }
  state.counters["points"] = double(pts.size());
  int unconverged = 0;
  for (const auto& p : pts) unconverged += p.rcwa_converged ? 0 : 1;
  state.counters["rcwa_unconverged"] = unconverged;
  if (const char* dir = std::getenv("FOVEA_BENCH_OUT"); dir && state.range(0)) {
    std::ofstream(std::string(dir) + "/kogelnik_vs_rcwa.md") << kogelnikVsRcwaMarkdown(pts);
  }
}
BENCHMARK(BM_KogelnikVsRcwaMap)->Arg(0)->Arg(1)->Iterations(1)->Unit(benchmark::kMillisecond);
