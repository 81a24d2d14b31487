// fovea-cli bench [--quick] --json: run time against error. Throughput of the Kogelnik kernel
// (scalar, SIMD double, SIMD float) on one core and on all cores, the gaze update and cold
// trace of the default scene at 20 000 rays, a 41-gaze x_p sweep on two cores and on one
// (scaling), ray count vs FOV error, float/double/long double on efficiency and FOV, and
// Kogelnik vs RCWA. scripts/benchmark_tables.py turns the JSON into docs/benchmarks.md tables.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <ctime>
#include <iostream>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <variant>
#include <vector>

#include <tbb/global_control.h>

#include "app/cli/cli_common.h"
#include "app/embedded_scene.h"
#include "model/analysis/gaze_studies.h"
#include "model/analysis/tolerance_analysis.h"
#include "model/analysis/tolerance_run.h"
#include "model/analysis/tolerance_spec.h"
#include "model/analysis/trace_evaluator.h"
#include "model/io/json_input.h"
#include "model/physics/hoe_recording.h"
#include "model/physics/kogelnik.h"
#include "model/physics/kogelnik_batch.h"
#include "model/physics/trace.h"
#include "model/physics/trace_pipeline.h"
#include "model/physics/trace_reference.h"
#include "model/rigorous/kogelnik_vs_rcwa.h"
#include "model/scene/scene_io.h"

