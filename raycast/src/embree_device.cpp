#include "embree_device.hpp"

#include <string>

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

/// Embree calls this on the thread whose API call failed; Embree's C API is compiled C++, so
/// the exception unwinds out of that call to the mote code that made it.
void throw_embree_error(void* /*user*/, RTCError code, const char* message) {
  throw Error("Embree: " + error_name(code) + ": " + (message != nullptr ? message : ""));
}

RTCDevice create_device() {
  RTCDevice device = rtcNewDevice(nullptr);
  if (device == nullptr) {
    throw Error("Embree: cannot create a device: " + error_name(rtcGetDeviceError(nullptr)));
  }
  rtcSetDeviceErrorFunction(device, throw_embree_error, nullptr);
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
  const RTCError code = rtcGetDeviceError(embree_device());
  if (code != RTC_ERROR_NONE) throw Error(std::string("Embree: ") + what + ": " + error_name(code));
}

}  // namespace mote::detail
