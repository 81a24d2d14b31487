#include "model/vector_state.h"

#include <tbb/task_scheduler_observer.h>

namespace fovea {

void clearUpperVectorState() {
#if defined(__x86_64__) || defined(__i386__)
  static const bool has_avx = __builtin_cpu_supports("avx");
  if (has_avx) asm volatile("vzeroupper" ::: "memory");
#endif
}

namespace {
class ClearOnEntry : public tbb::task_scheduler_observer {
 public:
  ClearOnEntry() { observe(true); }
  void on_scheduler_entry(bool /*is_worker*/) override { clearUpperVectorState(); }
};
}  // namespace

void clearUpperVectorStateOnTbbThreads() {
  static ClearOnEntry observer;  // lives as long as the process
}

}  // namespace fovea
