// fovea-cli report SCENE --out FILE.pdf|FILE.html [--gaze-deg A[,B] ...] [--rays N] [--follow-gaze]
//                 [--tolerance-trials N [--tolerance-spec FILE]] [--eye left|right|both]
//                 [--retina-speckle N] [--retina-grain pixel|pupil] [--retina-seed S]
//                 [--retina-calibration one|per-laser] [--json]
// The design report of a scene: title page with the scene summary, 3-D views, the bench at
// each gaze, retina maps, the analyses' plots and key numbers, and with --tolerance-trials the
// Tolerance section (app/studio/report_document.h, report_tolerance.h). A binocular scene: the
// report of one eye (--eye left|right: the manifest's "eye"), or by default (--eye both) the right
// eye's with a "Both eyes" section and the manifest's "eyes": {"left": {"gazes": [...]},
// "right": {...}}, each eye's FOV, efficiency and x_p per chosen gaze (app/studio/report_data.h).
// --retina-*: the retinal image figure's speckle and calibration, as the studio's Foveated preview
// sets them (issue 29); the manifest's "retina_image" echoes them.
//
// Why this command drives `fovea-studio --report` instead of linking the GUI: the report's
// 3-D figures need VTK's OpenGL rendering inside a Qt window, i.e. an X display (Xvfb when
// headless; Qt's offscreen platform gives VTK no GL context, docs/platform.md, quirk 6). Linking
// Qt Widgets + VTK into fovea-cli would make every command load them, slow every start, and
// break the GUI-less builds (the ASan preset builds fovea-cli with FOVEA_BUILD_GUI=OFF). So
// fovea-cli stays model-only and headless: it validates the arguments and the scene itself,
// then runs the fovea-studio next to it ($FOVEA_STUDIO overrides), under `xvfb-run` when
// there is no DISPLAY, and relays its JSON manifest. Exit codes: 0 written; 1 invalid scene,
// no studio or no display, or the report failed; 2 bad arguments.
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <climits>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <iostream>
#include <memory>

#include "app/cli/cli_common.h"
#include "app/cli/eye_option.h"
#include "model/io/json_input.h"
#include "model/io/save_temporaries.h"

