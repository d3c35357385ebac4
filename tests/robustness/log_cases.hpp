#pragma once
/// \file
/// Reading whole logs in strict and lenient mode for the catalogue, and what a cut CARMEN log
/// must give.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "catalogue.hpp"
#include "mote/logs/scan_source.hpp"

namespace mote::robustness {

/// Reads every frame of a log (the reader chosen by extension).
inline void read_log(const fs::path& file, bool lenient) {
  logs::ReaderOptions options;
  options.lenient = lenient;
  auto source = logs::open_scan_log(file, options);
  while (source->next()) {
  }
  if (!lenient) {
    EXPECT_EQ(source->stats().records_skipped, 0U) << file;
  }
}

/// Lenient mode on the same case: either the same kind of InputError (a defect that is not one
/// record: magic, no scans, no odometry), or the log is read and the skip count is non-zero
/// exactly when strict mode failed, with a first error naming the file on one line.
inline void check_lenient(const Case& c, const fs::path& file, bool strict_threw) {
  logs::ReaderOptions options;
  options.lenient = true;
  try {
    auto source = logs::open_scan_log(file, options);
    while (source->next()) {
    }
    const logs::ReadStats stats = source->stats();
    EXPECT_EQ(stats.records_skipped > 0, strict_threw) << c.name << " (lenient)";
    if (stats.records_skipped == 0) return;
    EXPECT_EQ(stats.first_error.rfind(file.string() + ": ", 0), 0U) << stats.first_error;
    EXPECT_TRUE(one_printable_line(stats.first_error)) << stats.first_error;
  } catch (const InputError& e) {
    check_error(e, file.string(), c.name + " (lenient)");
  } catch (const std::exception& e) {
    ADD_FAILURE() << c.name << " (lenient): an exception that is not InputError: " << e.what();
  }
}

/// Runs every case strictly, then leniently; returns how many failed in strict mode.
inline int run_log_cases(const std::vector<Case>& cases, const fs::path& file) {
  int errors = 0;
  for (const Case& c : cases) {
    const Outcome strict = run_case(c, file, [](const fs::path& f) { read_log(f, false); });
    check_lenient(c, file, strict.threw);
    errors += strict.threw ? 1 : 0;
  }
  return errors;
}

/// What `log` cut after `cut` bytes must give: an error when no scan line is left whole, or
/// when the cut line is a checked message (scans, ODOM, PARAM) that lost fields; otherwise the
/// cut may have left valid lines (inside a comment, an ignored message or the last number).
inline Expect carmen_cut(const std::string& log, std::size_t cut) {
  const auto fields = [](const std::string& line) {
    std::vector<std::string> out;
    std::size_t i = 0;
    while (i < line.size()) {
      while (i < line.size() && (line[i] == ' ' || line[i] == '\t' || line[i] == '\r')) ++i;
      const std::size_t start = i;
      while (i < line.size() && line[i] != ' ' && line[i] != '\t' && line[i] != '\r') ++i;
      if (i > start) out.push_back(line.substr(start, i - start));
    }
    return out;
  };
  const auto is_scan = [](const std::string& t) {
    return t == "FLASER" || t == "RLASER" || t == "ROBOTLASER1";
  };
  std::size_t scans = 0;
  for (std::size_t start = 0; start < cut;) {
    std::size_t end = log.find('\n', start);
    if (end == std::string::npos) end = log.size();
    const std::vector<std::string> full = fields(log.substr(start, end - start));
    const std::vector<std::string> kept = fields(log.substr(start, std::min(end, cut) - start));
    if (!full.empty() && !kept.empty() && kept[0] == full[0]) {
      const bool checked = is_scan(full[0]) || full[0] == "ODOM" || full[0] == "PARAM";
      if (checked && kept.size() < full.size()) return Expect::kError;
      if (is_scan(full[0]) && kept.size() == full.size()) ++scans;
    }
    start = end + 1;
  }
  return scans == 0 ? Expect::kError : Expect::kErrorOrValid;
}

}  // namespace mote::robustness
