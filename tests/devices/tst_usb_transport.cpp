// The libusb/FTDI transport, as far as it can be tested without hardware: the FTDI status
// bytes removed per max-packet chunk, the baud-rate divisor encoding (AN232B-05 values), and
// enumeration / opening a missing device failing cleanly.
#include <QtTest>
#include "tests/test_batch.h"
#include "tests/test_paths.h"

#include <mutex>

#include "devices/transport/device_error.h"
#include "devices/transport/ftdi.h"
#include "devices/transport/libusb_transport.h"

namespace tst_usb_transport {

using namespace fovea::devices;
using Bytes = std::vector<std::uint8_t>;

class TestUsbTransport : public QObject {
  Q_OBJECT
 private slots:
  void stripsTwoStatusBytesPerPacket() {
    // Two 8-byte packets (max packet 8 for the test): status 31 60 then 6 payload bytes,
    // status 31 60 then 2 payload bytes.
    const Bytes transfer = {0x31, 0x60, 1, 2, 3, 4, 5, 6, 0x31, 0x60, 7, 8};
    QCOMPARE(ftdi::stripStatusBytes(transfer, 8), (Bytes{1, 2, 3, 4, 5, 6, 7, 8}));
    // A status-only packet (the chip sends one every latency period) carries nothing.
    QCOMPARE(ftdi::stripStatusBytes(Bytes{0x31, 0x60}, 64), Bytes{});
    // 64-byte packets: a 132-byte transfer = 64 + 64 + 4 bytes = 62 + 62 + 2 payload bytes.
    Bytes big(132);
    for (std::size_t i = 0; i < big.size(); ++i) big[i] = static_cast<std::uint8_t>(i);
    const Bytes out = ftdi::stripStatusBytes(big, 64);
    QCOMPARE(out.size(), std::size_t{126});
    QCOMPARE(out.front(), std::uint8_t{2});
    QCOMPARE(out[61], std::uint8_t{63});
    QCOMPARE(out[62], std::uint8_t{66});  // bytes 64, 65 were the second packet's status
    QCOMPARE(out[123], std::uint8_t{127});
    QCOMPARE(out[124], std::uint8_t{130});  // 128, 129: the third packet's status
    QCOMPARE(out.back(), std::uint8_t{131});
  }

  void baudDivisors() {
    // 115200: 3 MHz / 115200 = 26.04 -> 208 eighths -> divisor 26, fraction 0 -> 0x001A.
    auto b = ftdi::baudDivisor(115200);
    QCOMPARE(b.value, std::uint16_t{0x001A});
    QCOMPARE(b.index, std::uint16_t{0});
    QVERIFY(std::abs(b.actual_baud - 3e6 / 26) < 1e-6);
    QVERIFY(std::abs(b.actual_baud / 115200 - 1) < 0.002);  // 0.16 % is inside the UART tolerance
    // 9600: 312.5 -> 312 + 4/8, sub-integer code for 4/8 is 1 -> 312 | 1 << 14 = 0x4138 (AN232B-05).
    QCOMPARE(ftdi::baudDivisor(9600).value, std::uint16_t{0x4138});
    // 38400: 78.125 -> 78 + 1/8, code 3 -> 0xC04E.
    QCOMPARE(ftdi::baudDivisor(38400).value, std::uint16_t{0xC04E});
    // 300 baud: divisor 10000 = 0x2710, no fraction.
    QCOMPARE(ftdi::baudDivisor(300).value, std::uint16_t{0x2710});
    // Special cases: 3 MBd divisor 1 -> 0, 2 MBd divisor 1.5 -> 1.
    QCOMPARE(ftdi::baudDivisor(3000000).value, std::uint16_t{0});
    QCOMPARE(ftdi::baudDivisor(2000000).value, std::uint16_t{1});
  }

  void enumerationWithoutHardwareIsEmptyNotACrash() {
    std::string error;
    const auto list = enumerateUsbControllers(&error);
    // This machine has no Thorlabs controller; the call must still return normally.
    for (const auto& d : list) QVERIFY(!d.is_virtual);
    QVERIFY(list.empty() || !list.front().serial.empty());
  }

