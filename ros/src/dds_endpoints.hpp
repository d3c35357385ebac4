#pragma once
/// \file
/// A DDS participant and the raw-CDR readers and writers of ROS 2 topics on it (raw_cdr_type.hpp),
/// with the QoS nav2's nodes use. Every entity is deleted with its owner; deleting the
/// participant deletes whatever is left under it.

#include <dds/dds.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "mote/ros/dds_domain.hpp"

namespace mote::ros::detail {

/// The QoS of one topic: ROS 2's history, reliability and durability.
struct TopicQos {
  bool reliable = true;
  bool transient_local = false;  ///< late joiners get the last `depth` samples
  int depth = 10;                ///< keep last
};

/// nav2_amcl's QoS (amcl_node.cpp; the same in Humble and Jazzy).
inline constexpr TopicQos kSensorQos{.reliable = false, .transient_local = false, .depth = 5};
inline constexpr TopicQos kMapQos{.reliable = true, .transient_local = true, .depth = 1};
inline constexpr TopicQos kInitialPoseQos{.reliable = true, .transient_local = false, .depth = 1};
inline constexpr TopicQos kAmclPoseQos{.reliable = true, .transient_local = true, .depth = 1};
inline constexpr TopicQos kParticleCloudQos{
    .reliable = false, .transient_local = false, .depth = 5};
inline constexpr TopicQos kTfQos{.reliable = true, .transient_local = false, .depth = 100};
inline constexpr TopicQos kTfStaticQos{.reliable = true, .transient_local = true, .depth = 100};
/// rclcpp's default (SystemDefaultsQoS / KeepLast 10, reliable, volatile).
inline constexpr TopicQos kDefaultQos{};

/// Throws mote::Error naming `what` when a Cyclone call returned a negative code.
dds_entity_t check_dds(dds_entity_t result, const std::string& what);

/// A DDS domain participant. Discovery and interfaces follow CYCLONEDDS_URI, as every ROS 2
/// node on rmw_cyclonedds does.
class Participant {
 public:
  /// Joins `domain_id` (ROS_DOMAIN_ID). Throws mote::Error when Cyclone cannot start.
  explicit Participant(int domain_id);
  ~Participant();
  Participant(const Participant&) = delete;
  Participant& operator=(const Participant&) = delete;
  [[nodiscard]] dds_entity_t handle() const noexcept { return handle_; }

 private:
  dds_entity_t handle_;
};

/// Writes serialized messages of one type to one ROS 2 topic.
class RawWriter {
 public:
  RawWriter(const Participant& participant, std::string_view ros_topic, std::string_view ros_type,
            TopicQos qos);
  ~RawWriter();
  RawWriter(const RawWriter&) = delete;
  RawWriter& operator=(const RawWriter&) = delete;
  /// Publishes one message: the 4-byte CDR header and the message. Throws mote::Error.
  void write(std::string_view cdr) const;
  /// Readers matched so far.
  [[nodiscard]] std::size_t matched() const;
  [[nodiscard]] const std::string& topic() const noexcept { return topic_; }

 private:
  std::string topic_;
  dds_entity_t writer_ = 0;
  const struct ddsi_sertype* type_ = nullptr;
};

/// Reads serialized messages of one type from one ROS 2 topic.
class RawReader {
 public:
  RawReader(const Participant& participant, std::string_view ros_topic, std::string_view ros_type,
            TopicQos qos);
  ~RawReader();
  RawReader(const RawReader&) = delete;
  RawReader& operator=(const RawReader&) = delete;
  /// Takes every message that has arrived, oldest first (each one's CDR bytes).
  [[nodiscard]] std::vector<std::string> take() const;
  /// Writers matched so far.
  [[nodiscard]] std::size_t matched() const;
  [[nodiscard]] dds_entity_t handle() const noexcept { return reader_; }
  [[nodiscard]] const std::string& topic() const noexcept { return topic_; }

 private:
  std::string topic_;
  dds_entity_t reader_ = 0;
};

}  // namespace mote::ros::detail
