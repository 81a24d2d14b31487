// Numerical stability of the coupled-wave core and of the 3-D trace: a property-based
// suite over random gratings and random scenes with a fixed seed, including the extremes.
//
// Properties, for every sample:
//  - no NaN or Inf anywhere in the result;
//  - 0 <= eta <= 1, 0 <= zero order <= 1, eta + zero order <= 1 (= 1 when lossless);
//  - agreement with the same model evaluated in long double from the same double inputs:
//        |x_double - x_long_double| <= 1e-9 |x_long_double| + S,
//    where S is the spread of the long-double result itself when the inputs move by 16 ulps of
//    a double (three random directions; computed only for samples that fail without it). S is
//    the part of the error that no double algorithm can avoid (the problem's own conditioning,
//    e.g. sin of a 1e7 rad phase in a 1 mm film at grazing incidence); an unstable formula
//    shows up as an error far above it;
//    where 16-ulp moves shift the coupled-wave phase by more than a radian, eta is undetermined
//    by double inputs (in any precision) and only the bounds and its envelope (nu^2/(nu^2+xi^2),
//    transmission; nu^2/xi^2, reflection past the branch change) are checked;
//  - discrete outcomes (reflection vs transmission, evanescent, plate hit, dominant layer, in
//    the pupil) agree, unless 16-ulp input moves flip them in long double too (a boundary case).
// Continuity across the branch boundaries of the closed forms has its own sweeps below.
//
// Sample counts: 10^6 random gratings and 10^6 ray-layer evaluations of random scenes by
// default (the CI run); FOVEA_STABILITY_SAMPLES=N overrides the grating count (the scene count
// scales with it), and sanitizer builds default to 1/20 of it.
// TBB before Qt: Qt's `emit` macro breaks tbb/profiling.h.
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <QtTest>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <limits>
#include <mutex>
#include <numbers>
#include <string>
#include <vector>

#include "app/embedded_scene.h"
#include "model/physics/grating.h"
#include "model/physics/kogelnik.h"
#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"
#include "model/physics/trace_reference.h"
#include "model/scene/scene_io.h"

