#pragma once
/// \file
/// The ROS 2 scan source (ros2_reader.cpp) and the openers of its storages (ros2_open.cpp).

#include <deque>
#include <map>
#include <set>

#include "bag_sync.hpp"
#include "ros2_messages.hpp"
#include "ros2_storage.hpp"

namespace mote::logs::detail {

class Ros2Source final : public ScanSource {
 public:
  /// `name` names the bag in errors (the folder or the file). Throws InputError when a decoded
  /// topic is not CDR or its schema does not match, or the scan/odometry topic is ambiguous.
  Ros2Source(std::string name, std::vector<std::unique_ptr<Ros2Storage>> storages,
             const ReaderOptions& options);

  std::optional<ScanFrame> next() override;
  [[nodiscard]] ReadStats stats() const override;
  [[nodiscard]] const std::string& scan_topic() const noexcept { return scan_topic_; }
  [[nodiscard]] const std::string& odom_topic() const noexcept { return odom_topic_; }

 private:
  void check_topic(const Ros2Storage& storage, const Ros2Topic& t);
  [[nodiscard]] std::vector<std::string> candidates(Ros2Type type) const;
  [[nodiscard]] std::string choose(Ros2Type type, const std::string& option, const char* flag,
                                   bool required) const;
  std::optional<Ros2Message> next_message();
  void dispatch(const Ros2Message& m);
  void decode(Ros2Type type, std::string_view data);
  void finish();
  void note_base_candidate(const std::string& child);

  std::string name_;
  std::vector<std::unique_ptr<Ros2Storage>> storages_;
  ReaderOptions options_;
  ScanSync sync_;
  ReadStats own_;
  std::map<std::string, std::set<std::string>> types_;  ///< decoded topics and their types
  std::set<std::string> tf_parents_;
  std::set<std::string> base_candidates_;  ///< children of the odometry frame on tf
  std::string scan_topic_;
  std::string odom_topic_;
  std::deque<ScanFrame> ready_;
  std::size_t current_ = 0;  ///< storage being read
  std::size_t scans_ = 0;
  bool finished_ = false;
};

/// The storages of a ROS 2 log: a rosbag2 folder (metadata.yaml), a .mcap or a .db3 file.
[[nodiscard]] std::vector<std::unique_ptr<Ros2Storage>> open_ros2_storages(
    const std::filesystem::path& path, const ReaderOptions& options);

}  // namespace mote::logs::detail
