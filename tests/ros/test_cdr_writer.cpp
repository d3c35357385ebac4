#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cdr.hpp"
#include "cdr_writer.hpp"
#include "mote/core/error.hpp"

namespace mote::ros::detail {
namespace {

using logs::detail::CdrReader;

TEST(CdrWriter, StartsWithThePlainLittleEndianHeader) {
  CdrWriter w;
  w.u32(7);
  const std::string bytes = std::move(w).finish();
  EXPECT_EQ(bytes, std::string("\x00\x01\x00\x00\x07\x00\x00\x00", 8));
}

TEST(CdrWriter, AlignsEachFieldToItsSizeAfterTheHeader) {
  CdrWriter w;
  w.u8(0xab);
  w.f64(1.0);  // 7 padding bytes: offset 1 -> 8 counted from the end of the header
  w.u8(0xcd);
  w.f32(2.0F);  // 3 padding bytes
  EXPECT_EQ(w.size(), 4U + 8U + 8U + 4U + 4U);
  const std::string bytes = std::move(w).finish();
  CdrReader r(bytes);
  EXPECT_EQ(static_cast<unsigned char>(bytes[4]), 0xab);
  EXPECT_EQ(bytes.substr(5, 7), std::string(7, '\0'));
  r.skip(1, 1, "u8");
  EXPECT_EQ(r.f64("f64"), 1.0);
  r.skip(1, 1, "u8");
  EXPECT_EQ(r.f32("f32"), 2.0F);
  EXPECT_NO_THROW(r.expect_end("test"));
}

TEST(CdrWriter, PadsToFourBytesAndCountsThePaddingInTheOptions) {
  CdrWriter w;
  w.string("ab");  // 4 + 3 bytes: one byte of padding
  const std::string bytes = std::move(w).finish();
  ASSERT_EQ(bytes.size(), 12U);
  EXPECT_EQ(bytes[3], '\x01');
  EXPECT_EQ(bytes.back(), '\0');
  CdrReader r(bytes);
  EXPECT_EQ(r.string("s"), "ab");
  EXPECT_NO_THROW(r.expect_end("test"));
}

TEST(CdrWriter, WritesWhatTheReaderReads) {
  CdrWriter w;
  w.i32(-5);
  w.string("");
  w.f64(-0.0);
  w.f32_sequence(std::vector<float>{1.5F, NAN, -INFINITY});
  w.i8_sequence(3, [](std::size_t k) { return static_cast<std::int8_t>(100 - 101 * int(k)); });
  const std::string bytes = std::move(w).finish();
  CdrReader r(bytes);
  EXPECT_EQ(r.i32("i32"), -5);
  EXPECT_EQ(r.string("empty"), "");
  const double zero = r.f64("f64");
  EXPECT_TRUE(zero == 0.0 && std::signbit(zero));
  ASSERT_EQ(r.sequence("floats", 4), 3U);
  EXPECT_EQ(r.f32("f"), 1.5F);
  EXPECT_TRUE(std::isnan(r.f32("f")));
  EXPECT_EQ(r.f32("f"), -INFINITY);
  ASSERT_EQ(r.sequence("bytes", 1), 3U);
  EXPECT_EQ(bytes.substr(r.position(), 3), std::string("\x64\xff\x9a", 3));
}

TEST(CdrWriter, RefusesWhatCdrCannotCarry) {
  CdrWriter w;
  EXPECT_THROW(w.string(std::string("a\0b", 3)), ConfigError);
  EXPECT_THROW(w.sequence(std::size_t{1} << 32U), ConfigError);
}

}  // namespace
}  // namespace mote::ros::detail
