#include "dds_endpoints.hpp"

#include <array>
#include <cstdlib>
#include <memory>

#include "mote/core/error.hpp"
#include "mote/ros/ros_names.hpp"
#include "raw_cdr_type.hpp"

#include <dds/ddsi/ddsi_serdata.h>
#include <dds/ddsi/ddsi_sertype.h>

namespace mote::ros::detail {
namespace {

// ROS 2 puts neither XTypes type information nor keys on its topics: the sertype carries the
// name and XCDR1 (raw_cdr_type.hpp), the QoS the representation, so a Fast DDS or Cyclone peer
// of any ROS 2 release matches.
struct QosDeleter {
  void operator()(dds_qos_t* q) const { dds_delete_qos(q); }
};

std::unique_ptr<dds_qos_t, QosDeleter> make_qos(TopicQos qos) {
  std::unique_ptr<dds_qos_t, QosDeleter> q(dds_create_qos());
  dds_qset_history(q.get(), DDS_HISTORY_KEEP_LAST, qos.depth);
  dds_qset_reliability(
      q.get(), qos.reliable ? DDS_RELIABILITY_RELIABLE : DDS_RELIABILITY_BEST_EFFORT, DDS_SECS(1));
  dds_qset_durability(
      q.get(), qos.transient_local ? DDS_DURABILITY_TRANSIENT_LOCAL : DDS_DURABILITY_VOLATILE);
  // A transient-local writer keeps what a late reader gets: the same depth.
  dds_qset_durability_service(q.get(), 0, DDS_HISTORY_KEEP_LAST, qos.depth, DDS_LENGTH_UNLIMITED,
                              DDS_LENGTH_UNLIMITED, DDS_LENGTH_UNLIMITED);
  const std::array<dds_data_representation_id_t, 1> xcdr1{DDS_DATA_REPRESENTATION_XCDR1};
  dds_qset_data_representation(q.get(), 1, xcdr1.data());
  return q;
}

dds_entity_t make_topic(const Participant& p, std::string_view ros_topic, std::string_view ros_type,
                        const ddsi_sertype** type_out) {
  const std::string name = dds_topic_name(ros_topic);
  ddsi_sertype* type = make_raw_cdr_type(dds_type_name(ros_type));
  const dds_entity_t topic =
      dds_create_topic_sertype(p.handle(), name.c_str(), &type, nullptr, nullptr, nullptr);
  if (topic < 0) ddsi_sertype_unref(type);
  check_dds(topic,
            "creating topic " + std::string(ros_topic) + " of type " + std::string(ros_type));
  if (type_out != nullptr) *type_out = type;
  return topic;
}

// The fully qualified ROS name, as ROS 2 prints it ("scan" -> "/scan").
std::string qualified(std::string_view ros_topic) {
  std::string name;
  if (!ros_topic.starts_with('/')) name.push_back('/');
  name.append(ros_topic);
  return name;
}

}  // namespace

dds_entity_t check_dds(dds_entity_t result, const std::string& what) {
  if (result < 0) throw Error("DDS: " + what + ": " + dds_strretcode(result));
  return result;
}

Participant::Participant(int domain_id)
    : handle_(check_dds(
          dds_create_participant(static_cast<dds_domainid_t>(domain_id), nullptr, nullptr),
          "joining domain " + std::to_string(domain_id) +
              " (check CYCLONEDDS_URI and ROS_DOMAIN_ID)")) {}

Participant::~Participant() { dds_delete(handle_); }

RawWriter::RawWriter(const Participant& participant, std::string_view ros_topic,
                     std::string_view ros_type, TopicQos qos)
    : topic_(qualified(ros_topic)) {
  const dds_entity_t topic = make_topic(participant, ros_topic, ros_type, &type_);
  const auto q = make_qos(qos);
  writer_ = check_dds(dds_create_writer(participant.handle(), topic, q.get(), nullptr),
                      "creating a writer on " + topic_);
}

RawWriter::~RawWriter() { dds_delete(writer_); }

void RawWriter::write(std::string_view cdr) const {
  ddsi_serdata* sample = make_raw_sample(type_, cdr);
  if (sample == nullptr) throw Error("DDS: out of memory for a sample on " + topic_);
  check_dds(dds_writecdr(writer_, sample), "writing to " + topic_);
}

std::size_t RawWriter::matched() const {
  dds_publication_matched_status_t status{};
  check_dds(dds_get_publication_matched_status(writer_, &status), "status of " + topic_);
  return status.current_count;
}

RawReader::RawReader(const Participant& participant, std::string_view ros_topic,
                     std::string_view ros_type, TopicQos qos)
    : topic_(qualified(ros_topic)) {
  const dds_entity_t topic = make_topic(participant, ros_topic, ros_type, nullptr);
  const auto q = make_qos(qos);
  reader_ = check_dds(dds_create_reader(participant.handle(), topic, q.get(), nullptr),
                      "creating a reader on " + topic_);
}

RawReader::~RawReader() { dds_delete(reader_); }

std::vector<std::string> RawReader::take() const {
  constexpr uint32_t kBatch = 16;
  std::vector<std::string> out;
  std::array<ddsi_serdata*, kBatch> samples{};
  std::array<dds_sample_info_t, kBatch> infos{};
  for (;;) {
    const dds_return_t n =
        dds_takecdr(reader_, samples.data(), kBatch, infos.data(), DDS_ANY_STATE);
    check_dds(n, "taking from " + topic_);
    for (dds_return_t k = 0; k < n; ++k) {
      if (infos[static_cast<std::size_t>(k)].valid_data) {
        out.emplace_back(raw_sample_bytes(samples[static_cast<std::size_t>(k)]));
      }
      ddsi_serdata_unref(samples[static_cast<std::size_t>(k)]);
    }
    if (n < static_cast<dds_return_t>(kBatch)) return out;
  }
}

std::size_t RawReader::matched() const {
  dds_subscription_matched_status_t status{};
  check_dds(dds_get_subscription_matched_status(reader_, &status), "status of " + topic_);
  return status.current_count;
}

}  // namespace mote::ros::detail

namespace mote::ros {

int ros_domain_id() {
  const char* text = std::getenv("ROS_DOMAIN_ID");
  if (text == nullptr || *text == '\0') return 0;
  char* end = nullptr;
  const long id = std::strtol(text, &end, 10);
  if (*end != '\0' || id < 0 || id > 232) {
    throw ConfigError("ROS_DOMAIN_ID is '" + std::string(text) +
                      "': expected a whole number from 0 to 232, as ROS 2 accepts");
  }
  return static_cast<int>(id);
}

}  // namespace mote::ros
