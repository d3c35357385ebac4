#pragma once
/// \file
/// Cyclone DDS as the reference for the golden tests: it serializes idlc-generated samples (what
/// a ROS 2 node on rmw_cyclonedds puts on the wire for the same IDL) and decodes CDR bytes into
/// them through a real reader. Everything runs in one participant of a loopback-only domain
/// whose id comes from the process id, so parallel test runs do not meet.

#include <dds/dds.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "mote/core/pose.hpp"
#include "mote/ros/messages.hpp"

namespace mote::ros::test {

/// One domain and participant; deleted with everything in it at destruction.
class CycloneDomain {
 public:
  CycloneDomain();
  ~CycloneDomain();
  CycloneDomain(const CycloneDomain&) = delete;
  CycloneDomain& operator=(const CycloneDomain&) = delete;

  [[nodiscard]] dds_entity_t participant() const noexcept { return participant_; }

 private:
  dds_entity_t domain_ = 0;
  dds_entity_t participant_ = 0;
};

/// A topic of one idlc type with a writer and a reader on it.
class CycloneChannel {
 public:
  CycloneChannel(const CycloneDomain& domain, const dds_topic_descriptor_t& type);
  ~CycloneChannel();
  CycloneChannel(const CycloneChannel&) = delete;
  CycloneChannel& operator=(const CycloneChannel&) = delete;

  /// The bytes Cyclone serializes `sample` (of the channel's type) to: the serdata a write
  /// makes, taken back from the reader as CDR (encapsulation header included).
  [[nodiscard]] std::string serialize(const void* sample);
  /// Delivers CDR bytes as a sample from the wire would arrive (a serdata made from them with
  /// the type's from_ser) and takes it from the reader as the idlc type; `check` sees the
  /// sample. Fails the test when Cyclone refuses the bytes.
  void decode(std::string_view bytes, const std::function<void(const void*)>& check);

 private:
  dds_entity_t topic_ = 0;
  dds_entity_t writer_ = 0;
  dds_entity_t reader_ = 0;
  const struct ddsi_sertype* sertype_ = nullptr;
};

/// A test suite that shares one domain between its tests (created once: a domain costs threads
/// and sockets). When Cyclone cannot create it, every test of the suite fails with the reason.
class CycloneTest : public ::testing::Test {
 public:
  static void SetUpTestSuite() {
    try {
      domain_ = std::make_unique<CycloneDomain>();
    } catch (const std::exception& e) {
      setup_error_ = e.what();
    }
  }
  static void TearDownTestSuite() { domain_.reset(); }

 protected:
  static const CycloneDomain& domain() {
    if (!domain_) throw std::runtime_error("no Cyclone DDS domain: " + setup_error_);
    return *domain_;
  }

 private:
  static inline std::unique_ptr<CycloneDomain> domain_;
  static inline std::string setup_error_;
};

/// Expects equal bytes; on a difference prints the first differing offset and both messages in
/// hex.
void expect_same_bytes(const std::string& ours, const std::string& cyclone);

/// An idlc string field pointing at `s` (Cyclone only reads it when writing).
inline char* idl_string(const std::string& s) { return const_cast<char*>(s.c_str()); }

/// An idlc sequence (any dds_sequence_* type) over the elements of `v`, which it does not own.
template <class Sequence, class T>
Sequence idl_sequence(std::vector<T>& v) {
  Sequence s{};
  s._maximum = static_cast<std::uint32_t>(v.size());
  s._length = s._maximum;
  s._buffer = v.data();
  s._release = false;
  return s;
}

/// The quaternion of a rotation by `yaw` about z, (x, y, z, w).
inline std::array<double, 4> yaw_quaternion(double yaw) {
  return {0.0, 0.0, std::sin(0.5 * yaw), std::cos(0.5 * yaw)};
}

}  // namespace mote::ros::test
