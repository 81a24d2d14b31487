#pragma once
// Errors from the bench hardware layers, each naming the device and what went wrong.
#include <stdexcept>
#include <string>

namespace fovea::devices {

class DeviceError : public std::runtime_error {
 public:
  enum class Kind {
    NotFound,      // no device with that serial / model
    Disconnected,  // unplugged (or never opened)
    Timeout,       // the device did not answer in time
    Io,            // USB / driver error
    SoftLimit,     // a requested move leaves the axis's soft limits (nothing was sent)
    NotHomed,      // absolute moves need a homed axis
    Disabled,      // the channel (motor drive) is disabled
    Protocol,      // a malformed or unexpected reply
    Usage,         // invalid argument (NaN distance, unknown model, ...)
    Controller,    // the controller reported an error (HW_RESPONSE / HW_RICHRESPONSE)
  };
  DeviceError(Kind kind, const std::string& message) : std::runtime_error(message), kind_(kind) {}
  Kind kind() const { return kind_; }

 private:
  Kind kind_;
};

}  // namespace fovea::devices
