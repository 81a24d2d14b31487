#include "devices/transport/libusb_transport.h"

#include <libusb.h>

#include <algorithm>
#include <array>
#include <map>

#include "devices/apt/stage_models.h"
#include "devices/transport/device_error.h"
#include "devices/transport/ftdi.h"

namespace fovea::devices {
namespace {

std::string usbError(int code) {
  return libusb_error_name(code);
}

std::string stringDescriptor(libusb_device_handle* h, std::uint8_t index) {
  if (index == 0) return {};
  std::array<unsigned char, 256> buf{};
  const int n = libusb_get_string_descriptor_ascii(h, index, buf.data(), static_cast<int>(buf.size()));
  return n > 0 ? std::string(reinterpret_cast<const char*>(buf.data()), static_cast<std::size_t>(n)) : std::string();
}

// Serial without opening the device (no permission needed): sysfs of the USB port path.
std::string sysfsSerial(libusb_device* dev) {
  std::array<std::uint8_t, 8> ports{};
  const int n = libusb_get_port_numbers(dev, ports.data(), static_cast<int>(ports.size()));
  if (n <= 0) return {};
  std::string path = "/sys/bus/usb/devices/" + std::to_string(libusb_get_bus_number(dev)) + "-";
  for (int i = 0; i < n; ++i) path += (i ? "." : "") + std::to_string(ports[static_cast<std::size_t>(i)]);
  std::FILE* f = std::fopen((path + "/serial").c_str(), "r");
  if (!f) return {};
  char line[64] = {};
  const bool ok = std::fgets(line, sizeof line, f) != nullptr;
  std::fclose(f);
  if (!ok) return {};
  std::string s(line);
  while (!s.empty() && (s.back() == '\n' || s.back() == '\r')) s.pop_back();
  return s;
}

DeviceInfo describe(libusb_device* dev, const libusb_device_descriptor& desc) {
  DeviceInfo info;
  info.serial = sysfsSerial(dev);
  libusb_device_handle* h = nullptr;
  if (libusb_open(dev, &h) == 0) {
    if (info.serial.empty()) info.serial = stringDescriptor(h, desc.iSerialNumber);
    info.description = stringDescriptor(h, desc.iProduct);
    libusb_close(h);
  }
  if (auto c = apt::controllerForSerial(info.serial))
    info.model = c->name;
  else
    info.model = info.description.empty() ? "Thorlabs APT controller" : info.description;
  return info;
}

template <typename F>
void forEachThorlabs(libusb_context* ctx, F&& f) {
  libusb_device** list = nullptr;
  const ssize_t n = libusb_get_device_list(ctx, &list);
  for (ssize_t i = 0; i < n; ++i) {
    libusb_device_descriptor desc{};
    if (libusb_get_device_descriptor(list[i], &desc) != 0) continue;
    if (desc.idVendor == ftdi::kThorlabsVid && desc.idProduct == ftdi::kThorlabsPid) f(list[i], desc);
  }
  if (list) libusb_free_device_list(list, 1);
}

int control(libusb_device_handle* h, std::uint8_t request, std::uint16_t value, std::uint16_t index) {
  return libusb_control_transfer(h, ftdi::kRequestTypeOut, request, value, index, nullptr, 0, 1000);
}

}  // namespace

std::vector<DeviceInfo> enumerateUsbControllers(std::string* error) {
  std::vector<DeviceInfo> out;
  libusb_context* ctx = nullptr;
  const int rc = libusb_init(&ctx);
  if (rc != 0) {
    if (error) *error = "libusb unavailable: " + usbError(rc);
    return out;
  }
  forEachThorlabs(
      ctx, [&](libusb_device* dev, const libusb_device_descriptor& desc) { out.push_back(describe(dev, desc)); });
  libusb_exit(ctx);
  return out;
}

LibusbTransport::LibusbTransport(std::string serial) : serial_(std::move(serial)) {
  info_.serial = serial_;
  if (auto c = apt::controllerForSerial(serial_)) info_.model = c->name;
}

LibusbTransport::~LibusbTransport() {
  close();
}

void LibusbTransport::open() {
  close();
  {
    std::lock_guard lock(mutex_);
    ready_ = failed_ = disconnected_ = false;
    error_.clear();
    rx_.clear();
    tx_.clear();
  }
  stop_ = false;
  io_ = std::thread([this] { ioThread(); });
  std::unique_lock lock(mutex_);
  cv_.wait(lock, [this] { return ready_ || failed_; });
  if (failed_) {
    const std::string why = error_;
    const bool not_found = why.rfind("no Thorlabs", 0) == 0;
    lock.unlock();
    stop_ = true;
    if (io_.joinable()) io_.join();
    throw DeviceError(not_found ? DeviceError::Kind::NotFound : DeviceError::Kind::Io, why);
  }
  open_ = true;
}

void LibusbTransport::close() {
  stop_ = true;
  cv_.notify_all();
  if (io_.joinable()) io_.join();
  std::lock_guard lock(mutex_);
  open_ = false;
}

bool LibusbTransport::isOpen() const {
  std::lock_guard lock(mutex_);
  return open_ && !disconnected_;
}

void LibusbTransport::write(std::span<const std::uint8_t> bytes) {
  std::lock_guard lock(mutex_);
  if (!open_ || disconnected_)
    throw DeviceError(DeviceError::Kind::Disconnected, "controller " + serial_ + " is disconnected");
  tx_.emplace_back(bytes.begin(), bytes.end());
  cv_.notify_all();
}

std::vector<std::uint8_t> LibusbTransport::read(std::chrono::milliseconds timeout) {
  std::unique_lock lock(mutex_);
  cv_.wait_for(lock, timeout, [this] { return !rx_.empty() || disconnected_ || !open_; });
  if (rx_.empty() && (disconnected_ || !open_))
    throw DeviceError(DeviceError::Kind::Disconnected, "controller " + serial_ + " is disconnected");
  std::vector<std::uint8_t> out(rx_.begin(), rx_.end());
  rx_.clear();
  return out;
}

DeviceInfo LibusbTransport::info() const {
  std::lock_guard lock(mutex_);
  return info_;
}

void LibusbTransport::ioThread() {
  libusb_context* ctx = nullptr;
  libusb_device_handle* handle = nullptr;
  auto fail = [&](const std::string& why) {
    if (handle) libusb_close(handle);
    if (ctx) libusb_exit(ctx);
    std::lock_guard lock(mutex_);
    failed_ = true;
    error_ = why;
    cv_.notify_all();
  };
  int rc = libusb_init(&ctx);
  if (rc != 0) return fail("libusb unavailable: " + usbError(rc));
  DeviceInfo found;
  libusb_device* target = nullptr;
  forEachThorlabs(ctx, [&](libusb_device* dev, const libusb_device_descriptor& desc) {
    if (target) return;
    DeviceInfo i = describe(dev, desc);
    if (i.serial == serial_) {
      target = libusb_ref_device(dev);
      found = i;
    }
  });
  if (!target) return fail("no Thorlabs controller with serial " + serial_ + " on the USB bus");
  rc = libusb_open(target, &handle);
  libusb_unref_device(target);
  if (rc != 0) return fail("cannot open controller " + serial_ + ": " + usbError(rc) + " (udev permissions?)");
  libusb_set_auto_detach_kernel_driver(handle, 1);  // ftdi_sio may have claimed it
  if ((rc = libusb_claim_interface(handle, 0)) != 0)
    return fail("cannot claim controller " + serial_ + ": " + usbError(rc));

  // FTDI setup, in the order the APT document gives for its D2XX example.
  const ftdi::BaudDivisor baud = ftdi::baudDivisor(115200);
  const std::uint16_t port = ftdi::kInterfaceA;
  struct Step {
    std::uint8_t request;
    std::uint16_t value, index;
    int dwell_ms;
  };
  const Step steps[] = {
      {ftdi::kSetBaudRate, baud.value, static_cast<std::uint16_t>(baud.index), 0},
      {ftdi::kSetData, ftdi::kData8N1, port, 50},  // 8 data bits, no parity, 1 stop bit; pre-purge dwell
      {ftdi::kReset, ftdi::kPurgeRx, port, 0},
      {ftdi::kReset, ftdi::kPurgeTx, port, 50},  // post-purge dwell
      {ftdi::kReset, ftdi::kResetSio, port, 0},
      {ftdi::kSetFlowCtrl, 0, static_cast<std::uint16_t>(ftdi::kFlowRtsCts | port), 0},
      {ftdi::kSetModemCtrl, ftdi::kRtsHigh, port, 0},
      {ftdi::kSetLatencyTimer, 2, port, 0},
  };
  for (const auto& s : steps) {
    if ((rc = control(handle, s.request, s.value, s.index)) < 0) {
      libusb_release_interface(handle, 0);
      return fail("FTDI setup of controller " + serial_ + " failed: " + usbError(rc));
    }
    if (s.dwell_ms) std::this_thread::sleep_for(std::chrono::milliseconds(s.dwell_ms));
  }
  int max_packet = libusb_get_max_packet_size(libusb_get_device(handle), ftdi::kEndpointIn);
  if (max_packet <= 2) max_packet = static_cast<int>(ftdi::kFullSpeedPacket);
  {
    std::lock_guard lock(mutex_);
    info_ = found;
    ready_ = true;
  }
  cv_.notify_all();
  notifyEvent(TransportEvent::Connected);

  std::vector<std::uint8_t> buffer(4096);
  bool gone = false;
  while (!stop_ && !gone) {
    std::deque<std::vector<std::uint8_t>> out;
    {
      std::lock_guard lock(mutex_);
      out.swap(tx_);
    }
    for (auto& chunk : out) {
      // RTS/CTS may hold the bridge back: a timed-out transfer can be partial, so resend the rest.
      std::size_t done = 0;
      while (done < chunk.size() && !gone && !stop_) {
        int sent = 0;
        rc = libusb_bulk_transfer(handle, ftdi::kEndpointOut, chunk.data() + done,
                                  static_cast<int>(chunk.size() - done), &sent, 1000);
        done += static_cast<std::size_t>(std::max(sent, 0));
        if (rc == LIBUSB_ERROR_NO_DEVICE || rc == LIBUSB_ERROR_IO || rc == LIBUSB_ERROR_PIPE)
          gone = true;
        else if (rc != 0 && rc != LIBUSB_ERROR_TIMEOUT)
          break;  // unexpected: drop the rest of this chunk
      }
    }
    int got = 0;
    rc = libusb_bulk_transfer(handle, ftdi::kEndpointIn, buffer.data(), static_cast<int>(buffer.size()), &got, 20);
    if (rc == LIBUSB_ERROR_NO_DEVICE || rc == LIBUSB_ERROR_IO) gone = true;
    if (got > 2) {
      auto payload = ftdi::stripStatusBytes(std::span(buffer.data(), static_cast<std::size_t>(got)),
                                            static_cast<std::size_t>(max_packet));
      if (!payload.empty()) {
        std::lock_guard lock(mutex_);
        rx_.insert(rx_.end(), payload.begin(), payload.end());
        cv_.notify_all();
      }
    }
  }
  if (gone) {
    {
      std::lock_guard lock(mutex_);
      disconnected_ = true;
    }
    cv_.notify_all();
    notifyEvent(TransportEvent::Disconnected);
  } else {
    libusb_release_interface(handle, 0);
  }
  libusb_close(handle);
  libusb_exit(ctx);
}

// ---- Hot-plug monitor -----------------------------------------------------------------------------
namespace {
int LIBUSB_CALL onHotplug(libusb_context*, libusb_device*, libusb_hotplug_event, void* user) {
  static_cast<std::atomic<bool>*>(user)->store(true);  // no I/O inside the callback (libusb rule)
  return 0;
}
}  // namespace

UsbHotplugMonitor::UsbHotplugMonitor(Callback callback) : callback_(std::move(callback)) {
  hotplug_ = libusb_has_capability(LIBUSB_CAP_HAS_HOTPLUG) != 0;
  thread_ = std::thread([this] { run(); });
}

UsbHotplugMonitor::~UsbHotplugMonitor() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

void UsbHotplugMonitor::run() {
  libusb_context* ctx = nullptr;
  if (libusb_init(&ctx) != 0) return;
  libusb_hotplug_callback_handle cb = 0;
  bool registered = false;
  if (hotplug_) {
    registered =
        libusb_hotplug_register_callback(
            ctx,
            static_cast<libusb_hotplug_event>(LIBUSB_HOTPLUG_EVENT_DEVICE_ARRIVED | LIBUSB_HOTPLUG_EVENT_DEVICE_LEFT),
            LIBUSB_HOTPLUG_NO_FLAGS, ftdi::kThorlabsVid, ftdi::kThorlabsPid, LIBUSB_HOTPLUG_MATCH_ANY, onHotplug,
            &changed_, &cb) == LIBUSB_SUCCESS;
  }
  std::map<std::string, DeviceInfo> known;
  auto poll_start = std::chrono::steady_clock::now();
  while (!stop_) {
    if (registered) {
      timeval tv{0, 200000};
      libusb_handle_events_timeout_completed(ctx, &tv, nullptr);
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(200));
      if (std::chrono::steady_clock::now() - poll_start >= std::chrono::seconds(1)) {
        changed_ = true;
        poll_start = std::chrono::steady_clock::now();
      }
    }
    if (!changed_.exchange(false)) continue;
    std::map<std::string, DeviceInfo> now;
    forEachThorlabs(ctx, [&](libusb_device* dev, const libusb_device_descriptor& desc) {
      DeviceInfo i = describe(dev, desc);
      now[i.serial] = i;
    });
    for (const auto& [serial, info] : now)
      if (!known.count(serial) && callback_) callback_(TransportEvent::Connected, info);
    for (const auto& [serial, info] : known)
      if (!now.count(serial) && callback_) callback_(TransportEvent::Disconnected, info);
    known = std::move(now);
  }
  if (registered) libusb_hotplug_deregister_callback(ctx, cb);
  libusb_exit(ctx);
}

}  // namespace fovea::devices
