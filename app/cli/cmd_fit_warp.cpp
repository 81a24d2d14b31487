// fovea-cli fit-warp --pairs FILE --model poly1|poly2|poly3|homography
//                    [--holdout-fraction F] [--seed N] [--json]
// FILE: {"pairs":[{"src":[x,y],"dst":[u,v]},...], "query":[[x,y],...]} (query optional).
// Seed B.2.1: least-squares warp with a held-out residual; degenerate input exits 1.
#include <cmath>
#include <iostream>

#include "app/cli/cli_common.h"
#include "app/cli/preview_json_io.h"
#include "model/image/warp.h"

namespace fovea::cli {
namespace cmd_fit_warp {  // one per command file: fovea-cli compiles in unity batches
namespace {

Eigen::Vector2d point(const nlohmann::json& j, const std::string& where) {
  if (!j.is_array() || j.size() != 2) inputError(where + " must be [x, y]");
  Eigen::Vector2d p;
  for (int k = 0; k < 2; ++k) {
    if (j[k].is_null())
      p[k] = std::nan("");  // NaN written by JSON writers as null
    else if (!j[k].is_number())
      inputError(where + " must hold two numbers");
    else
      p[k] = j[k].get<double>();
  }
  return p;
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("fit-warp", "Fit a 2-D polynomial or homography warp to point pairs (B.2.1)");
  struct Args {
    std::string pairs, model;
    double holdout = 0.0;
    std::uint64_t seed = 1;
    bool json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--pairs", a->pairs, "JSON file of point pairs (and optional query points)")->required();
  cmd->add_option("--model", a->model, "poly1, poly2, poly3 or homography")
      ->required()
      ->check(CLI::IsMember({"poly1", "poly2", "poly3", "homography"}));
  cmd->add_option("--holdout-fraction", a->holdout, "fraction of pairs held out for the residual (default 0)")
      ->check(CLI::Range(0.0, 0.95));
  addSeedOption(cmd, a->seed, "seed of the hold-out split (default 1)");
  cmd->add_flag("--json", a->json, "print the result as JSON");
  cmd->callback([a] {
    const nlohmann::json in = readJsonFileOrExit(a->pairs);
    if (!in.is_object() || !in.contains("pairs") || !in["pairs"].is_array())
      inputError(a->pairs + ": needs a \"pairs\" array of {\"src\":[x,y],\"dst\":[u,v]}");
    std::vector<image::PointPair> pairs;
    for (std::size_t i = 0; i < in["pairs"].size(); ++i) {
      const auto& p = in["pairs"][i];
      const std::string where = a->pairs + ": pairs[" + std::to_string(i) + "]";
      if (!p.is_object() || !p.contains("src") || !p.contains("dst")) inputError(where + " needs src and dst");
      pairs.push_back({point(p["src"], where + ".src"), point(p["dst"], where + ".dst")});
    }
    std::vector<Eigen::Vector2d> query;
    if (in.contains("query")) {
      if (!in["query"].is_array()) inputError(a->pairs + ": query must be an array of [x, y]");
      for (std::size_t i = 0; i < in["query"].size(); ++i)
        query.push_back(point(in["query"][i], a->pairs + ": query[" + std::to_string(i) + "]"));
    }
    const image::WarpModel model = *image::warpModelFromString(a->model);
    image::WarpFit fit;
    try {
      fit = image::fitWarpWithHoldout(pairs, model, a->holdout, a->seed);
    } catch (const image::WarpError& e) {
      inputError(a->pairs + ": " + e.what());
    }
    nlohmann::json predicted = nlohmann::json::array();
    for (const auto& q : query) {
      const Eigen::Vector2d p = fit.warp.apply(q);
      predicted.push_back({p.x(), p.y()});
    }
    nlohmann::json out{{"model", a->model},
                       {"coefficients", fit.warp.coefficients()},
                       {"rms_px", {{"fit", fit.rms_fit_px}, {"holdout", fit.rms_holdout_px}}},
                       {"query_predicted", predicted},
                       {"pairs", {{"fitted", fit.fitted}, {"held_out", fit.held_out}}},
                       {"holdout_indices", fit.holdout_indices},
                       {"seed", a->seed}};
    if (a->json) {
      printJson(out);
      return;
    }
    std::cout << a->model << ": RMS fit " << fit.rms_fit_px << " px over " << fit.fitted << " pairs";
    if (fit.held_out > 0) std::cout << ", held-out " << fit.rms_holdout_px << " px over " << fit.held_out;
    std::cout << "\n";
    for (const auto& p : predicted) std::cout << p[0] << " " << p[1] << "\n";
  });
}

const Registrar reg{"fit-warp", &install};

}  // namespace
}  // namespace cmd_fit_warp
}  // namespace fovea::cli
