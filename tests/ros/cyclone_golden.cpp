/// \file
/// The Cyclone DDS side of the golden tests (see cyclone_golden.hpp).

#include "cyclone_golden.hpp"

#include <dds/ddsi/ddsi_serdata.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <atomic>
#include <stdexcept>

namespace mote::ros::test {
namespace {

// Loopback only and no multicast: a CI machine may have neither a network nor multicast.
constexpr const char* kLoopbackConfig =
    "<CycloneDDS><Domain><General><Interfaces><NetworkInterface address=\"127.0.0.1\"/>"
    "</Interfaces><AllowMulticast>false</AllowMulticast></General></Domain></CycloneDDS>";

dds_entity_t check(dds_entity_t e, const char* what) {
  if (e < 0) throw std::runtime_error(std::string(what) + ": " + dds_strretcode(e));
  return e;
}

std::string unique_topic_name() {
  static std::atomic<int> counter{0};
  // The process id too: two test processes whose domain ids collide still never share a topic.
  return "mote_golden_" + std::to_string(getpid()) + "_" + std::to_string(counter++);
}

/// Takes the one sample waiting in `reader` as serialized data (the reader sits in the same
/// participant as the writer, so a write delivers it before returning).
ddsi_serdata* take_serdata(dds_entity_t reader) {
  ddsi_serdata* sd = nullptr;
  dds_sample_info_t info;
  const dds_return_t n = dds_takecdr(reader, &sd, 1, &info, DDS_ANY_STATE);
  if (n != 1)
    throw std::runtime_error("dds_takecdr: expected one sample, got " + std::to_string(n));
  return sd;
}

}  // namespace

CycloneDomain::CycloneDomain() {
  const auto id = static_cast<dds_domainid_t>(100 + getpid() % 100);
  domain_ = check(dds_create_domain(id, kLoopbackConfig), "dds_create_domain");
  participant_ = check(dds_create_participant(id, nullptr, nullptr), "dds_create_participant");
}

CycloneDomain::~CycloneDomain() {
  dds_delete(participant_);
  dds_delete(domain_);
}

CycloneChannel::CycloneChannel(const CycloneDomain& domain, const dds_topic_descriptor_t& type) {
  const std::string name = unique_topic_name();
  topic_ = check(dds_create_topic(domain.participant(), &type, name.c_str(), nullptr, nullptr),
                 "dds_create_topic");
  dds_qos_t* qos = dds_create_qos();
  dds_qset_reliability(qos, DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
  dds_qset_history(qos, DDS_HISTORY_KEEP_ALL, 0);
  writer_ = dds_create_writer(domain.participant(), topic_, qos, nullptr);
  reader_ = dds_create_reader(domain.participant(), topic_, qos, nullptr);
  dds_delete_qos(qos);
  check(writer_, "dds_create_writer");
  check(reader_, "dds_create_reader");
}

CycloneChannel::~CycloneChannel() {
  dds_delete(reader_);
  dds_delete(writer_);
  dds_delete(topic_);
}

std::string CycloneChannel::serialize(const void* sample) {
  check(dds_write(writer_, sample), "dds_write");
  ddsi_serdata* sd = take_serdata(reader_);
  sertype_ = sd->type;
  std::string bytes(ddsi_serdata_size(sd), '\0');
  ddsi_serdata_to_ser(sd, 0, bytes.size(), bytes.data());
  ddsi_serdata_unref(sd);
  return bytes;
}

void CycloneChannel::decode(std::string_view bytes,
                            const std::function<void(const void*)>& check_sample) {
  ASSERT_NE(sertype_, nullptr) << "serialize a sample first: it gives the channel its sertype";
  ddsrt_iovec_t iov;
  iov.iov_base = const_cast<char*>(bytes.data());
  iov.iov_len = bytes.size();
  ddsi_serdata* sd = ddsi_serdata_from_ser_iov(sertype_, SDK_DATA, 1, &iov, bytes.size());
  ASSERT_NE(sd, nullptr) << "Cyclone refused the bytes (from_ser_iov)";
  // dds_writecdr takes over the reference; the reader gets it as a remote sample would arrive.
  ASSERT_EQ(dds_writecdr(writer_, sd), DDS_RETCODE_OK);
  void* samples[1] = {nullptr};
  dds_sample_info_t info;
  ASSERT_EQ(dds_take(reader_, samples, &info, 1, 1), 1) << "the reader did not decode the bytes";
  EXPECT_TRUE(info.valid_data);
  check_sample(samples[0]);
  dds_return_loan(reader_, samples, 1);
}

void expect_same_bytes(const std::string& ours, const std::string& cyclone) {
  if (ours == cyclone) return;
  const auto hex = [](const std::string& b) {
    static constexpr char kHex[] = "0123456789abcdef";
    std::string out;
    for (const char c : b) {
      const auto u = static_cast<unsigned char>(c);
      out += {kHex[u >> 4U], kHex[u & 15U], ' '};
    }
    return out;
  };
  std::size_t at = 0;
  while (at < ours.size() && at < cyclone.size() && ours[at] == cyclone[at]) ++at;
  ADD_FAILURE() << "CDR bytes differ from Cyclone's at byte " << at << " (sizes " << ours.size()
                << " and " << cyclone.size() << ")\n  mote:    " << hex(ours)
                << "\n  Cyclone: " << hex(cyclone);
}

}  // namespace mote::ros::test