namespace tst_numerical_stability {

using namespace fovea;
using LD = long double;

namespace {

#if defined(__SANITIZE_ADDRESS__)
constexpr long kDefaultSamples = 50'000;
#else
constexpr long kDefaultSamples = 1'000'000;
#endif

long sampleCount() {
  if (const char* e = std::getenv("FOVEA_STABILITY_SAMPLES"); e && *e) return std::max(1L, std::atol(e));
  return kDefaultSamples;
}

// Counter-based generator: sample i has its own stream (order- and thread-independent).
struct Rng {
  std::uint64_t s;
  explicit Rng(std::uint64_t seed, std::uint64_t i) : s(seed ^ (i * 0x9e3779b97f4a7c15ULL)) { next(); }
  std::uint64_t next() {
    std::uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  double u() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double range(double a, double b) { return a + (b - a) * u(); }
  double logu(double a, double b) { return std::exp(range(std::log(a), std::log(b))); }
  double sign() { return (next() & 1) ? 1.0 : -1.0; }
  int pick(int n) { return static_cast<int>(next() % static_cast<std::uint64_t>(n)); }
};

// x moved by k ulps of a double in a random direction (relative 2^-52 k).
double nudge(double x, Rng& r, double k = 16.0) {
  return x * (1.0 + r.sign() * k * 0x1.0p-52 * r.u());
}

bool finite(double x) {
  return std::isfinite(x);
}

// ---- Planar gratings and Kogelnik-level cases ----------------------------------------------
enum Kind {
  kGeneral,
  kGrazing,
  kMillimetre,
  kStrong,
  kBranchChange,
  kEvanescent,
  kFarFromRecording,
  kAbsorbing,
  kKogelnikRaw,
  kThinWeak,
  kKinds
};
const char* kindName(int k) {
  static const char* names[] = {"general",    "grazing probe",    "1 mm film", "n1 0.05-0.1",  "branch change",
                                "evanescent", "far from record.", "absorbing", "raw Kogelnik", "thin/weak"};
  return names[k];
}

// A Kogelnik-level case (c_R, c_S, vartheta, kappa, alpha, d) in double.
struct RawCase {
  double c_r, c_s, vartheta, kappa, alpha, d;
};

struct Sample {
  int kind = kGeneral;
  bool raw = false;
  PlanarGrating planar;
  RawCase rawcase{};
};

PlanarGrating randomPlanar(Rng& r) {
  PlanarGrating g;
  g.film.n0 = r.range(1.0, 2.5);
  g.film.n1 = std::min(r.logu(1e-7, 0.1), 0.5 * g.film.n0);
  g.film.thickness_um = r.logu(1e-2, 1000.0);
  g.period_nm = r.logu(60.0, 20000.0);
  g.slant_deg = r.range(-180.0, 180.0);
  g.probe_deg = r.range(-89.99, 89.99);
  g.wavelength_nm = r.range(350.0, 1600.0);
  g.polarization = static_cast<Polarization>(r.pick(3));
  return g;
}

Sample makeSample(std::uint64_t seed, long i) {
  Rng r(seed, static_cast<std::uint64_t>(i));
  Sample s;
  s.kind = static_cast<int>(i % kKinds);
  s.planar = randomPlanar(r);
  PlanarGrating& g = s.planar;
  switch (s.kind) {
    case kGeneral:
      break;
    case kGrazing:
      g.probe_deg = r.sign() * (90.0 - r.logu(1e-9, 0.1));
      if (r.pick(2)) g.film.thickness_um = r.logu(10.0, 1000.0);
      break;
    case kMillimetre:
      g.film.thickness_um = r.pick(4) ? 1000.0 : r.range(300.0, 1000.0);
      break;
    case kStrong:
      g.film.n1 = r.range(0.05, 0.1);
      g.film.thickness_um = r.logu(1.0, 1000.0);
      break;
    case kBranchChange: {
      // Reflection (c_S < 0) with xi = nu (1 +- delta): the sinh -> sin switch of Eq. 56.
      s.raw = true;
      RawCase& c = s.rawcase;
      c.c_r = r.logu(1e-3, 1.0);
      c.c_s = -r.logu(1e-3, 1.5);
      c.kappa = r.logu(1e-5, 1.0);
      c.d = r.logu(0.1, 1000.0);
      c.alpha = r.pick(4) == 0 ? r.logu(1e-9, 1e-2) : 0.0;
      const double nu = c.kappa * c.d / std::sqrt(c.c_r * -c.c_s);
      const double xi = nu * (1.0 + r.sign() * (r.pick(8) == 0 ? 0.0 : r.logu(1e-16, 0.1)));
      c.vartheta = r.sign() * 2.0 * xi * -c.c_s / c.d;
      break;
    }
    case kEvanescent:
      g.period_nm = r.logu(40.0, 260.0);
      g.slant_deg = r.sign() * r.range(15.0, 165.0);
      break;
    case kFarFromRecording: {
      // Bragg-matched at a recording wavelength, probed far from it.
      const double lambda_rec = r.range(400.0, 700.0);
      const double phi = r.range(-180.0, 180.0), theta_b = r.range(-80.0, 80.0);
      const double c = std::abs(std::cos((phi - theta_b) * std::numbers::pi / 180.0));
      g.slant_deg = phi;
      g.probe_deg = theta_b;
      g.period_nm = lambda_rec / (2.0 * g.film.n0 * std::max(c, 1e-3));
      g.wavelength_nm = lambda_rec * r.logu(0.3, 3.0);
      break;
    }
    case kAbsorbing:
      g.film.alpha_per_um = r.logu(1e-8, 2.0);
      if (r.pick(3) == 0) g.film.thickness_um = r.logu(100.0, 1000.0);
      break;
    case kKogelnikRaw: {
      s.raw = true;
      RawCase& c = s.rawcase;
      c.c_r = r.logu(1e-9, 1.0);
      c.c_s = r.sign() * r.logu(1e-12, 3.0);
      c.vartheta = r.sign() * r.logu(1e-12, 20.0);
      c.kappa = r.logu(1e-10, 1.0);
      c.d = r.logu(1e-3, 1000.0);
      c.alpha = r.pick(3) == 0 ? r.logu(1e-9, 5.0) : 0.0;
      break;
    }
    case kThinWeak:
      g.film.thickness_um = r.logu(1e-4, 1.0);
      g.film.n1 = r.logu(1e-12, 1e-3);
      break;
  }
  return s;
}

struct Outcome {
  double eta = 0, zero = 0, nu = 0, xi = 0;
  bool reflection = false, evanescent = false;
};

template <class T>
Outcome evaluate(const Sample& s) {
  Outcome o;
  if (s.raw) {
    const RawCase& c = s.rawcase;
    const kogelnik::ResultT<T> k =
        kogelnik::evaluateT<T>(T(c.c_r), T(c.c_s), T(c.vartheta), T(c.kappa), T(c.alpha), T(c.d));
    o = {double(k.efficiency), double(k.zero_order), double(k.nu), double(k.xi), k.reflection, false};
    return o;
  }
  const PlanarDiffractionT<T> p = diffractPlanarT<T>(s.planar);
  const auto& k = p.grating.kogelnik;
  return {double(k.efficiency), double(k.zero_order), double(k.nu), double(k.xi), k.reflection, p.grating.evanescent};
}

Sample perturbed(const Sample& s, Rng& r) {
  Sample p = s;
  if (s.raw) {
    RawCase& c = p.rawcase;
    c.c_r = nudge(c.c_r, r);
    c.c_s = nudge(c.c_s, r);
    c.vartheta = nudge(c.vartheta, r);
    c.kappa = nudge(c.kappa, r);
    c.alpha = nudge(c.alpha, r);
    c.d = nudge(c.d, r);
  } else {
    PlanarGrating& g = p.planar;
    g.film.n0 = nudge(g.film.n0, r);
    g.film.n1 = nudge(g.film.n1, r);
    g.film.thickness_um = nudge(g.film.thickness_um, r);
    g.film.alpha_per_um = nudge(g.film.alpha_per_um, r);
    g.period_nm = nudge(g.period_nm, r);
    g.slant_deg = nudge(g.slant_deg, r);
    g.probe_deg = nudge(g.probe_deg, r);
    g.wavelength_nm = nudge(g.wavelength_nm, r);
  }
  return p;
}

// Input i (0-based over the sample's double inputs) moved by `ulps` ulps; false past the last.
bool nudgedInput(const Sample& s, int i, double ulps, Sample& out) {
  out = s;
  const double f = 1.0 + ulps * 0x1.0p-52;
  if (s.raw) {
    double* v[] = {&out.rawcase.c_r,   &out.rawcase.c_s,   &out.rawcase.vartheta,
                   &out.rawcase.kappa, &out.rawcase.alpha, &out.rawcase.d};
    if (i >= 6) return false;
    *v[i] *= f;
    return true;
  }
  PlanarGrating& g = out.planar;
  double* v[] = {&g.film.n0,   &g.film.n1,   &g.film.thickness_um, &g.film.alpha_per_um,
                 &g.period_nm, &g.slant_deg, &g.probe_deg,         &g.wavelength_nm};
  if (i >= 8) return false;
  *v[i] *= f;
  return true;
}

// Statistics of one suite, merged over threads.
struct Tally {
  long samples = 0, conditioned = 0, boundary_flips = 0, failures = 0, phase_indeterminate = 0;
  double max_rel_plain = 0;   // max |d - ld| / |ld| over the samples that passed without S
  double max_excess = 0;      // max |d - ld| / (1e-9 |ld| + S) over the conditioned ones (<= 1: passed)
  double max_spread_rel = 0;  // largest S / max(|ld|, 1e-300) seen (how ill-conditioned it gets)
  std::vector<std::string> messages;
  std::array<long, kKinds> per_kind{};
  void merge(const Tally& t) {
    samples += t.samples;
    conditioned += t.conditioned;
    boundary_flips += t.boundary_flips;
    phase_indeterminate += t.phase_indeterminate;
    failures += t.failures;
    max_rel_plain = std::max(max_rel_plain, t.max_rel_plain);
    max_excess = std::max(max_excess, t.max_excess);
    max_spread_rel = std::max(max_spread_rel, t.max_spread_rel);
    for (int k = 0; k < kKinds; ++k) per_kind[k] += t.per_kind[k];
    for (const auto& m : t.messages)
      if (messages.size() < 20) messages.push_back(m);
  }
  void fail(const std::string& m) {
    ++failures;
    if (messages.size() < 20) messages.push_back(m);
  }
};

std::string describe(const Sample& s) {
  char buf[512];
  if (s.raw) {
    const RawCase& c = s.rawcase;
    std::snprintf(buf, sizeof buf, "[%s] c_r %.17g c_s %.17g vartheta %.17g kappa %.17g alpha %.17g d %.17g",
                  kindName(s.kind), c.c_r, c.c_s, c.vartheta, c.kappa, c.alpha, c.d);
  } else {
    const PlanarGrating& g = s.planar;
    std::snprintf(buf, sizeof buf,
                  "[%s] n0 %.17g n1 %.17g d %.17g alpha %.17g period %.17g slant %.17g probe %.17g lambda %.17g pol %d",
                  kindName(s.kind), g.film.n0, g.film.n1, g.film.thickness_um, g.film.alpha_per_um, g.period_nm,
                  g.slant_deg, g.probe_deg, g.wavelength_nm, static_cast<int>(g.polarization));
  }
  return buf;
}

// Agreement of one quantity; `spread` computes S lazily (returns the spread of that quantity).
// Below this a difference is not a precision question (the subnormal range has fewer digits).
constexpr double kTiny = 1e-300;

template <class SpreadFn>
bool agrees(double d, double ld, SpreadFn spread, Tally& t, bool& used_spread, double& excess) {
  const double plain = std::abs(d - ld);
  if (plain <= 1e-9 * std::abs(ld) + kTiny) {
    if (std::abs(ld) > 1e-280) t.max_rel_plain = std::max(t.max_rel_plain, plain / std::abs(ld));
    return true;
  }
  used_spread = true;
  const double s = spread();
  t.max_spread_rel = std::max(t.max_spread_rel, s / std::max(std::abs(ld), 1e-300));
  const double bound = 1e-9 * std::abs(ld) + kTiny + s;
  excess = std::max(excess, bound > 0 ? plain / bound : std::numeric_limits<double>::infinity());
  return plain <= bound;
}

void checkSample(const Sample& s, std::uint64_t seed, long i, Tally& t) {
  ++t.samples;
  ++t.per_kind[s.kind];
  const Outcome d = evaluate<double>(s);
  // 1. finite
  if (!finite(d.eta) || !finite(d.zero) || !finite(d.nu) || !finite(d.xi)) {
    t.fail("non-finite " + describe(s));
    return;
  }
  // 2. bounds
  const bool lossless = s.raw ? s.rawcase.alpha == 0.0 : s.planar.film.alpha_per_um == 0.0;
  if (!(d.eta >= 0.0 && d.eta <= 1.0 && d.zero >= 0.0 && d.zero <= 1.0 && d.eta + d.zero <= 1.0 + 1e-12) ||
      (lossless && std::abs(d.eta + d.zero - 1.0) > 1e-12)) {
    t.fail("bounds: eta " + std::to_string(d.eta) + " zero " + std::to_string(d.zero) + " " + describe(s));
    return;
  }
  // 3. long double
  const Outcome ld = evaluate<LD>(s);
  // Long double at moved inputs, computed on demand: three random 16-ulp moves of every input,
  // and +-16 ulps of each input alone (their half-differences summed: the linearised effect).
  std::vector<Outcome> moved, plus, minus;
  const auto ensureMoved = [&] {
    if (!moved.empty()) return;
    Rng r(seed ^ 0xabcdefULL, static_cast<std::uint64_t>(i));
    for (int k = 0; k < 3; ++k) moved.push_back(evaluate<LD>(perturbed(s, r)));
    Sample m;
    for (int k = 0; nudgedInput(s, k, 16.0, m); ++k) {
      plus.push_back(evaluate<LD>(m));
      nudgedInput(s, k, -16.0, m);
      minus.push_back(evaluate<LD>(m));
    }
  };
  if (d.reflection != ld.reflection || d.evanescent != ld.evanescent) {
    ensureMoved();
    bool flips = false;
    for (const Outcome& m : moved) flips = flips || m.reflection != ld.reflection || m.evanescent != ld.evanescent;
    if (!flips) {
      t.fail("branch differs from long double " + describe(s));
      return;
    }
    ++t.boundary_flips;
    return;  // a boundary case: the two sides are different formulas by design
  }
  bool used = false;
  double excess = 0;
  const auto spreadOf = [&](double Outcome::*f) {
    return [&, f] {
      ensureMoved();
      double sp = 0, linear = 0;
      for (const Outcome& m : moved) sp = std::max(sp, std::abs(m.*f - ld.*f));
      for (std::size_t k = 0; k < plus.size(); ++k) linear += 0.5 * std::abs(plus[k].*f - minus[k].*f);
      return std::max(sp, linear);
    };
  };
  const char* bad = nullptr;
  if (!agrees(d.eta, ld.eta, spreadOf(&Outcome::eta), t, used, excess))
    bad = "eta";
  else if (!agrees(d.zero, ld.zero, spreadOf(&Outcome::zero), t, used, excess))
    bad = "zero order";
  else if (!agrees(d.nu, ld.nu, spreadOf(&Outcome::nu), t, used, excess))
    bad = "nu";
  else if (!agrees(d.xi, ld.xi, spreadOf(&Outcome::xi), t, used, excess))
    bad = "xi";
  if (used && !bad) {
    ++t.conditioned;
    t.max_excess = std::max(t.max_excess, excess);
  }
  if (bad && (std::string(bad) == "eta" || std::string(bad) == "zero order")) {
    // A phase known to worse than a radian (nu or xi move by more than 1 under 16-ulp input moves,
    // e.g. nu = 1e7 at a probe 1e-8 deg from grazing): eta is then any value under its envelope,
    // in double as in long double. Only the bounds and the envelope are properties there.
    ensureMoved();
    double phase = 0;
    for (std::size_t k = 0; k < plus.size(); ++k)
      phase += 0.5 * (std::abs(plus[k].nu - minus[k].nu) + std::abs(plus[k].xi - minus[k].xi));
    for (const Outcome& m : moved) phase = std::max(phase, std::abs(m.nu - ld.nu) + std::abs(m.xi - ld.xi));
    if (phase > 1.0) {
      const double nu2 = d.nu * d.nu, xi2 = d.xi * d.xi;
      const double envelope = d.reflection ? (d.xi > d.nu ? nu2 / xi2 : 1.0) : nu2 / (nu2 + xi2);
      if (!lossless || d.eta <= envelope * (1 + 1e-9) + 1e-300) {
        ++t.phase_indeterminate;
        bad = nullptr;
      }
    }
  }
  if (bad) {
    ensureMoved();
    char buf[400];
    std::snprintf(buf, sizeof buf,
                  "%s differs from long double: eta %.17g/%.17g zero %.17g/%.17g nu %.17g/%.17g xi %.17g/%.17g "
                  "(moved eta %.17g zero %.17g) ",
                  bad, d.eta, ld.eta, d.zero, ld.zero, d.nu, ld.nu, d.xi, ld.xi, moved[0].eta, moved[0].zero);
    t.fail(buf + describe(s));
  }
}

// ---- Random scenes ---------------------------------------------------------------------------
using fovea::embeddedDefaultScene;

Scene randomScene(Rng& r) {
  Scene s = embeddedDefaultScene();
  s.projector.pose.position_mm = {r.range(-60, 60), r.range(-30, 30), r.range(-70, -5)};
  {  // aimed at the plate centre, give or take 15 deg (most rays then meet the plate)
    const auto& pp = s.projector.pose.position_mm;
    const double vx = -pp[0], vy = -pp[1], vz = -pp[2], n = std::sqrt(vx * vx + vy * vy + vz * vz);
    s.projector.pose.rotation_deg = {std::atan2(vx, vz) * 180 / std::numbers::pi + r.range(-15, 15),
                                     std::asin(vy / n) * 180 / std::numbers::pi + r.range(-15, 15), r.range(-10, 10)};
  }
  s.projector.fov_deg = {r.range(5, 80), r.range(5, 60)};
  s.hoe.pose.position_mm = {r.range(-3, 3), r.range(-3, 3), r.range(-3, 3)};
  s.hoe.pose.rotation_deg = {r.range(-25, 25), r.range(-15, 15), r.range(-10, 10)};
  s.hoe.size_mm = {r.range(5, 80), r.range(5, 60)};
  s.hoe.cover_index = r.pick(3) ? 1.0 : r.range(1.0, 1.6);
  s.hoe.substrate_index = r.pick(3) ? 1.0 : r.range(1.0, 1.6);
  const int layers = 1 + r.pick(3);
  s.hoe_layers.resize(static_cast<std::size_t>(layers));
  for (int i = 0; i < layers; ++i) {
    HoeLayer& l = s.hoe_layers[static_cast<std::size_t>(i)];
    l.name = "L" + std::to_string(i);
    l.n0 = r.range(1.4, 1.7);
    l.n1 = r.pick(5) ? r.logu(1e-5, 0.05) : r.range(0.05, 0.1);
    l.thickness_um = r.pick(5) ? r.logu(1.0, 100.0) : r.range(300.0, 1000.0);
    l.offset_um = r.range(-50, 50);
    l.absorption_per_mm = r.pick(4) ? 0.0 : r.logu(1e-3, 50.0);
    l.shrinkage_percent = r.range(-3, 3);
    l.recording_n0_delta = r.range(-0.02, 0.02);
    l.recording.wavelength_nm = r.range(420, 680);
    l.recording.phase_conjugate = r.pick(2) == 0;
    const auto& pp = s.projector.pose.position_mm;
    l.recording.reference_point_mm = {pp[0] + r.range(-10, 10), pp[1] + r.range(-10, 10), pp[2] + r.range(-10, 10)};
    l.recording.signal_point_mm = r.pick(4) ? Vec3mm{r.range(-5, 5), r.range(-5, 5), r.range(-40, -10)}
                                            : Vec3mm{r.range(-30, 30), r.range(-30, 30), r.range(-200, 200)};
  }
  s.projector.wavelengths_nm.clear();
  const int nw = 1 + r.pick(3);
  for (int i = 0; i < nw; ++i)
    s.projector.wavelengths_nm.push_back(
        r.pick(3) ? s.hoe_layers[static_cast<std::size_t>(r.pick(layers))].recording.wavelength_nm
                  : r.range(380, 1000));
  s.eye.relief_mm = r.range(10, 40);
  s.eye.lateral_offset_mm = {r.range(-5, 5), r.range(-5, 5)};
  s.eye.gaze_deg = {r.range(-30, 30), r.range(-20, 20)};
  s.eye.pupil_diameter_mm = r.range(2, 8);
  return s;
}

// Every double a trace reads, moved by 16 ulps.
Scene perturbedScene(const Scene& s0, Rng& r) {
  Scene s = s0;
  auto n3 = [&](std::array<double, 3>& a) {
    for (double& x : a) x = nudge(x, r);
  };
  auto n2 = [&](std::array<double, 2>& a) {
    for (double& x : a) x = nudge(x, r);
  };
  n3(s.projector.pose.position_mm);
  n3(s.projector.pose.rotation_deg);
  n2(s.projector.fov_deg);
  for (double& w : s.projector.wavelengths_nm) w = nudge(w, r);
  n3(s.hoe.pose.position_mm);
  n3(s.hoe.pose.rotation_deg);
  n2(s.hoe.size_mm);
  s.hoe.cover_index = nudge(s.hoe.cover_index, r);
  s.hoe.substrate_index = nudge(s.hoe.substrate_index, r);
  for (HoeLayer& l : s.hoe_layers) {
    l.n0 = nudge(l.n0, r);
    l.n1 = nudge(l.n1, r);
    l.thickness_um = nudge(l.thickness_um, r);
    l.absorption_per_mm = nudge(l.absorption_per_mm, r);
    l.shrinkage_percent = nudge(l.shrinkage_percent, r);
    l.recording_n0_delta = nudge(l.recording_n0_delta, r);
    l.recording.wavelength_nm = nudge(l.recording.wavelength_nm, r);
    n3(l.recording.reference_point_mm);
    n3(l.recording.signal_point_mm);
  }
  s.eye.relief_mm = nudge(s.eye.relief_mm, r);
  s.eye.pupil_diameter_mm = nudge(s.eye.pupil_diameter_mm, r);
  s.eye.eyeball_diameter_mm = nudge(s.eye.eyeball_diameter_mm, r);
  n2(s.eye.lateral_offset_mm);
  n2(s.eye.gaze_deg);
  return s;
}

}  // namespace

class TestNumericalStability : public QObject {
  Q_OBJECT
 private slots:
  void randomGratings() {
    const long n = sampleCount();
    const std::uint64_t seed = 0x5eed2024ULL;
    std::mutex m;
    Tally total;
    tbb::parallel_for(tbb::blocked_range<long>(0, n, 4096), [&](const tbb::blocked_range<long>& range) {
      Tally t;
      for (long i = range.begin(); i != range.end(); ++i) checkSample(makeSample(seed, i), seed, i, t);
      std::lock_guard<std::mutex> lock(m);
      total.merge(t);
    });
    for (const auto& msg : total.messages) qWarning("%s", msg.c_str());
    qInfo("random gratings: %ld samples (%ld per kind), %ld failures", total.samples, total.per_kind[0],
          total.failures);
    qInfo("  max relative difference to long double where well conditioned: %.3g", total.max_rel_plain);
    qInfo("  %ld samples needed the conditioning allowance (max error / allowance %.3g; worst spread/value %.3g)",
          total.conditioned, total.max_excess, total.max_spread_rel);
    qInfo("  %ld samples on a reflection/evanescent boundary (flipped by 16-ulp input moves)", total.boundary_flips);
    qInfo("  %ld samples with a phase undetermined in double (16-ulp moves shift it > 1 rad): bounds and envelope only",
          total.phase_indeterminate);
    QCOMPARE(total.samples, n);
    QCOMPARE(total.failures, 0L);
  }

