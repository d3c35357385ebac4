// libFuzzer target: LocalizerConfig and NodeParams YAML (flat amcl keys or a nav2 params file),
// from memory.
#include <cstddef>
#include <cstdint>
#include <string>

#include "fuzz_support.hpp"
#include "mote/core/error.hpp"
#include "mote/engine/localizer_config.hpp"
#include "mote/engine/node_params.hpp"

namespace {

/// Whatever the loader accepts must be a valid configuration, and its warnings single lines.
void check(const mote::LoadedConfig& loaded) {
  try {
    loaded.config.validate();
  } catch (const mote::ConfigError& e) {
    mote::fuzz::finding(std::string("parse_config accepted an invalid config: ") + e.what());
  }
  for (const std::string& warning : loaded.warnings) {
    for (const char c : warning) {
      if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) {
        mote::fuzz::finding("warning is not one printable line: " + warning);
      }
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  mote::fuzz::expect_clean("fuzz.yaml", [&] { check(mote::parse_config(text, "fuzz.yaml")); });
  mote::fuzz::expect_clean("fuzz.yaml", [&] { (void)mote::parse_node_params(text, "fuzz.yaml"); });
  return 0;
}