namespace fovea::cli {
namespace cmd_bench {  // one per command file: fovea-cli compiles in unity batches
namespace {

using Clock = std::chrono::steady_clock;

// Best of `repeats` batches of at least `min_s` seconds: seconds per call of f.
template <class F>
double secondsPerCall(F&& f, double min_s, int repeats = 3) {
  double best = 1e300;
  for (int r = 0; r < repeats; ++r) {
    long calls = 0;
    const auto t0 = Clock::now();
    double el = 0;
    do {
      f();
      ++calls;
      el = std::chrono::duration<double>(Clock::now() - t0).count();
    } while (el < min_s);
    best = std::min(best, el / calls);
  }
  return best;
}

struct KogelnikInputs {
  std::vector<double> c_r, c_s, vt, kappa, d;
  std::vector<float> fc_r, fc_s, fvt, fkappa, fd;
};

// The prototype's coupled-wave inputs: every ray-layer pair of the default scene (the
// pipeline's coupled-wave stage sees exactly these).
KogelnikInputs prototypeInputs(const Scene& s) {
  KogelnikInputs in;
  TraceOptions o;
  o.rays = 6667;
  o.keep_rays = true;
  const TraceResult r = traceScene(s, o);
  const Frame f = frameOf(s.hoe.pose);
  for (const TracedRay& ray : r.ray_list) {
    if (!ray.hits_hoe) continue;
    const Eigen::Vector3d local = f.toLocal(ray.hoe_point);
    for (const HoeLayer& l : s.hoe_layers) {
      const LayerModel m = makeLayerModel(s.hoe, l);
      const RecordedGrating g = recordAt(m, local.x(), local.y());
      if (!g.valid) continue;
      const double lambda_um = ray.wavelength_nm * 1e-3;
      const LayerGeometryT<double> lg =
          layerGeometryT<double>(m.film, g.k_recorded, f.axes.transpose() * ray.projector_direction, s.hoe.cover_index,
                                 s.hoe.cover_index, s.hoe.substrate_index, lambda_um);
      if (!lg.entered) continue;
      in.c_r.push_back(lg.geometry.c_r);
      in.c_s.push_back(lg.geometry.c_s);
      in.vt.push_back(lg.geometry.vartheta);
      in.kappa.push_back(std::numbers::pi * m.film.n1 / lambda_um);
      in.d.push_back(m.film.thickness_um);
    }
  }
  for (std::size_t i = 0; i < in.c_r.size(); ++i) {
    in.fc_r.push_back(float(in.c_r[i]));
    in.fc_s.push_back(float(in.c_s[i]));
    in.fvt.push_back(float(in.vt[i]));
    in.fkappa.push_back(float(in.kappa[i]));
    in.fd.push_back(float(in.d[i]));
  }
  return in;
}

nlohmann::json throughput(const Scene& scene, bool quick) {
  const double min_s = quick ? 0.05 : 0.3;
  const KogelnikInputs in = prototypeInputs(scene);
  const std::size_t n = in.c_r.size();
  std::vector<double> eta(n), ref(n);
  std::vector<float> feta(n);
  nlohmann::json j;
  j["kogelnik_inputs"] = n;
  j["simd"] = kogelnik::batchInstructionSet();
  for (std::size_t i = 0; i < n; ++i)
    ref[i] = kogelnik::lossless(in.c_r[i], in.c_s[i], in.vt[i], in.kappa[i], in.d[i]).efficiency;
  double max_err_d = 0, max_err_f = 0;
  {
    tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
    volatile double sink = 0;
    const double scalar = secondsPerCall(
        [&] {
          double acc = 0;
          for (std::size_t i = 0; i < n; ++i)
            acc += kogelnik::lossless(in.c_r[i], in.c_s[i], in.vt[i], in.kappa[i], in.d[i]).efficiency;
          sink = acc;
        },
        min_s);
    const double batch = secondsPerCall(
        [&] {
          kogelnik::losslessBatch(in.c_r.data(), in.c_s.data(), in.vt.data(), in.kappa.data(), in.d.data(), eta.data(),
                                  n);
        },
        min_s);
    const double fbatch = secondsPerCall(
        [&] {
          kogelnik::losslessBatch(in.fc_r.data(), in.fc_s.data(), in.fvt.data(), in.fkappa.data(), in.fd.data(),
                                  feta.data(), n);
        },
        min_s);
    for (std::size_t i = 0; i < n; ++i) {
      max_err_d = std::max(max_err_d, std::abs(eta[i] - ref[i]));
      max_err_f = std::max(max_err_f, std::abs(double(feta[i]) - ref[i]));
    }
    j["kogelnik_scalar_double_evals_per_s_1core"] = n / scalar;
    j["kogelnik_simd_double_evals_per_s_1core"] = n / batch;
    j["kogelnik_simd_float_evals_per_s_1core"] = n / fbatch;
    j["kogelnik_evals_per_s_1core"] = n / batch;  // the studio's path: SIMD double (float gains below)
    j["simd_double_max_abs_error"] = max_err_d;
    j["simd_float_max_abs_error"] = max_err_f;
    (void)sink;

    // Gaze update of the default scene at 20 000 rays (6 667 per wavelength), memoised.
    const Scene& s = scene;
    TraceOptions o;
    o.rays = 6667;
    TracePipeline p;
    p.run(s, o);
    double yaw = 0;
    j["gaze_update_ms_20k_1core"] = 1e3 * secondsPerCall(
                                              [&] {
                                                yaw = yaw > 10 ? -10 : yaw + 0.5;
                                                o.gaze_deg = std::array<double, 2>{yaw, 0.0};
                                                p.run(s, o);
                                              },
                                              min_s);
    // Gaze update with the HOE following the gaze (x_p): a new plate position each time, so
    // everything after the projector grid reruns (culled to the pupil, as the studies do).
    TraceOptions c = o;
    c.cull_to_pupil = true;
    TracePipeline pc;
    j["gaze_and_hoe_shift_update_ms_20k_1core"] = 1e3 * secondsPerCall(
                                                            [&] {
                                                              yaw = yaw > 10 ? -10 : yaw + 0.5;
                                                              c.gaze_deg = std::array<double, 2>{yaw, 0.0};
                                                              c.hoe_shift_mm = {0.17 * yaw, 0.0};
                                                              pc.run(s, c);
                                                            },
                                                            min_s);
    j["trace_cold_ms_20k_1core"] = 1e3 * secondsPerCall([&] { TracePipeline().run(s, o); }, min_s);
    TraceStats st;
    TracePipeline().run(s, o, &st);
    j["ray_layer_evaluations_20k"] = st.evaluations;
    // The same gaze update at the ray count that holds the FOV to 0.1 deg (64 000 per
    // wavelength, "Ray count vs FOV error"), without and with the per-ray list the studio draws.
    for (const bool keep : {false, true}) {
      TraceOptions w;
      w.rays = 64000;
      w.keep_rays = keep;
      TracePipeline pw;
      pw.run(s, w);
      j[keep ? "gaze_update_keep_rays_ms_64k_per_wavelength_1core" : "gaze_update_ms_64k_per_wavelength_1core"] =
          1e3 * secondsPerCall(
                    [&] {
                      yaw = yaw > 10 ? -10 : yaw + 0.5;
                      w.gaze_deg = std::array<double, 2>{yaw, 0.0};
                      pw.run(s, w);
                    },
                    min_s);
    }
  }
  {
    volatile double sink = 0;
    constexpr int kReps = 64;
    const int threads = int(std::max(1u, std::thread::hardware_concurrency()));
    const std::size_t chunk = (n + threads - 1) / threads;
    const double all = secondsPerCall(
        [&] {
          std::vector<std::thread> pool;
          for (int t = 0; t < threads; ++t)
            pool.emplace_back([&, t] {
              const std::size_t b = t * chunk, e = std::min(n, b + chunk);
              for (int rep = 0; rep < kReps && b < e; ++rep)  // amortise the thread start
                kogelnik::losslessBatch(in.c_r.data() + b, in.c_s.data() + b, in.vt.data() + b, in.kappa.data() + b,
                                        in.d.data() + b, eta.data() + b, e - b);
            });
          for (auto& th : pool) th.join();
          sink = eta[0];
        },
        min_s);
    (void)sink;
    j["kogelnik_evals_per_s_all_cores"] = double(kReps) * n / all;
    j["cores"] = threads;
  }
  {
    // 41-gaze x_p sweep (-20..20 deg by 1 deg, HOE shift optimised per gaze) on two cores, and
    // on one core for the scaling. Default evaluator (the CLI's and studio's ray count), then
    // the 1 500 rays/λ of the first measurement (the evaluator's earlier default) for
    // comparison. Fastest of `repeats`; the process CPU time is the steadier figure on a
    // loaded machine.
    const double step = quick ? 4.0 : 1.0;
    struct Run {
      int threads, rays;
    };
    for (const Run run : {Run{2, TraceEvaluatorOptions{}.rays}, Run{1, TraceEvaluatorOptions{}.rays}, Run{2, 1500}}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(run.threads));
      TraceEvaluatorOptions eo;
      eo.rays = run.rays;
      std::atomic<long long> traces{0};
      const FovEvaluator traced = traceEvaluator(eo);
      const FovEvaluator eval = [&](const Scene& sc, const FovQuery& q) {
        ++traces;
        return traced(sc, q);
      };
      double secs = 1e300, cpu = 1e300;
      std::size_t gazes = 0;
      for (int rep = 0; rep < (quick ? 1 : 2); ++rep) {
        traces = 0;
        const auto t0 = Clock::now();
        const std::clock_t c0 = std::clock();
        const auto r = sweepGaze(scene, eval, -20, 20, step, GazeAxis::Yaw, ShiftMethod::Hoe);
        cpu = std::min(cpu, double(std::clock() - c0) / CLOCKS_PER_SEC);
        secs = std::min(secs, std::chrono::duration<double>(Clock::now() - t0).count());
        gazes = r.ok() ? r.value->samples.size() : 0;
      }
      const std::string sweep = quick ? "sweep_s_" : "sweep_41_gaze_s_";
      if (run.rays != TraceEvaluatorOptions{}.rays) {
        j[sweep + "2cores_1500_rays"] = secs;
      } else if (run.threads == 2) {
        j["sweep_gazes"] = gazes;
        j["sweep_rays_per_wavelength"] = eo.rays;
        j["sweep_traces"] = traces.load();  // x_p bracket, edge bisections and eye-box borders
        j[sweep + "2cores"] = secs;
        j[sweep + "cpu_2cores"] = cpu;
      } else {
        j[sweep + "1core"] = secs;
        j[sweep + "cpu_1core"] = cpu;
      }
    }
    const std::string sweep = quick ? "sweep_s_" : "sweep_41_gaze_s_";
    j["sweep_speedup_2cores"] = j[sweep + "1core"].get<double>() / j[sweep + "2cores"].get<double>();
  }
  return j;
}

nlohmann::json raysVsFov(const Scene& s, bool quick) {
  // Horizontal FOV at zero gaze against ray density, one wavelength (532 nm; all three behave
  // alike: every layer is recorded in place). The plate subtends exactly 2 atan(22/22) = 90 deg.
  nlohmann::json rows = nlohmann::json::array();
  std::vector<int> counts{250, 500, 1000, 2000, 4000, 8000, 16000, 32000, 64000, 128000, 256000, 512000};
  if (quick) counts = {250, 1000, 4000, 16000, 64000};
  const double truth = 90.0;
  int least = -1;
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  for (int n : counts) {
    TraceOptions o;
    o.rays = n;
    o.wavelength_nm = 532.0;
    o.gaze_deg = std::array<double, 2>{0.0, 0.0};
    TraceResult r;
    const double ms = 1e3 * secondsPerCall([&] { r = traceScene(s, o); }, 0.0, 1);
    const double err = truth - r.fov_deg.horizontal;
    rows.push_back({{"rays_per_wavelength", n},
                    {"fov_h_deg", r.fov_deg.horizontal},
                    {"fov_v_deg", r.fov_deg.vertical},
                    {"error_deg", err},
                    {"trace_ms_1core", ms}});
    if (least < 0 && std::abs(err) <= 0.1) least = n;
  }
  return {{"rows", rows},
          {"reference_deg", truth},
          {"least_rays_for_0_1_deg", least >= 0 ? nlohmann::json(least) : nlohmann::json()}};
}

nlohmann::json precision(const Scene& s, bool quick) {
  TraceOptions o;
  o.rays = quick ? 1000 : 4000;
  o.gaze_deg = std::array<double, 2>{0.0, 0.0};
  const auto f = referenceTrace<float>(s, o);
  const auto d = referenceTrace<double>(s, o);
  const auto l = referenceTrace<long double>(s, o);
  nlohmann::json j;
  auto row = [&](const auto& t, const char* name) {
    double max_eff = 0, sum_eff = 0;
    int n = 0, flips = 0;
    for (std::size_t i = 0; i < t.rays.size(); ++i) {
      if (t.rays[i].in_pupil != l.rays[i].in_pupil) ++flips;
      if (!l.rays[i].hits_hoe) continue;
      const double e = std::abs(double(t.rays[i].efficiency) - double(l.rays[i].efficiency));
      max_eff = std::max(max_eff, e);
      sum_eff += e;
      ++n;
    }
    j[name] = {{"max_efficiency_error", max_eff},
               {"mean_efficiency_error", n ? sum_eff / n : 0.0},
               {"pupil_decisions_differing", flips},
               {"fov_h_error_deg", std::abs(double(t.fov_deg[0]) - double(l.fov_deg[0]))},
               {"fov_v_error_deg", std::abs(double(t.fov_deg[1]) - double(l.fov_deg[1]))},
               {"fov_h_deg", double(t.fov_deg[0])}};
  };
  row(f, "float");
  row(d, "double");
  row(l, "long_double");
  const double tf = secondsPerCall([&] { referenceTrace<float>(s, o); }, 0.0, 1);
  const double td = secondsPerCall([&] { referenceTrace<double>(s, o); }, 0.0, 1);
  const double tl = secondsPerCall([&] { referenceTrace<long double>(s, o); }, 0.0, 1);
  j["float"]["trace_ms"] = 1e3 * tf;
  j["double"]["trace_ms"] = 1e3 * td;
  j["long_double"]["trace_ms"] = 1e3 * tl;
  j["rays_per_wavelength"] = o.rays;
  return j;
}

nlohmann::json kogelnikVsRcwaJson(bool quick) {
  const auto grid = quick ? rigorous::KogelnikRcwaGrid::quick() : rigorous::KogelnikRcwaGrid{};
  const auto points = rigorous::kogelnikVsRcwa(grid);
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& b : rigorous::summariseByRho(points))
    rows.push_back({{"rho_min", b.rho_min},
                    {"rho_max", std::isfinite(b.rho_max) ? nlohmann::json(b.rho_max) : nlohmann::json()},
                    {"points", b.points},
                    {"max_abs_error", b.max_error},
                    {"median_abs_error", b.median_error},
                    {"max_abs_error_nu_le_half_pi", b.max_error_weak},
                    {"kogelnik_ns", b.mean_kogelnik_ns},
                    {"rcwa_ms", b.mean_rcwa_ms}});
  return {{"points", points.size()}, {"by_rho", rows}};
}

// One tolerance trial of the shipped spec (resources/tolerance/prototype-tolerance.json: 14
// parameters, 5 gazes, 532 nm, refind) on one core, and what it predicts for a 1 000-trial run on
// two cores: the nominal unit once plus 1 000 trials shared by two workers.
nlohmann::json toleranceTiming(const Scene& scene, bool quick) {
  nlohmann::json j;
  auto doc = parseJsonText(analysis::defaultToleranceSpecText());
  const ToleranceSpec spec = parseToleranceSpec(std::get<nlohmann::json>(doc));
  tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
  const int trials = quick ? 8 : 32;
  const std::clock_t c0 = std::clock();
  const auto t0 = std::chrono::steady_clock::now();
  (void)nominalFigures(scene, spec);
  const std::clock_t c1 = std::clock();
  const auto t1 = std::chrono::steady_clock::now();
  (void)runToleranceTrials(scene, spec, 1, {0, static_cast<std::uint64_t>(trials)});
  const std::clock_t c2 = std::clock();
  const auto t2 = std::chrono::steady_clock::now();
  const double cpu_nominal = double(c1 - c0) / CLOCKS_PER_SEC, cpu_trial = double(c2 - c1) / CLOCKS_PER_SEC / trials;
  j["spec"] = "resources/tolerance/prototype-tolerance.json";
  j["trials_timed"] = trials;
  j["trial_ms_cpu_1core"] = 1e3 * cpu_trial;
  j["trial_ms_wall_1core"] = 1e3 * std::chrono::duration<double>(t2 - t1).count() / trials;
  j["nominal_ms_cpu"] = 1e3 * cpu_nominal;
  j["nominal_ms_wall"] = 1e3 * std::chrono::duration<double>(t1 - t0).count();
  j["predicted_1000_trials_cpu_s"] = cpu_nominal + 1000 * cpu_trial;
  j["predicted_1000_trials_s_2cores"] = cpu_nominal + 1000 * cpu_trial / 2;
  return j;
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand(
      "bench", "Run time against error: throughput, gaze update, sweeps, ray count, precision, Kogelnik vs RCWA");
  auto quick = std::make_shared<bool>(false), json = std::make_shared<bool>(false);
  cmd->add_flag("--quick", *quick, "small grids and short timings (seconds instead of minutes)");
  cmd->add_flag("--json", *json, "print JSON (keys documented in docs/benchmarks.md)");
  auto only = std::make_shared<std::string>();
  cmd->add_option("--only", *only, "run one section only: tolerance (one trial and the 1 000-trial prediction)")
      ->check(CLI::IsMember({"tolerance"}));
  cmd->callback([=] {
    const Scene scene = loadSceneOrExit("");
    nlohmann::json out;
    out["quick"] = *quick;
    if (*only == "tolerance") {
      out["tolerance"] = toleranceTiming(scene, *quick);
      if (*json) return printJson(out);
      std::cout << "tolerance trial: " << out["tolerance"]["trial_ms_cpu_1core"].get<double>()
                << " ms CPU on one core; 1 000 trials predicted "
                << out["tolerance"]["predicted_1000_trials_s_2cores"].get<double>() << " s on two idle cores\n";
      return;
    }
    out["throughput"] = throughput(scene, *quick);
    out["kogelnik_evals_per_s_1core"] = out["throughput"]["kogelnik_evals_per_s_1core"];
    out["rays_vs_fov"] = raysVsFov(scene, *quick);
    out["precision"] = precision(scene, *quick);
    out["kogelnik_vs_rcwa"] = kogelnikVsRcwaJson(*quick);
    out["tolerance"] = toleranceTiming(scene, *quick);
    if (*json) return printJson(out);
    const auto& t = out["throughput"];
    std::cout << "Kogelnik: " << t["kogelnik_evals_per_s_1core"].get<double>() / 1e6 << " M evals/s on one core (SIMD "
              << t["simd"].get<std::string>() << "), " << t["kogelnik_evals_per_s_all_cores"].get<double>() / 1e6
              << " M on " << t["cores"] << " cores\n"
              << "gaze update (20k rays): " << t["gaze_update_ms_20k_1core"].get<double>() << " ms; cold trace "
              << t["trace_cold_ms_20k_1core"].get<double>() << " ms\n";
  });
}

const Registrar reg{"bench", &install};

}  // namespace
}  // namespace cmd_bench
}  // namespace fovea::cli