  void reflectionBranchChangeIsContinuous() {
    // Sweep xi through nu at fixed nu: eta is Lipschitz across the switch, at every scale of nu
    // (thin weak gratings to 1 mm films) and in the absorbing form at vanishing absorption.
    for (double nu : {1e-6, 1e-3, 0.3, 1.0, 3.0, 30.0, 600.0}) {
      const double c_r = 0.7, c_s = -0.9, d = 50.0;
      const double kappa = nu * std::sqrt(c_r * -c_s) / d;
      const auto eta = [&](double xi) {
        return kogelnik::lossless(c_r, c_s, 2.0 * xi * -c_s / d, kappa, d).efficiency;
      };
      const auto eta_ld = [&](LD xi) {
        return kogelnik::losslessT<LD>(c_r, c_s, 2.0L * xi * -c_s / d, kappa, d).efficiency;
      };
      const double at = eta(nu);
      QVERIFY(std::abs(at - nu * nu / (1 + nu * nu)) <= 1e-12 * at);
      const double slope = double(std::abs(eta_ld(nu * (1 + 1e-4L)) - eta_ld(nu * (1 - 1e-4L))) / (2e-4L * nu));
      for (double rel = 1e-16; rel < 2e-3; rel *= 3.7) {
        for (double sgn : {-1.0, 1.0}) {
          const double xi = nu * (1 + sgn * rel);
          const double jump = std::abs(eta(xi) - at);
          QVERIFY2(
              jump <= 4 * slope * std::abs(xi - nu) + 8e-16 * at,
              qPrintable(
                  QString("nu %1 rel %2: |eta - eta(nu)| %3, slope %4").arg(nu).arg(sgn * rel).arg(jump).arg(slope)));
          QVERIFY(std::abs(kogelnik::absorbing(c_r, c_s, 2.0 * xi * -c_s / d, kappa, 1e-300, d).efficiency - eta(xi)) <=
                  1e-12);
        }
      }
    }
  }