namespace fovea::cli {
namespace cmd_report {  // one per command file: fovea-cli compiles in unity batches
namespace {

struct ReportArgs {
  std::string scene, out;
  std::vector<std::string> gazes;
  int rays = 1500;
  int tolerance_trials = 0;
  std::string tolerance_spec;
  bool follow_gaze = false;
  bool json = false;
  int retina_speckle = 0;  // the retinal image's options (the preview's Retina image controls)
  std::string retina_grain = "pixel", retina_calibration = "one";
  int retina_seed = 1;
};

std::string lower(std::string s) {
  for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string findStudio() {
  if (const char* env = std::getenv("FOVEA_STUDIO"); env && *env) return env;
  std::error_code ec;
  const auto self = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto next = self.parent_path() / "fovea-studio";
    if (std::filesystem::exists(next)) return next.string();
  }
  return {};
}

std::string findInPath(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return {};
  std::string p(path);
  std::size_t start = 0;
  while (start <= p.size()) {
    const std::size_t end = p.find(':', start);
    const std::string dir = p.substr(start, end == std::string::npos ? std::string::npos : end - start);
    const auto candidate = std::filesystem::path(dir.empty() ? "." : dir) / name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return {};
}

// Runs argv, returns its exit status; its stdout is captured into `output`, stderr passes.
int runCapturing(const std::vector<std::string>& argv, std::string& output) {
  int pipefd[2];
  if (::pipe(pipefd) != 0) inputError(std::string("cannot create a pipe: ") + std::strerror(errno));
  const pid_t pid = ::fork();
  if (pid < 0) inputError(std::string("cannot start fovea-studio: ") + std::strerror(errno));
  if (pid == 0) {
    ::dup2(pipefd[1], STDOUT_FILENO);
    ::close(pipefd[0]);
    ::close(pipefd[1]);
    std::vector<char*> args;
    for (const auto& a : argv) args.push_back(const_cast<char*>(a.c_str()));
    args.push_back(nullptr);
    ::execv(args[0], args.data());
    std::cerr << "fovea-cli: cannot run " << argv[0] << ": " << std::strerror(errno) << "\n";
    ::_exit(127);
  }
  ::close(pipefd[1]);
  char buffer[4096];
  ssize_t n;
  while ((n = ::read(pipefd[0], buffer, sizeof buffer)) > 0 || (n < 0 && errno == EINTR))
    if (n > 0) output.append(buffer, static_cast<std::size_t>(n));
  ::close(pipefd[0]);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + (WIFSIGNALED(status) ? WTERMSIG(status) : 0);
}

void install(CLI::App& app) {
  auto* cmd =
      app.add_subcommand("report", "Design report of a scene as PDF or self-contained HTML (needs fovea-studio)");
  auto a = std::make_shared<ReportArgs>();
  cmd->add_option("SCENE", a->scene, "scene file (default: the embedded prototype bench)");
  cmd->add_option("--out", a->out, "FILE.pdf or FILE.html")->required();
  cmd->add_option("--gaze-deg", a->gazes,
                  "gazes YAW[,PITCH] (deg) for the ray and retina figures (default: the scene's)");
  cmd->add_option("--rays", a->rays, "rays per wavelength for the traces and the sweep (default 1500)")
      ->check(CLI::Range(50, 1000000));
  cmd->add_flag("--follow-gaze", a->follow_gaze,
                "HOE follows gaze: trace each gaze with the FOV-maximising HOE shift x_p (drawn shifted)");
  cmd->add_option("--tolerance-trials", a->tolerance_trials,
                  "add the Tolerance section: a tolerance run of N trials (default 0: none)")
      ->check(CLI::Range(0, 1000000));
  cmd->add_option("--tolerance-spec", a->tolerance_spec,
                  "the tolerance spec for --tolerance-trials (default: the shipped prototype spec)")
      ->check(CLI::ExistingFile);
  cmd->add_flag("--json", a->json,
                "print the manifest {\"out\",\"format\",\"pages\",\"figures\",\"problems\",\"gaze_figures\","
                "\"sections\"}");
  cmd->add_option("--retina-speckle", a->retina_speckle,
                  "the retinal image's independent speckle patterns per laser (0: off, default; up to 16)")
      ->check(CLI::Range(0, 16));
  cmd->add_option("--retina-grain", a->retina_grain, "speckle grain: pixel (default) or pupil")
      ->check(CLI::IsMember({"pixel", "pupil"}));
  cmd->add_option("--retina-seed", a->retina_seed, "the speckle patterns' seed (default 1; 1..999, the studio's range)")
      ->check(CLI::Range(1, 999));
  cmd->add_option("--retina-calibration", a->retina_calibration,
                  "geometric calibration of the retinal image: one (default, the laser nearest 555 nm) or per-laser")
      ->check(CLI::IsMember({"one", "per-laser"}));
  const auto eye = addEyeOption(cmd);
  cmd->callback([a, eye] {
    const std::string ext = lower(std::filesystem::path(a->out).extension().string());
    if (ext != ".pdf" && ext != ".html" && ext != ".htm") usageError("--out: the file must end in .pdf or .html");
    if (auto why = cannotWriteFile(a->out)) usageError("--out: cannot write '" + a->out + "': " + *why);
    for (const auto& g : a->gazes) {
      const auto v = parseNumberList(g, "--gaze-deg", 1, 2);
      for (double x : v)
        if (!(std::abs(x) <= 90.0)) usageError("--gaze-deg: angles must lie in -90 .. 90, got '" + g + "'");
    }
    if (!a->tolerance_spec.empty() && a->tolerance_trials == 0)
      usageError("--tolerance-spec needs --tolerance-trials N");
    // Exit 1 with every problem before starting the studio; --eye on a monocular scene: exit 2.
    eyeRuns(loadSceneOrExit(a->scene), *eye, a->scene);

    const std::string studio = findStudio();
    if (studio.empty())
      inputError("report: fovea-studio was not found next to fovea-cli (build the GUI, or set FOVEA_STUDIO)");
    std::vector<std::string> argv;
    const bool display = (std::getenv("DISPLAY") && *std::getenv("DISPLAY")) ||
                         (std::getenv("WAYLAND_DISPLAY") && *std::getenv("WAYLAND_DISPLAY"));
    if (!display) {
      const std::string xvfb = findInPath("xvfb-run");
      if (xvfb.empty()) inputError("report: no DISPLAY and no xvfb-run to render the 3-D views (install xvfb)");
      argv = {xvfb, "-a", "-s", "-screen 0 1920x1080x24"};
    }
    argv.push_back(studio);
    if (!a->scene.empty()) argv.push_back(std::filesystem::absolute(a->scene).string());
    argv.push_back("--report");
    argv.push_back(std::filesystem::absolute(a->out).string());
    for (const auto& g : a->gazes) argv.push_back("--gaze-deg=" + g);
    argv.push_back("--rays");
    argv.push_back(std::to_string(a->rays));
    if (a->follow_gaze) argv.push_back("--follow-gaze");
    if (!eye->empty()) argv.push_back("--report-eye=" + *eye);
    argv.push_back("--report-retina=" + std::to_string(a->retina_speckle) + "," + a->retina_grain + "," +
                   a->retina_calibration + "," + std::to_string(a->retina_seed));
    if (a->tolerance_trials > 0) {
      argv.push_back("--report-tolerance");
      argv.push_back(std::to_string(a->tolerance_trials));
      if (!a->tolerance_spec.empty()) {
        argv.push_back("--report-tolerance-spec");
        argv.push_back(std::filesystem::absolute(a->tolerance_spec).string());
      }
    }
    std::string manifest;
    const int code = runCapturing(argv, manifest);
    if (code == 2) usageError("report: fovea-studio refused the arguments");
    if (code != 0) inputError("report: fovea-studio failed (exit " + std::to_string(code) + ")");
    nlohmann::json m;
    try {
      m = readJsonText(manifest, "fovea-studio's manifest");
    } catch (const std::exception&) {
      inputError("report: unexpected output from fovea-studio: " + manifest.substr(0, 200));
    }
    if (a->json) return printJson(m);
    std::cout << "report written to " << m.value("out", a->out) << " (" << m.value("figures", 0) << " figures";
    if (m.contains("pages") && m["pages"].is_number()) std::cout << ", " << m["pages"].get<int>() << " pages";
    std::cout << ")\n";
  });
}

const Registrar reg{"report", &install};

}  // namespace
}  // namespace cmd_report
}  // namespace fovea::cli
