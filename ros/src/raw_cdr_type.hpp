#pragma once
/// \file
/// A Cyclone DDS type whose samples are the serialized bytes themselves: the 4-byte CDR
/// encapsulation header and the message, exactly what rmw_cyclonedds and rmw_fastrtps put on the
/// wire and what a rosbag2 file stores. With it mote publishes a recorded message unchanged and
/// hands a received one to logs/'s decoders, and needs no generated code per message type.
/// ROS 2 topics are keyless and matched by type name only (no XTypes information is sent), so
/// the type is a name and XCDR1, nothing more.

#include <dds/dds.h>

#include <cstddef>
#include <string>
#include <string_view>

namespace mote::ros::detail {

/// A new sertype for the DDS type name `dds_type` ("sensor_msgs::msg::dds_::LaserScan_"), to be
/// handed to dds_create_topic_sertype (which takes the reference and may swap it for an equal,
/// already registered one).
[[nodiscard]] struct ddsi_sertype* make_raw_cdr_type(const std::string& dds_type);

/// A serialized sample of `type` holding a copy of `cdr` (header included), reference count 1,
/// for dds_writecdr (which takes the reference).
[[nodiscard]] struct ddsi_serdata* make_raw_sample(const struct ddsi_sertype* type,
                                                   std::string_view cdr);

/// The bytes of a sample that dds_takecdr returned on a reader of a raw type.
[[nodiscard]] std::string_view raw_sample_bytes(const struct ddsi_serdata* sample);

}  // namespace mote::ros::detail
