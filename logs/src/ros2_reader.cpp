/// \file
/// ROS 2 scan source over one or more storages (a rosbag2 folder's files in order, or a lone
/// .mcap or .db3). Topics are chosen by type: the scan topic (sensor_msgs/msg/LaserScan) and the
/// odometry topic (nav_msgs/msg/Odometry) when the bag has exactly one, or the one named in the
/// options; with no odometry topic, odometry comes from the odom -> base transform on /tf.
/// Every tf2_msgs/msg/TFMessage topic (/tf, /tf_static) feeds the transform buffer (ScanSync).

#include <algorithm>
#include <map>
#include <set>

#include "bag_format.hpp"
#include "bag_sync.hpp"
#include "mote/core/error.hpp"
#include "ros2_messages.hpp"
#include "ros2_reader.hpp"

namespace mote::logs::detail {
namespace {

std::string join(const std::vector<std::string>& names) {
  std::string out;
  for (const std::string& n : names) out += (out.empty() ? "'" : ", '") + n + "'";
  return out.empty() ? "none" : out;
}

}  // namespace

Ros2Source::Ros2Source(std::string name, std::vector<std::unique_ptr<Ros2Storage>> storages,
                       const ReaderOptions& options)
    : name_(std::move(name)),
      storages_(std::move(storages)),
      options_(options),
      sync_(options.odom_frame, options.base_frame) {
  for (const auto& s : storages_) {
    for (const Ros2Topic& t : s->topics()) check_topic(*s, t);
  }
  scan_topic_ = choose(Ros2Type::kLaserScan, options_.scan_topic, "--scan-topic", true);
  odom_topic_ = choose(Ros2Type::kOdometry, options_.odom_topic, "--odom-topic", false);
  if (!odom_topic_.empty()) sync_.use_odometry_topic();
}

/// A decoded type must arrive as CDR and, where the file carries a ros2msg schema, have the
/// fields the decoder reads.
void Ros2Source::check_topic(const Ros2Storage& storage, const Ros2Topic& t) {
  const Ros2Type type = ros2_type(t.type);
  if (type == Ros2Type::kOther) return;
  types_[t.name].insert(t.type);
  if (t.encoding != "cdr") {
    throw InputError(
        storage.name(), t.place,
        "topic '" + t.name + "' (" + t.type + ") is encoded as '" + t.encoding + "', expected cdr");
  }
  if (t.schema_encoding == "ros2msg") {
    if (const auto problem = schema_mismatch(type, t.schema_text)) {
      throw InputError(storage.name(), t.place,
                       "schema text of " + t.type + " does not match it: " + *problem);
    }
  }
}

std::vector<std::string> Ros2Source::candidates(Ros2Type type) const {
  std::vector<std::string> out;
  for (const auto& [topic, types] : types_) {
    for (const std::string& t : types) {
      if (ros2_type(t) == type) out.push_back(topic);
    }
  }
  return out;
}

std::string Ros2Source::choose(Ros2Type type, const std::string& option, const char* flag,
                               bool required) const {
  const std::vector<std::string> found = candidates(type);
  const std::string type_name =
      type == Ros2Type::kLaserScan ? "sensor_msgs/msg/LaserScan" : "nav_msgs/msg/Odometry";
  if (!option.empty()) {
    if (std::find(found.begin(), found.end(), option) != found.end()) return option;
    throw InputError(
        name_, "",
        "no " + type_name + " topic '" + option + "' (" + flag + "); the bag has " + join(found));
  }
  if (found.size() == 1) return found.front();
  if (found.empty() && !required) return "";
  throw InputError(name_, "topics",
                   (found.empty() ? "no " + type_name + " topic"
                                  : "several " + type_name + " topics: " + join(found) +
                                        "; choose one with " + flag));
}

std::optional<ScanFrame> Ros2Source::next() {
  while (ready_.empty() && !finished_) {
    if (std::optional<Ros2Message> m = next_message()) {
      dispatch(*m);
      (void)sync_.flush(ready_, false);
    } else {
      finish();
    }
  }
  if (ready_.empty()) return std::nullopt;
  ScanFrame frame = std::move(ready_.front());
  ready_.pop_front();
  return frame;
}

std::optional<Ros2Message> Ros2Source::next_message() {
  while (current_ < storages_.size()) {
    if (std::optional<Ros2Message> m = storages_[current_]->next()) return m;
    ++current_;
  }
  return std::nullopt;
}

void Ros2Source::finish() {
  finished_ = true;
  if (scans_ == 0 && stats().records_skipped == 0) {
    throw InputError(name_, "end of the log", "no message on the scan topic '" + scan_topic_ + "'");
  }
  if (!sync_.flush(ready_, true)) {
    std::vector<std::string> parents(tf_parents_.begin(), tf_parents_.end());
    throw InputError(name_, "end of the log",
                     "scans without odometry: no nav_msgs/msg/Odometry topic and no tf "
                     "transform from '" +
                         options_.odom_frame +
                         "' (--odom-frame); parent frames on tf: " + join(parents));
  }
}

void Ros2Source::dispatch(const Ros2Message& m) {
  const Ros2Storage& storage = *storages_[current_];
  const Ros2Topic& topic = storage.topics()[m.topic];
  const Ros2Type type = ros2_type(topic.type);
  const bool used = (type == Ros2Type::kLaserScan && topic.name == scan_topic_) ||
                    (type == Ros2Type::kOdometry && topic.name == odom_topic_) ||
                    type == Ros2Type::kTf;
  if (!used) {
    ++own_.records_ignored;
    return;
  }
  try {
    decode(type, m.data);
    ++own_.records_read;
  } catch (const BagDecodeError& e) {
    const std::string where = m.place + ", byte " + std::to_string(e.offset) + " of the message";
    const std::string problem = topic.name + " (" + topic.type + "): " + e.problem;
    if (!options_.lenient) throw InputError(storage.name(), where, problem);
    ++own_.records_skipped;
    own_.bytes_skipped += m.data.size();
    if (own_.first_error.empty())
      own_.first_error = InputError(storage.name(), where, problem).what();
  }
}

void Ros2Source::decode(Ros2Type type, std::string_view data) {
  if (type == Ros2Type::kLaserScan) {
    sync_.add_scan(decode_laser_scan_cdr(data));
    ++scans_;
  } else if (type == Ros2Type::kOdometry) {
    sync_.add_odometry(decode_odometry_cdr(data));
  } else {
    const std::vector<TransformMessage> transforms = decode_tf_cdr(data);
    for (const TransformMessage& t : transforms) {
      tf_parents_.insert(t.parent);
      if (t.parent == options_.odom_frame) note_base_candidate(t.child);
    }
    sync_.add_transforms(transforms);
  }
}

/// With odometry from tf and no --base-frame, the base is the child of the odometry frame; two
/// of them (odom -> base_link and odom -> base_footprint) would interleave their poses.
void Ros2Source::note_base_candidate(const std::string& child) {
  if (!odom_topic_.empty() || !options_.base_frame.empty()) return;
  base_candidates_.insert(child);
  if (base_candidates_.size() > 1) {
    const std::vector<std::string> names(base_candidates_.begin(), base_candidates_.end());
    throw InputError(name_, "tf",
                     "several frames under '" + options_.odom_frame + "' on tf: " + join(names) +
                         "; choose one with --base-frame");
  }
}

ReadStats Ros2Source::stats() const {
  ReadStats out = own_;
  for (const auto& s : storages_) {
    const ReadStats& st = s->stats();
    out.records_skipped += st.records_skipped;
    out.bytes_skipped += st.bytes_skipped;
    if (out.first_error.empty()) out.first_error = st.first_error;
    out.warnings.insert(out.warnings.end(), st.warnings.begin(), st.warnings.end());
  }
  return out;
}

}  // namespace mote::logs::detail