  void seriesSwitchesAreContinuous() {
    // shc: Taylor series below |u2| = 1e-4, closed form above.
    for (double sgn : {-1.0, 1.0}) {
      const double below = kogelnik::shc(sgn * std::nextafter(1e-4, 0.0)), above = kogelnik::shc(sgn * 1e-4);
      const double below_ld = double(kogelnik::shc<LD>(sgn * LD(std::nextafter(1e-4, 0.0))));
      QVERIFY(std::abs(below - below_ld) <= 2e-16);
      QVERIFY(std::abs(above - below) <= 4e-16);
    }
    // Absorbing solution: series in Q^2 below |Q^2| = 1e-6. Cross it with a weak lossy grating.
    for (bool reflection : {false, true}) {
      const double c_r = 0.8, c_s = reflection ? -0.6 : 0.6, alpha = 2e-4, kappa = 1e-3;
      double previous = -1;
      for (double d = 0.5; d < 1.5; d += 1e-3) {
        const auto k = kogelnik::absorbing(c_r, c_s, 0.0, kappa, alpha, d);
        const auto kl = kogelnik::absorbingT<LD>(c_r, c_s, 0.0, kappa, alpha, d);
        QVERIFY2(std::abs(k.efficiency - double(kl.efficiency)) <= 1e-13 * double(kl.efficiency),
                 qPrintable(QString("d %1: %2 vs %3").arg(d).arg(k.efficiency).arg(double(kl.efficiency))));
        QVERIFY(std::abs(k.zero_order - double(kl.zero_order)) <= 1e-14);
        if (previous >= 0) QVERIFY(k.efficiency > previous);  // monotone through the switch
        previous = k.efficiency;
      }
    }
    // alpha -> 0: the absorbing form tends to the lossless one.
    for (double alpha : {1e-3, 1e-6, 1e-9, 1e-12, 1e-200}) {
      const auto a = kogelnik::absorbing(0.9, -0.7, 0.004, 0.05, alpha, 30.0);
      const auto l = kogelnik::lossless(0.9, -0.7, 0.004, 0.05, 30.0);
      QVERIFY(std::abs(a.efficiency - l.efficiency) <= 5 * alpha * 30.0 / 0.7 + 1e-13);
    }
  }

