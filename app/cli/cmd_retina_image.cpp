// fovea-cli retina-image [SCENE] --image IMG --out OUT.png [--gaze-deg A[,B]] [--accommodation-d D]
//                        [--hoe-shift-mm X[,Y]] [--speckle N] [--speckle-grain pixel|pupil] [--seed S]
//                        [--rays N] [--no-blend]
//                        [--per-laser-calibration] [--json]
// Issue 29: the image on both displays -> the retinal image in visual angle (linear RGB,
// written sRGB-encoded), with the line-of-sight spot and resolution of each display
// (model/image/retina_image.h, model/analysis/retinal_psf.h; docs/physics.md section 6).
// --eye left|right|both: each eye of a binocular scene (app/cli/eye_option.h); with both eyes the
// right eye's image is written to OUT and the left eye's next to it, OUT's name with "-left"
// before the extension; each eye's document names its file in "image_out".
#include <chrono>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <sstream>

#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "model/analysis/analysis_json.h"
#include "model/image/image_io.h"
#include "model/image/retina_image.h"
#include "model/io/save_temporaries.h"

namespace fovea::cli {
namespace cmd_retina_image {  // one per command file: fovea-cli compiles in unity batches
namespace {

// Renders one eye (or the monocular scene), writes its image to `file`; the JSON document.
nlohmann::json renderOne(const EyeRun& run, const std::string& file, const cv::Mat& target,
                         const image::RetinaImageOptions& o, bool json) {
  const auto t0 = std::chrono::steady_clock::now();
  image::RetinaImageResult r;
  try {
    r = image::renderRetinaImage(run.scene, target, o);
  } catch (const std::invalid_argument& e) {
    inputError(e.what());
  }
  const auto t1 = std::chrono::steady_clock::now();
  try {
    image::writeLinearRgb(file, r.image);
  } catch (const image::ImageIoError& e) {
    inputError(e.what());
  }
  nlohmann::json j;
  const bool have_p = !r.peripheral.empty() && r.peripheral[r.peripheral_reference].valid;
  j["peripheral"] = have_p ? spotMetricsJson(r.peripheral[r.peripheral_reference].metrics) : nlohmann::json(nullptr);
  j["foveal"] = r.foveal.empty() ? nlohmann::json(nullptr) : spotMetricsJson(r.foveal[r.foveal_reference].metrics);
  j["speckle_contrast"] = r.speckle_contrast ? nlohmann::json(*r.speckle_contrast) : nlohmann::json(nullptr);
  j["power_in_pupil"] = r.power_in_pupil;
  j["power_on_retina"] = r.power_on_retina;
  j["accommodation_d"] = o.accommodation_d;
  j["gaze_deg"] = {o.gaze_deg[0], o.gaze_deg[1]};
  // Additions.
  j["hoe_shift_mm"] = {o.hoe_shift_mm[0], o.hoe_shift_mm[1]};
  j["speckle_expected"] = r.speckle_expected ? nlohmann::json(*r.speckle_expected) : nlohmann::json(nullptr);
  j["speckle_patterns"] = o.speckle_patterns;
  j["speckle_grain"] = o.speckle_grain_pupil ? "pupil" : "pixel";
  j["speckle_dof"] = r.speckle_dof.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.speckle_dof);
  j["spot_fwhm_definition"] = "diameter enclosing half the power (EE50): the FWHM of a Gaussian spot";
  j["power_off_canvas"] = r.power_off_canvas;
  j["power_units"] = "linear value x canvas pixels (uniform radiance 1 gives 1 per pixel), summed over R, G, B";
  nlohmann::json per = nlohmann::json::array();
  for (const auto& p : r.peripheral) per.push_back(peripheralSpotJson(p));
  j["peripheral_per_wavelength"] = per;
  nlohmann::json fov = nlohmann::json::array();
  for (const auto& f : r.foveal) fov.push_back(fovealSpotJson(f));
  j["foveal_per_primary"] = fov;
  nlohmann::json lc = nlohmann::json::array();
  for (const auto& c : r.lateral_colour)
    lc.push_back({{"wavelength_nm", c.wavelength_nm},
                  {"valid", c.valid},
                  {"field_deg", c.field_deg},
                  {"offset_arcmin", c.offset_arcmin}});
  j["lateral_colour"] = lc;
  // The field-dependent peripheral PSF at its nodes (world angles), per laser.
  nlohmann::json field = nlohmann::json::array();
  const std::size_t nodes = r.peripheral.empty() ? 0 : r.peripheral_field.size() / r.peripheral.size();
  for (std::size_t n = 0; n < r.peripheral_field.size(); ++n) {
    const auto& f = r.peripheral_field[n];
    nlohmann::json e = spotMetricsJson(f.spot.metrics);
    e["wavelength_nm"] = r.peripheral[n / nodes].wavelength_nm;
    e["world_deg"] = f.world_deg;
    e["field_deg"] = f.spot.field_deg;
    e["radius_major_arcmin"] = f.spot.radius_major_arcmin;
    e["radius_minor_arcmin"] = f.spot.radius_minor_arcmin;
    e["orientation_deg"] = f.spot.orientation_deg;
    e["astigmatism_d"] = f.spot.astigmatism_d;
    field.push_back(e);
  }
  j["peripheral_field"] = field;
  j["colour_calibration"] = o.per_laser_calibration ? "per-laser" : "common";
  j["rays_in_pupil"] = r.rays_in_pupil;
  j["pixels_per_degree"] = r.pixels_per_degree;
  j["size"] = {r.image.cols, r.image.rows};
  j["render_ms"] = std::chrono::duration<double, std::milli>(t1 - t0).count();
  if (run.side) j["image_out"] = file;
  if (json) return j;
  std::ostringstream os;
  os << eyePrefix(run) << "retinal image " << file << " (" << r.image.cols << "x" << r.image.rows << "), accommodation "
     << o.accommodation_d << " D\n";
  if (have_p) {
    const auto& m = r.peripheral[r.peripheral_reference].metrics;
    os << "peripheral: spot " << m.fwhm_arcmin << " arcmin, MTF50 " << m.mtf50_cpd << " cpd, MTF10 " << m.mtf10_cpd
       << " cpd\n";
  }
  if (!r.foveal.empty()) {
    const auto& m = r.foveal[r.foveal_reference].metrics;
    os << "foveal: spot " << m.fwhm_arcmin << " arcmin, MTF50 " << m.mtf50_cpd << " cpd, MTF10 " << m.mtf10_cpd
       << " cpd\n";
  }
  os << "power in pupil " << r.power_in_pupil << ", on retina " << r.power_on_retina << "\n";
  printText(os.str());
  return j;
}

void install(CLI::App& app) {
  auto* cmd = app.add_subcommand("retina-image",
                                 "Retinal image of both displays at a gaze and accommodation (PSFs, shading, speckle)");
  struct Args {
    std::string scene, image, out, gaze = "0,0", accommodation = "1.25", shift = "0,0", speckle = "0", rays = "20000",
                                   seed = "1", grain = "pixel";
    bool json = false, noBlend = false, perLaser = false;
  };
  auto a = std::make_shared<Args>();
  cmd->add_option("SCENE", a->scene, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--image", a->image, "image shown on both displays (spans the projector's FOV)")->required();
  auto* out = cmd->add_option("--out", a->out, "retinal image to write (PNG, TIFF or EXR)")->required();
  cmd->add_option("--gaze-deg", a->gaze, "gaze yaw[,pitch] in degrees (default 0,0)");
  cmd->add_option("--accommodation-d", a->accommodation,
                  "accommodation in diopters, 0..4 (default 1.25: the foveal image at 0.8 m)");
  cmd->add_option("--hoe-shift-mm", a->shift, "HOE lateral shift x[,y] in mm (default 0,0)");
  cmd->add_option("--speckle", a->speckle, "independent speckle patterns per laser (0: speckle off, default)");
  cmd->add_option("--seed", a->seed, "speckle random seed (default 1)");
  cmd->add_option("--speckle-grain", a->grain,
                  "speckle grain: 'pixel' (one canvas pixel, default) or 'pupil' (the pupil's Airy grain lambda/D, "
                  "integrated over each canvas pixel; docs/physics.md)");
  cmd->add_option("--rays", a->rays, "traced rays per laser (default 20000)");
  cmd->add_flag("--no-blend", a->noBlend, "hard switch at eps_o instead of the B.2.3 blend");
  cmd->add_flag("--per-laser-calibration", a->perLaser,
                "warp each laser on its own (no lateral colour); default: one geometric calibration for all "
                "lasers, measured on the laser nearest 555 nm");
  cmd->add_flag("--json", a->json, "print the JSON result");
  const auto eye = addEyeOption(cmd);
  cmd->callback([a, out, eye] {
    checkOutputOption(out, a->out);
    image::RetinaImageOptions o;
    const auto g = parseNumberList(a->gaze, "--gaze-deg", 1, 2);
    o.gaze_deg = {g[0], g.size() > 1 ? g[1] : 0.0};
    if (std::abs(o.gaze_deg[0]) > 60 || std::abs(o.gaze_deg[1]) > 60)
      usageError("--gaze-deg: each angle must be within -60..60 degrees");
    o.accommodation_d = parseNumberList(a->accommodation, "--accommodation-d", 1, 1)[0];
    if (o.accommodation_d < 0 || o.accommodation_d > 4)
      usageError("--accommodation-d: must be within 0..4 D (the schematic eye's range), got '" + a->accommodation +
                 "'");
    const auto s = parseNumberList(a->shift, "--hoe-shift-mm", 1, 2);
    o.hoe_shift_mm = {s[0], s.size() > 1 ? s[1] : 0.0};
    const double speckle = parseNumberList(a->speckle, "--speckle", 1, 1)[0];
    if (speckle < 0 || speckle > 1000 || speckle != std::floor(speckle))
      usageError("--speckle: a whole number of patterns within 0..1000, got '" + a->speckle + "'");
    o.speckle_patterns = static_cast<int>(speckle);
    o.speckle_seed = parseSeed(a->seed, "--seed");
    if (a->grain != "pixel" && a->grain != "pupil")
      usageError("--speckle-grain: 'pixel' or 'pupil', got '" + a->grain + "'");
    o.speckle_grain_pupil = a->grain == "pupil";
    const double rays = parseNumberList(a->rays, "--rays", 1, 1)[0];
    if (rays < 100 || rays > 1e6 || rays != std::floor(rays))
      usageError("--rays: a whole number within 100..1000000, got '" + a->rays + "'");
    o.rays = static_cast<int>(rays);
    o.blend = !a->noBlend;
    o.per_laser_calibration = a->perLaser;
    const std::vector<EyeRun> runs = eyeRuns(loadSceneOrExit(a->scene), *eye, a->scene);
    cv::Mat target;
    try {
      target = image::readLinearRgb(a->image);
    } catch (const image::ImageIoError& e) {
      inputError(e.what());
    }
    std::vector<nlohmann::json> docs;
    for (const EyeRun& run : runs) {
      std::string file = a->out;
      if (runs.size() > 1 && run.side == EyeSide::Left) {
        const std::filesystem::path p(a->out);
        file = (p.parent_path() / (p.stem().string() + "-left" + p.extension().string())).string();
        if (auto why = cannotWriteFile(file)) usageError("--out: cannot write the left eye's '" + file + "': " + *why);
      }
      docs.push_back(renderOne(run, file, target, o, a->json));
    }
    if (a->json) printJson(combineEyeDocuments(runs, docs));
  });
}

const Registrar reg{"retina-image", &install};

}  // namespace
}  // namespace cmd_retina_image
}  // namespace fovea::cli
