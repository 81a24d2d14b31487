#include "model/memory_policy.h"

#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace fovea {

bool keepFreedMemoryForReuse() {
#if defined(__GLIBC__)
  // Setting either threshold also turns off glibc's dynamic threshold, which would otherwise
  // move them with the sizes freed (mallopt(3)).
  const bool mmap_ok = mallopt(M_MMAP_THRESHOLD, static_cast<int>(kKeptBlockBytes)) == 1;
  const bool trim_ok = mallopt(M_TRIM_THRESHOLD, static_cast<int>(kKeptBlockBytes)) == 1;
  return mmap_ok && trim_ok;
#else
  return false;
#endif
}

}  // namespace fovea
