// fovea-cli eye-dataset --out DIR --frames N [--start I] [--seed S] [--domain wide|classic]
//                       [--subset NAME] [--size PX] [--no-png] [--json]
// Writes synthetic IR eye-camera frames with their ground truth, from the same renderer the
// tests and `track --virtual` use, for training the learned pupil detector
// (scripts/train-pupil-net.sh). --domain wide (model/gaze/wide_eye_domain.h) draws from the
// randomised domain, subset "train" by default (train_hard: the hard subset's combination in
// the training's bands; train_partial: train's draws, every frame partial; the held-out
// subsets can be written for inspection: easy, glints, occlusion, motion_blur, off_axis,
// partial, hard, closed);
// --domain classic cycles through the pupil benchmark's subsets. DIR gets:
//   images/NNNNNN.png  the frames (8-bit grey, at --size when given) unless --no-png;
//   images.u8          all frames packed, N x size x size bytes (row-major), for the trainer;
//   labels.csv         index,subset,visible,visible_fraction,cx_px,cy_px,major_px,minor_px,
//                      angle_deg in the rendered frame's pixels (400 x 400);
//   dataset.json       domain, subset, seed, frames, frame and stored sizes.
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>

#include <opencv2/imgproc.hpp>

#include "app/cli/cli_common.h"
#include "model/gaze/pupil_benchmark.h"
#include "model/gaze/wide_eye_domain.h"
#include "model/image/image_io.h"

namespace fovea::cli {
namespace cmd_eye_dataset {  // one per command file: fovea-cli compiles in unity batches
namespace {

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("eye-dataset", "Write synthetic IR eye frames with ground truth (training data)");
  struct Args {
    std::string out, domain = "wide", subset = "train";
    int frames = 0, size_px = 0, start = 0;
    unsigned seed = 1;
    bool no_png = false, json = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("--out", a->out, "output directory (created)")->required();
  cmd->add_option("--frames", a->frames, "number of frames")->required()->check(CLI::Range(1, 1000000));
  cmd->add_option("--start", a->start, "index of the first frame (default 0: shards of one set)")
      ->check(CLI::Range(0, 100000000));
  addSeedOption(cmd, a->seed, "seed of the frames (default 1)");
  cmd->add_option("--domain", a->domain, "wide (randomised, default) or classic (the pupil benchmark's)");
  cmd->add_option("--subset", a->subset,
                  "wide domain: train (default), train_hard, train_partial or a held-out subset name");
  cmd->add_option("--size", a->size_px, "store frames downscaled to PX x PX (INTER_AREA); default: as rendered")
      ->check(CLI::Range(8, 4096));
  cmd->add_flag("--no-png", a->no_png, "write only images.u8 and the labels");
  cmd->add_flag("--json", a->json, "print a summary as JSON");
  cmd->callback([a] {
    if (a->domain != "wide" && a->domain != "classic")
      usageError("--domain: '" + a->domain + "' is not one of wide, classic");
    const auto wide_subset = gaze::parseWideSubset(a->subset);
    if (a->domain == "wide" && !wide_subset) {
      std::string names;
      for (const auto s : gaze::allWideSubsets())
        names += (names.empty() ? "" : ", ") + std::string(gaze::wideSubsetName(s));
      usageError("--subset: '" + a->subset + "' is not one of " + names);
    }
    namespace fs = std::filesystem;
    const fs::path dir(a->out);
    std::error_code ec;
    fs::create_directories(dir / "images", ec);
    if (ec) inputError("--out: " + a->out + ": " + ec.message());
    std::ofstream labels(dir / "labels.csv"), packed(dir / "images.u8", std::ios::binary);
    if (!labels || !packed) inputError("--out: " + a->out + ": cannot write there");
    labels << "index,subset,visible,visible_fraction,cx_px,cy_px,major_px,minor_px,angle_deg\n" << std::setprecision(9);
    cv::Size frame_size;
    int visible = 0;
    const auto classic = gaze::allSubsets();
    for (int i = a->start; i < a->start + a->frames; ++i) {
      std::string subset_name;
      gaze::EyeFrame f;
      if (a->domain == "wide") {
        f = gaze::renderWideFrame(*wide_subset, i, a->seed);
        subset_name = gaze::wideSubsetName(*wide_subset);
      } else {
        const gaze::EyeSubset s = classic[static_cast<std::size_t>(i) % classic.size()];
        f = gaze::renderBenchmarkFrame(s, i / static_cast<int>(classic.size()), a->seed);
        subset_name = gaze::subsetName(s);
      }
      frame_size = f.image.size();
      cv::Mat stored = f.image;
      if (a->size_px > 0) cv::resize(f.image, stored, {a->size_px, a->size_px}, 0, 0, cv::INTER_AREA);
      if (!stored.isContinuous()) stored = stored.clone();
      packed.write(reinterpret_cast<const char*>(stored.data), static_cast<std::streamsize>(stored.total()));
      if (!a->no_png) {
        std::ostringstream name;
        name << std::setw(6) << std::setfill('0') << i << ".png";
        try {
          image::writeCameraImage((dir / "images" / name.str()).string(), stored);
        } catch (const image::ImageIoError& e) {
          inputError(std::string("--out: cannot write a frame: ") + e.what());
        }
      }
      const auto& t = f.truth;
      visible += t.pupil_visible ? 1 : 0;
      labels << i << ',' << subset_name << ',' << (t.pupil_visible ? 1 : 0) << ',' << t.visible_fraction << ','
             << t.pupil.centre.x << ',' << t.pupil.centre.y << ',' << t.pupil.major_px << ',' << t.pupil.minor_px << ','
             << t.pupil.angle_deg << '\n';
    }
    const int stored_px = a->size_px > 0 ? a->size_px : frame_size.width;
    const nlohmann::json meta{
        {"domain", a->domain},
        {"subset", a->domain == "wide" ? a->subset : std::string("cycle")},
        {"seed", a->seed},
        {"start", a->start},
        {"frames", a->frames},
        {"with_pupil", visible},
        {"frame_size_px", {frame_size.width, frame_size.height}},
        {"stored_size_px",
         {a->size_px > 0 ? a->size_px : frame_size.width, a->size_px > 0 ? a->size_px : frame_size.height}},
        {"png", !a->no_png}};
    std::ofstream(dir / "dataset.json") << meta.dump(2) << '\n';
    labels.close();
    packed.close();
    if (!labels || !packed) inputError("--out: " + a->out + ": write failed");
    if (a->json)
      printJson(meta);
    else
      std::cout << "wrote " << a->frames << " frames (" << visible << " with a pupil) at " << stored_px << " px to "
                << a->out << "\n";
  });
}

const Registrar reg{"eye-dataset", &install};

}  // namespace
}  // namespace cmd_eye_dataset
}  // namespace fovea::cli