  void grazingDiffractionTendsToZeroOnBothSides() {
    // c_S -> 0 with vartheta != 0: both closed forms vanish like |c_S| (transmission) and
    // |c_S|^(1/2)..|c_S| (reflection), so switching geometry and the 1e-12 grazing cut are
    // continuous to the level of eta at the cut.
    for (double vartheta : {1e-3, 0.05, 2.0}) {
      for (double kappa : {1e-3, 0.05, 0.5}) {
        for (double cs = 1e-2; cs > 1e-12; cs /= 10) {
          const double t = kogelnik::lossless(0.8, cs, vartheta, kappa, 40.0).efficiency;
          const double r = kogelnik::lossless(0.8, -cs, vartheta, kappa, 40.0).efficiency;
          // eta <= nu^2/xi^2 = 4 kappa^2 |c_S| / (c_R vartheta^2) on both sides.
          QVERIFY(t <= 4 * kappa * kappa * cs / (0.8 * vartheta * vartheta) * 1.0001 + 1e-300);
          QVERIFY(r <= 4 * kappa * kappa * cs / (0.8 * vartheta * vartheta) * 1.0001 + 1e-300);
        }
        QCOMPARE(kogelnik::lossless(0.8, 0.5e-12, vartheta, kappa, 40.0).efficiency, 0.0);
      }
    }
  }

