#include "viz/software_gl.h"

#include <cstdlib>
#include <string>

#if defined(__linux__)
#include <sched.h>
#include <unistd.h>
#endif

namespace fovea::viz {

int matchSoftwareRasterizerToAffinity() {
#if defined(__linux__)
  if (std::getenv("LP_NUM_THREADS") != nullptr) return 0;
  cpu_set_t allowed;
  CPU_ZERO(&allowed);
  if (sched_getaffinity(0, sizeof(allowed), &allowed) != 0) return 0;
  const int usable = CPU_COUNT(&allowed);
  const long online = sysconf(_SC_NPROCESSORS_ONLN);
  if (usable <= 0 || online <= 0 || usable >= online) return 0;
  setenv("LP_NUM_THREADS", std::to_string(usable).c_str(), 0);
  return usable;
#else
  return 0;
#endif
}

}  // namespace fovea::viz
