// What one frame of the studio's 3-D view costs (viz/scene_view.h) on the machine's OpenGL
// (Mesa llvmpipe under Xvfb in CI): the default scene with its ray fans, at the view size the
// studio has at 1920x1080 (758x703 px) and at 1366x768 (~500x420 px), drawn as at rest
// (depth-peeled translucency, full resolution) and as while a hand drags (one-pass OIT, at
// the drag resolution). Each iteration renders into an off-screen framebuffer and reads it
// back (SceneView::renderToImage); the counter paint_ms is VTK's render plus the blit alone
// (VtkGlWidget::lastPaintMs), i.e. without the read-back. Run under Xvfb:
//   xvfb-run -a -s "-screen 0 1920x1080x24" build/default/benchmarks/fovea-view-benchmarks
// docs/benchmarks.md ("Responsive drag") has the numbers.
#include <benchmark/benchmark.h>

#include <QApplication>

#include <memory>

#include "app/embedded_scene.h"
#include "model/memory_policy.h"
#include "model/physics/projector_rays.h"
#include "model/physics/trace.h"
#include "model/scene/scene_io.h"
#include "viz/scene_view.h"
#include "viz/trace_overlay.h"
#include "viz/vtk_gl_widget.h"

namespace {

struct View {
  fovea::viz::SceneView view;
  std::unique_ptr<fovea::viz::TraceOverlay> overlay;
  View(int w, int h) {
    view.resize(w, h);
    view.show();
    const fovea::Scene scene = fovea::embeddedDefaultScene();
    view.setScene(scene, true);
    overlay = std::make_unique<fovea::viz::TraceOverlay>(&view);
    fovea::TraceOptions o;
    o.rays = 4000;
    o.keep_rays = true;
    const fovea::TraceResult t = fovea::traceScene(scene, o);
    overlay->show(scene, t, fovea::projectorGrid(scene.projector, o.rays), {0.0, 0.0}, {});
    for (int i = 0; i < 50; ++i) QApplication::processEvents();  // exposed, first frame
  }
};

// Args: view width, height, drag resolution in % (0: at rest, depth-peeled at full resolution).
void BM_SceneViewFrame(benchmark::State& state) {
  View v(static_cast<int>(state.range(0)), static_cast<int>(state.range(1)));
  const int drag_percent = static_cast<int>(state.range(2));
  if (drag_percent > 0) {
    v.view.setDragRenderScale(drag_percent / 100.0);
    v.view.setDragRendering(true);
  }
  v.view.renderToImage();  // shader variants compiled outside the timing
  double paint_ms = 0.0;
  for (auto _ : state) {
    benchmark::DoNotOptimize(v.view.renderToImage().constBits());
    paint_ms += v.view.lastPaintMs();
  }
  state.counters["paint_ms"] = paint_ms / static_cast<double>(state.iterations());
  state.counters["render_px"] = v.view.lastRenderSize().width() * v.view.lastRenderSize().height();
}
BENCHMARK(BM_SceneViewFrame)
    ->Args({758, 703, 0})
    ->Args({758, 703, 100})
    ->Args({758, 703, 75})
    ->Args({758, 703, 50})
    ->Args({758, 703, 25})
    ->Args({500, 420, 0})
    ->Args({500, 420, 50})
    ->Unit(benchmark::kMillisecond)
    ->MinTime(1.0);

}  // namespace

int main(int argc, char** argv) {
  fovea::keepFreedMemoryForReuse();  // as the studio (model/memory_policy.h)
  fovea::viz::installDefaultSurfaceFormat();
  QApplication app(argc, argv);
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
