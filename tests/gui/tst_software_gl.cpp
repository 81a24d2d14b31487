// viz/software_gl.h: llvmpipe's rasterizer threads follow the CPUs the studio may run on
// (LP_NUM_THREADS set when the affinity mask is narrower than the online CPUs), and a value
// the user set is kept.
#include <QtTest>

#include <cstdlib>

#include <sched.h>
#include <unistd.h>

#include "viz/software_gl.h"

namespace tst_software_gl {

class TestSoftwareGl : public QObject {
  Q_OBJECT
 private:
  cpu_set_t original_{};

 private slots:
  void initTestCase() {
    QCOMPARE(sched_getaffinity(0, sizeof(original_), &original_), 0);
    if (CPU_COUNT(&original_) < 2) QSKIP("needs at least two CPUs to narrow the affinity");
  }
  void cleanup() {
    sched_setaffinity(0, sizeof(original_), &original_);
    unsetenv("LP_NUM_THREADS");
  }

  void pinnedToOneCpuUsesOneRasterizerThread() {
    unsetenv("LP_NUM_THREADS");
    cpu_set_t one;
    CPU_ZERO(&one);
    for (int c = 0; c < CPU_SETSIZE; ++c)
      if (CPU_ISSET(c, &original_)) {
        CPU_SET(c, &one);
        break;
      }
    QCOMPARE(sched_setaffinity(0, sizeof(one), &one), 0);
    QCOMPARE(fovea::viz::matchSoftwareRasterizerToAffinity(), 1);
    QCOMPARE(qgetenv("LP_NUM_THREADS"), QByteArray("1"));
  }

  void theUsersSettingIsKept() {
    setenv("LP_NUM_THREADS", "3", 1);
    cpu_set_t one;
    CPU_ZERO(&one);
    CPU_SET(sched_getcpu(), &one);
    QCOMPARE(sched_setaffinity(0, sizeof(one), &one), 0);
    QCOMPARE(fovea::viz::matchSoftwareRasterizerToAffinity(), 0);
    QCOMPARE(qgetenv("LP_NUM_THREADS"), QByteArray("3"));
  }

  void everyOnlineCpuLeavesMesasDefault() {
    unsetenv("LP_NUM_THREADS");
    if (CPU_COUNT(&original_) < sysconf(_SC_NPROCESSORS_ONLN)) QSKIP("this process is already pinned");
    QCOMPARE(fovea::viz::matchSoftwareRasterizerToAffinity(), 0);
    QVERIFY(qgetenv("LP_NUM_THREADS").isEmpty());
  }
};

QTEST_GUILESS_MAIN(TestSoftwareGl)

}  // namespace tst_software_gl
#include "tst_software_gl.moc"
