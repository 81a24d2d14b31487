// The process's allocator policy (model/memory_policy.h): after keepFreedMemoryForReuse(), a
// large block freed and allocated again is not faulted in again, on the main thread and on a
// worker (its own malloc arena); with glibc's default threshold restored, the same block faults
// every page again, so the measure tells the two apart.
#include <QtTest>

#include <dlfcn.h>
#include <sys/resource.h>

#include <cstddef>
#include <cstdlib>
#include <thread>

#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include "model/memory_policy.h"

namespace tst_memory_policy {

namespace {

constexpr std::size_t kBlockBytes = 48u << 20;  // a 1920 x 1080 x 3 plane of doubles
constexpr long kPages = static_cast<long>(kBlockBytes / 4096);

long threadMinorFaults() {
  rusage usage{};
  getrusage(RUSAGE_THREAD, &usage);
  return usage.ru_minflt;
}

// Minor faults of allocating the block, touching each page and freeing it; volatile stores so
// that the compiler cannot drop the allocation.
long faultsOfOneBlock() {
  const long before = threadMinorFaults();
  auto* block = static_cast<volatile char*>(std::malloc(kBlockBytes));
  if (block == nullptr) return -1;
  for (std::size_t i = 0; i < kBlockBytes; i += 4096) block[i] = 1;
  std::free(const_cast<char*>(block));
  return threadMinorFaults() - before;
}

// The ASan tree runs this executable (built in the default tree) with the ASan runtime
// preloaded (tests/asan): its allocator replaces glibc's, so the runtime is asked, not the
// compiler.
bool asanRuntimeLoaded() {
  return dlsym(RTLD_DEFAULT, "__asan_init") != nullptr;
}

// Faults of the second of two blocks in a row (the first may fault: fresh memory).
long faultsOfSecondBlock() {
  faultsOfOneBlock();
  return faultsOfOneBlock();
}

}  // namespace

class TestMemoryPolicy : public QObject {
  Q_OBJECT

 private slots:
  void freedBlocksAreReusedWithoutFaults() {
#if !defined(__GLIBC__)
    QSKIP("the policy is glibc's mallopt");
#else
    if (asanRuntimeLoaded()) {
      QVERIFY(!fovea::keepFreedMemoryForReuse());  // ASan's mallopt takes nothing, and the policy says so
      QSKIP("ASan's allocator replaces glibc's: there is no policy to check");
    }
    QVERIFY(fovea::keepFreedMemoryForReuse());
    const long main_thread = faultsOfSecondBlock();
    long worker = -1;
    std::thread([&] { worker = faultsOfSecondBlock(); }).join();
    qInfo("second 48 MiB block: %ld faults on the main thread, %ld on a worker (%ld pages)", main_thread, worker,
          kPages);
    QVERIFY2(main_thread >= 0 && main_thread < kPages / 100, "the freed block was returned to the kernel");
    QVERIFY2(worker >= 0 && worker < kPages / 100, "the worker's freed block was returned to the kernel");

    // glibc's default thresholds (128 KiB: blocks above it mapped afresh and unmapped on free,
    // the heap's free top trimmed), the heap given back first: every page faults again. Then the
    // policy is restored for the rest of the process.
    QCOMPARE(mallopt(M_MMAP_THRESHOLD, 128 * 1024), 1);
    QCOMPARE(mallopt(M_TRIM_THRESHOLD, 128 * 1024), 1);
    malloc_trim(0);
    const long unmapped = faultsOfSecondBlock();
    QVERIFY(fovea::keepFreedMemoryForReuse());
    QVERIFY2(unmapped > kPages * 9 / 10, qPrintable(QString("default threshold: only %1 faults").arg(unmapped)));
#endif
  }
};

QTEST_GUILESS_MAIN(TestMemoryPolicy)

}  // namespace tst_memory_policy
#include "tst_memory_policy.moc"
