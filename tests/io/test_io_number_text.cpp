// Numbers to and from text: hand-written cases, and round trips of awkward doubles that must come back
// bit for bit (the tool files written for OpenVINS, Kalibr, VINS-Fusion and ORB-SLAM3 rely on it).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <random>

#include "imucal/io/number_text.hpp"

namespace imucal::io {
namespace {

TEST(NumberText, ParsesWhatLoggersWriteAndNamesWhatItRefuses) {
  EXPECT_EQ(parseNumber(" +2.5\t").value, 2.5);
  EXPECT_EQ(parseNumber("-1e-3").value, -0.001);
  EXPECT_EQ(parseNumber("").status, NumberStatus::Empty);
  EXPECT_EQ(parseNumber("  ").status, NumberStatus::Empty);
  EXPECT_EQ(parseNumber("1,5").status, NumberStatus::NotANumber);  // a decimal comma is the reader's to convert
  EXPECT_EQ(parseNumber("2.5 m/s").status, NumberStatus::NotANumber);
  EXPECT_EQ(parseNumber("++1").status, NumberStatus::NotANumber);
  EXPECT_EQ(parseNumber("1e999").status, NumberStatus::OutOfRange);
  EXPECT_TRUE(std::isnan(parseNumber("nan").value));
}

TEST(NumberText, ExactTextIsTheShortestThatReadsBackTheSameDouble) {
  EXPECT_EQ(formatExact(0.1), "0.1");
  EXPECT_EQ(formatExact(-2.5), "-2.5");
  EXPECT_EQ(formatExact(1.0), "1");
  EXPECT_EQ(formatExactReal(1.0), "1.0");
  EXPECT_EQ(formatExactReal(-3.0), "-3.0");
  EXPECT_EQ(formatExactReal(0.1), "0.1");
  EXPECT_EQ(formatExactReal(1e-20), "1e-20");
  EXPECT_EQ(formatExactReal(std::numeric_limits<double>::infinity()), "inf");
  // Doubles that 15 digits do not pin down, spread over every exponent.
  std::mt19937_64 rng(7);
  for (int i = 0; i < 20000; ++i) {
    std::uint64_t bits = rng();
    double v = 0.0;
    std::memcpy(&v, &bits, sizeof v);
    if (!std::isfinite(v)) continue;
    for (const std::string& text : {formatExact(v), formatExactReal(v)}) {
      const ParsedNumber back = parseNumber(text);
      ASSERT_EQ(back.status, NumberStatus::Ok) << text;
      std::uint64_t back_bits = 0;
      std::memcpy(&back_bits, &back.value, sizeof back_bits);
      ASSERT_EQ(back_bits, bits) << text;
    }
  }
}

TEST(NumberText, RoundedTextHidesFloatNoiseOnly) {
  EXPECT_EQ(formatRounded(0.1 + 0.05), "0.15");  // 0.15000000000000002 exactly
  EXPECT_EQ(formatRounded(123456.789, 4), "1.235e+05");
  EXPECT_EQ(formatRounded(-0.000125), "-0.000125");
}

}  // namespace
}  // namespace imucal::io