  void randomScenes() {
    // Random benches (projector, plate pose and size, 1-3 layers with random recordings,
    // shrinkage, index change, absorption, 1 mm films, cover/substrate indices, eye): the
    // memoised pipeline equals the plain loop (bit for bit, efficiencies to 1e-12), and the double trace agrees with
    // the long-double one ray by ray and on the FOV.
    const long target = std::max(1L, sampleCount());  // ray-layer evaluations
    const std::uint64_t seed = 0x3d5ceeULL;
    std::mutex m;
    long evaluations = 0, rays_checked = 0, scenes = 0, conditioned = 0, flips = 0, failures = 0;
    double max_rel_plain = 0, max_fov_diff = 0;
    std::vector<std::string> messages;
    std::atomic<long> done{0};
    const long scene_count = std::max(1L, target / 150);
    tbb::parallel_for(tbb::blocked_range<long>(0, scene_count, 1), [&](const tbb::blocked_range<long>& range) {
      for (long i = range.begin(); i != range.end(); ++i) {
        Rng r(seed, static_cast<std::uint64_t>(i));
        const Scene s = randomScene(r);
        TraceOptions o;
        o.rays = 60 + r.pick(80);
        o.keep_rays = true;
        o.efficiency_threshold = r.pick(4) ? 0.1 : r.logu(1e-6, 0.5);
        o.polarization = static_cast<Polarization>(r.pick(3));
        if (r.pick(3) == 0) o.hoe_shift_mm = {r.range(-5, 5), r.range(-5, 5)};
        if (r.pick(3) == 0) o.source_shift_mm = r.range(-10, 10);
        const TraceResult piped = TracePipeline().run(s, o);
        const ReferenceTrace<double> dref = referenceTrace<double>(s, o);
        const ReferenceTrace<LD> lref = referenceTrace<LD>(s, o);
        std::vector<ReferenceTrace<LD>> moved;
        auto ensureMoved = [&] {
          if (!moved.empty()) return;
          Rng rr(seed ^ 0x77ULL, static_cast<std::uint64_t>(i));
          for (int k = 0; k < 3; ++k) moved.push_back(referenceTrace<LD>(perturbedScene(s, rr), o));
        };
        long ev = 0, checked = 0, cond = 0, fl = 0, fail = 0;
        double mrel = 0;
        std::vector<std::string> msg;
        auto failWith = [&](const std::string& t) {
          ++fail;
          if (msg.size() < 5) msg.push_back("scene " + std::to_string(i) + ": " + t);
        };
        // Pipeline == plain loop (double), bit for bit but for the efficiency: the pipeline solves
        // lossless films through the SIMD Kogelnik batch (kogelnik_batch.h, its own sin/sinh
        // kernels), within 1e-12 of the scalar closed forms the plain loop calls.
        if (piped.ray_list.size() != dref.rays.size()) failWith("ray count");
        for (std::size_t k = 0; k < dref.rays.size() && k < piped.ray_list.size(); ++k) {
          const TracedRay& a = piped.ray_list[k];
          const ReferenceRay<double>& b = dref.rays[k];
          if (a.hits_hoe != b.hits_hoe || !(std::abs(a.efficiency - b.efficiency) <= 1e-12) ||
              a.in_pupil != b.in_pupil ||
              (b.in_pupil && (a.field_deg != b.field_deg || a.out_direction != b.out_direction))) {
            char buf[300];
            std::snprintf(buf, sizeof buf,
                          "pipeline differs from the plain loop at ray %zu: hits %d/%d eff %.17g/%.17g pupil %d/%d "
                          "layer %d/%d exits %d/%d",
                          k, a.hits_hoe, b.hits_hoe, a.efficiency, b.efficiency, a.in_pupil, b.in_pupil, a.layer,
                          b.layer, a.exits, b.exits);
            failWith(buf);
          }
          if (!std::isfinite(a.efficiency) || a.efficiency < 0 || a.efficiency > 1 + 1e-12)
            failWith("efficiency " + std::to_string(a.efficiency));
          if (a.exits && (!a.out_direction.allFinite() || std::abs(a.out_direction.norm() - 1) > 1e-12))
            failWith("direction");
          if (a.in_pupil && !(std::isfinite(a.field_deg[0]) && std::isfinite(a.field_deg[1]))) failWith("field angle");
          if (a.hits_hoe) ev += static_cast<long>(s.hoe_layers.size());
        }
        if (piped.fov_deg.horizontal != double(dref.fov_deg[0]) || piped.fov_deg.vertical != double(dref.fov_deg[1]) ||
            piped.fov_deg.diagonal != double(dref.fov_deg[2]) || piped.rays_in_pupil != dref.rays_in_pupil)
          failWith("pipeline FOV differs from the plain loop");
        for (double f : {piped.fov_deg.horizontal, piped.fov_deg.vertical, piped.fov_deg.diagonal,
                         piped.mean_efficiency, piped.mean_efficiency_on_hoe})
          if (!std::isfinite(f) || f < 0) failWith("non-finite or negative summary");
        // double vs long double, ray by ray.
        for (std::size_t k = 0; k < dref.rays.size(); ++k) {
          const auto& a = dref.rays[k];
          const auto& b = lref.rays[k];
          ++checked;
          const bool discrete_same = a.hits_hoe == b.hits_hoe && a.exits == b.exits && a.in_pupil == b.in_pupil &&
                                     (a.layer == b.layer || a.efficiency == 0.0);
          if (!discrete_same) {
            ensureMoved();
            bool flipped = false;
            for (const auto& mv : moved) {
              const auto& c = mv.rays[k];
              flipped = flipped || c.hits_hoe != b.hits_hoe || c.exits != b.exits || c.in_pupil != b.in_pupil ||
                        c.layer != b.layer;
            }
            if (flipped) {
              ++fl;
            } else {
              failWith("discrete outcome differs from long double at ray " + std::to_string(k));
            }
            continue;
          }
          const double ld = double(b.efficiency), diff = std::abs(a.efficiency - ld);
          if (diff <= 1e-9 * std::abs(ld)) {
            if (ld != 0) mrel = std::max(mrel, diff / ld);
          } else {
            ensureMoved();
            double spread = 0;
            for (const auto& mv : moved) spread = std::max(spread, std::abs(double(mv.rays[k].efficiency) - ld));
            ++cond;
            if (!(diff <= 1e-9 * std::abs(ld) + spread)) {
              char buf[160];
              std::snprintf(buf, sizeof buf, "ray %zu: efficiency %.17g vs long double %.17g (spread %.3g)", k,
                            a.efficiency, ld, spread);
              failWith(buf);
            }
          }
        }
        // FOV: double vs long double.
        double fov_diff = 0;
        for (int c = 0; c < 3; ++c) {
          const double x = dref.fov_deg[c], y = double(lref.fov_deg[c]);
          const double diff = std::abs(x - y);
          if (diff <= 1e-9 * std::abs(y) + 1e-12) continue;
          ensureMoved();
          double spread = 0;
          for (const auto& mv : moved) spread = std::max(spread, std::abs(double(mv.fov_deg[c]) - y));
          if (!(diff <= 1e-9 * std::abs(y) + 1e-12 + spread)) {
            // A discrete flip of an extreme ray (counted above) moves the FOV by up to a ray spacing.
            if (fl == 0)
              failWith("FOV component " + std::to_string(c) + ": " + std::to_string(x) + " vs " + std::to_string(y));
          }
          fov_diff = std::max(fov_diff, diff);
        }
        std::lock_guard<std::mutex> lock(m);
        evaluations += ev;
        rays_checked += checked;
        ++scenes;
        conditioned += cond;
        flips += fl;
        failures += fail;
        max_rel_plain = std::max(max_rel_plain, mrel);
        max_fov_diff = std::max(max_fov_diff, fov_diff);
        for (auto& s2 : msg)
          if (messages.size() < 20) messages.push_back(s2);
        ++done;
      }
    });
    for (const auto& msg : messages) qWarning("%s", msg.c_str());
    qInfo("random scenes: %ld scenes, %ld rays, %ld ray-layer evaluations, %ld failures", scenes, rays_checked,
          evaluations, failures);
    qInfo("  max relative efficiency difference to long double where well conditioned: %.3g", max_rel_plain);
    qInfo("  %ld rays needed the conditioning allowance, %ld rays on a discrete boundary; max FOV difference %.3g deg",
          conditioned, flips, max_fov_diff);
    QCOMPARE(failures, 0L);
    QVERIFY(evaluations >= target / 3);
  }
};

QTEST_GUILESS_MAIN(TestNumericalStability)

}  // namespace tst_numerical_stability
#include "tst_numerical_stability.moc"
