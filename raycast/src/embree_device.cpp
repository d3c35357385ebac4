#include "embree_device.hpp"

#include <string>
#include <utility>

#include "mote/core/error.hpp"

namespace mote::detail {

namespace {

std::string error_name(RTCError code) {
  switch (code) {
    case RTC_ERROR_NONE:
      return "no error";
    case RTC_ERROR_INVALID_ARGUMENT:
      return "invalid argument";
    case RTC_ERROR_INVALID_OPERATION:
      return "invalid operation";
    case RTC_ERROR_OUT_OF_MEMORY:
      return "out of memory";
    case RTC_ERROR_UNSUPPORTED_CPU:
      return "unsupported CPU";
    case RTC_ERROR_CANCELLED:
      return "cancelled";
    default:
      return "unknown error";
  }
}

/// The first Embree error reported on this thread since the last check. Embree calls its
/// error callback from inside its C API (and from within its own catch handlers), so throwing
/// there would unwind through C frames: the callback only records, and check_embree() throws
/// once the call has returned to mote.
struct PendingError {
  RTCError code = RTC_ERROR_NONE;
  std::string message;
};
thread_local PendingError pending;

void record_embree_error(void* /*user*/, RTCError code, const char* message) noexcept {
  if (pending.code != RTC_ERROR_NONE) return;  // the first error explains the rest
  pending.code = code;
  try {
    pending.message = message != nullptr ? message : "";
  } catch (...) {  // out of memory for the message: the code alone must do
    pending.message.clear();
  }
}

[[noreturn]] void throw_error(const char* what, RTCError code, const std::string& message) {
  throw Error(std::string("Embree: ") + what + ": " + error_name(code) +
              (message.empty() ? "" : ": " + message));
}

RTCDevice create_device() {
  RTCDevice device = rtcNewDevice(nullptr);
  if (device == nullptr) {
    throw Error("Embree: cannot create a device: " + error_name(rtcGetDeviceError(nullptr)));
  }
  rtcSetDeviceErrorFunction(device, record_embree_error, nullptr);
  return device;
}

}  // namespace

RTCDevice embree_device() {
  // Function-local static: created once, thread-safe, released by the OS at exit (releasing it
  // from a static destructor could race TBB's own shutdown).
  static const RTCDevice device = create_device();
  return device;
}

void check_embree(const char* what) {
  const RTCError device_code = rtcGetDeviceError(embree_device());  // read and clear it too
  check_embree_thread(what);
  if (device_code != RTC_ERROR_NONE) throw_error(what, device_code, "");
}

void check_embree_thread(const char* what) {
  if (pending.code == RTC_ERROR_NONE) return;
  (void)rtcGetDeviceError(embree_device());  // clear Embree's record of it too
  const PendingError error = std::exchange(pending, PendingError{});
  throw_error(what, error.code, error.message);
}

}  // namespace mote::detail