  void recordedDeviceEnumerates() {
    // A KDC101 described for umockdev (tests/devices/data/kdc101.umockdev: sysfs attributes
    // and descriptors of VID 0403 PID FAF0, serial 27000001). This test re-runs itself under
    // umockdev-run, which fakes /sys and /dev for libusb.
    if (qEnvironmentVariableIsSet("FOVEA_UMOCKDEV_CHILD")) {
      std::string error;
      const auto list = enumerateUsbControllers(&error);
      QVERIFY2(error.empty(), error.c_str());
      QCOMPARE(list.size(), std::size_t{1});
      QCOMPARE(list[0].serial, std::string("27000001"));
      QCOMPARE(list[0].model, std::string("KDC101"));
      // The hot-plug monitor reports the controller present at start as connected.
      std::mutex m;
      std::vector<std::string> arrived;
      {
        UsbHotplugMonitor monitor([&](TransportEvent e, const DeviceInfo& d) {
          std::lock_guard lock(m);
          if (e == TransportEvent::Connected) arrived.push_back(d.serial);
        });
        QTRY_VERIFY_WITH_TIMEOUT(
            [&] {
              std::lock_guard lock(m);
              return !arrived.empty();
            }(),
            5000);
      }
      QCOMPARE(arrived.front(), std::string("27000001"));
      return;
    }
    const QString runner = QStandardPaths::findExecutable("umockdev-run");
    if (runner.isEmpty()) QSKIP("umockdev-run is not installed (scripts/install-deps.sh)");
    QProcess p;
    QProcessEnvironment env = QProcessEnvironment::systemEnvironment();
    env.insert("FOVEA_UMOCKDEV_CHILD", "1");
    // umockdev works by LD_PRELOAD, which an ASan build must be told to accept.
    env.insert("ASAN_OPTIONS", env.value("ASAN_OPTIONS") + ":verify_asan_link_order=0");
    // This test's executable holds other tests too: it is named before the test function.
    QStringList command{QCoreApplication::applicationFilePath(), fovea::testing::currentTestName(),
                        "recordedDeviceEnumerates"};
    // The ASan tree runs this executable with the ASan runtime preloaded (tests/CMakeLists.txt,
    // FOVEA_TEST_DRIVERS). umockdev-run itself must not load it (the two preloads' start-up
    // hangs it); the child gets it back first, ahead of umockdev's own preload.
    if (env.contains("LD_PRELOAD")) {
      env.insert("FOVEA_CHILD_PRELOAD", env.value("LD_PRELOAD"));
      env.remove("LD_PRELOAD");
      command = QStringList{"/bin/sh", "-c",
                            R"(LD_PRELOAD="$FOVEA_CHILD_PRELOAD${LD_PRELOAD:+:$LD_PRELOAD}" exec "$@")", "sh"} +
                command;
    }
    p.setProcessEnvironment(env);
    p.start(runner,
            QStringList{"-d", QString(FOVEA_SOURCE_DIR) + "/tests/devices/data/kdc101.umockdev", "--"} + command);
    QVERIFY(p.waitForFinished(30000));
    const QByteArray out = p.readAllStandardOutput() + p.readAllStandardError();
    QVERIFY2(p.exitStatus() == QProcess::NormalExit && p.exitCode() == 0, out.constData());
    QVERIFY2(out.contains("PASS   : tst_usb_transport::TestUsbTransport::recordedDeviceEnumerates()"), out.constData());
  }

  void openingAMissingControllerNamesIt() {
    LibusbTransport t("27999999");
    try {
      t.open();
      QFAIL("opened a controller that does not exist");
    } catch (const DeviceError& e) {
      QVERIFY(e.kind() == DeviceError::Kind::NotFound || e.kind() == DeviceError::Kind::Io);
      QVERIFY2(std::string(e.what()).find("27999999") != std::string::npos || e.kind() == DeviceError::Kind::Io,
               e.what());
    }
    QVERIFY(!t.isOpen());
    QVERIFY_THROWS_EXCEPTION(DeviceError, t.write(Bytes{1, 2, 3}));
  }
};

QTEST_GUILESS_MAIN(TestUsbTransport)

}  // namespace tst_usb_transport
#include "tst_usb_transport.moc"
