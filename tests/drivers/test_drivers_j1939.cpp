// J1939 frames with known values, identifier parsing, pairing into IMU samples, and candump parsing.
#include <gtest/gtest.h>

#include "scratch_dir.hpp"

#include <cmath>
#include <limits>

#include "imucal/core/units.hpp"
#include "imucal/drivers/candump.hpp"
#include "imucal/drivers/emulation/j1939_emulation.hpp"
#include "imucal/drivers/j1939.hpp"
#include "imucal/drivers/j1939_config_file.hpp"
#include "imucal/drivers/j1939_imu.hpp"
#include "imucal/io/errors.hpp"

namespace imucal::drivers {
namespace {

using namespace j1939;
constexpr std::array<FigureOfMerit, 3> kGood{FigureOfMerit::FullyFunctional, FigureOfMerit::FullyFunctional, FigureOfMerit::FullyFunctional};

CanFrame frame(std::uint32_t pgn, std::uint8_t source, const std::array<std::uint8_t, 8>& data, std::int64_t utime) {
  CanFrame f;
  f.utime = utime;
  f.id = encodeIdentifier({3, pgn, 0xFF, source});
  f.extended = true;
  f.length = 8;
  f.data = data;
  return f;
}

TEST(DriversJ1939, IdentifierPdu2AndPdu1) {
  // Priority 3, PGN 0xF02A (PDU2: PS is the group extension), source 0xE2.
  Identifier id = parseIdentifier(0x0CF02AE2);
  EXPECT_EQ(id.priority, 3);
  EXPECT_EQ(id.pgn, kPgnAngularRate);
  EXPECT_EQ(id.source, 0xE2);
  EXPECT_EQ(id.destination, 0xFF);
  EXPECT_EQ(encodeIdentifier(id), 0x0CF02AE2u);
  // PDU1: PGN 0xEF00 (proprietary A) to destination 0x17 from 0x80; the PS byte is not in the PGN.
  id = parseIdentifier(0x18EF1780);
  EXPECT_EQ(id.priority, 6);
  EXPECT_EQ(id.pgn, 0xEF00u);
  EXPECT_EQ(id.destination, 0x17);
  EXPECT_EQ(id.source, 0x80);
  EXPECT_EQ(encodeIdentifier(id), 0x18EF1780u);
  // The data-page bit is part of the PGN.
  id = parseIdentifier(0x19F02AE2);
  EXPECT_EQ(id.pgn, 0x1F02Au);
}

TEST(DriversJ1939, KnownFramesDecode) {
  // Zero rates and 5 ms latency: 0x7D00 = 32000 counts = 32000 / 128 - 250 = 0 deg/s.
  const AngularRate r = decodeAngularRate({0x00, 0x7D, 0x00, 0x7D, 0x00, 0x7D, 0x00, 0x0A});
  EXPECT_EQ(r.pitch.state, ValueState::Valid);
  EXPECT_DOUBLE_EQ(r.pitch.si, 0.0);
  EXPECT_DOUBLE_EQ(r.yaw.si, 0.0);
  ASSERT_TRUE(r.latency_s);
  EXPECT_DOUBLE_EQ(*r.latency_s, 0.005);
  // 1 g up on the vertical axis: 0x80D5 = 32981 counts = 329.81 - 320 = 9.81 m/s^2.
  const Acceleration a = decodeAcceleration({0x00, 0x7D, 0x00, 0x7D, 0xD5, 0x80, 0x00, 0xFF});
  EXPECT_NEAR(a.vertical.si, 9.81, 1e-12);
  EXPECT_NEAR(a.lateral.si, 0.0, 1e-12);
  // Range ends: 0 counts = -250 deg/s, 0xFAFF = 64255 counts = 251.99 deg/s.
  EXPECT_NEAR(decode16(0x0000, units::deg / 128, -250 * units::deg).si / units::deg, -250.0, 1e-12);
  EXPECT_NEAR(decode16(0xFAFF, units::deg / 128, -250 * units::deg).si / units::deg, 64255.0 / 128 - 250, 1e-12);
  // Figures of merit: byte 7 bits 1-2, 3-4, 5-6.
  const AngularRate m = decodeAngularRate({0, 0x7D, 0, 0x7D, 0, 0x7D, 0b00100100, 0xFF});
  EXPECT_EQ(m.merit[0], FigureOfMerit::FullyFunctional);
  EXPECT_EQ(m.merit[1], FigureOfMerit::Degraded);
  EXPECT_EQ(m.merit[2], FigureOfMerit::Error);
  EXPECT_FALSE(m.latency_s) << "0xFF is not available";
}

TEST(DriversJ1939, EncodeThenDecodeIsTheSameWithinHalfABit) {
  const double rate_bit = units::deg / 128.0;
  for (double v : {-4.36, -0.0123, 0.0, 0.5, 1.2345, 4.36}) {  // rad/s, within +-250 deg/s = +-4.363 rad/s
    const AngularRate r = decodeAngularRate(encodeAngularRate(v, -v, 0.5 * v, kGood, 0.0125));
    EXPECT_NEAR(r.pitch.si, v, 0.5 * rate_bit + 1e-12);
    EXPECT_NEAR(r.roll.si, -v, 0.5 * rate_bit + 1e-12);
    EXPECT_NEAR(r.yaw.si, 0.5 * v, 0.5 * rate_bit + 1e-12);
    EXPECT_DOUBLE_EQ(*r.latency_s, 0.0125);
  }
  for (double v : {-319.0, -9.80665, 0.0, 0.004, 12.3456, 300.0}) {
    const Acceleration a = decodeAcceleration(encodeAcceleration(v, -v, v / 2, kGood));
    EXPECT_NEAR(a.lateral.si, v, 0.005 + 1e-9);
    EXPECT_NEAR(a.longitudinal.si, -v, 0.005 + 1e-9);
    EXPECT_NEAR(a.vertical.si, v / 2, 0.005 + 1e-9);
  }
}

TEST(DriversJ1939, NotAvailableErrorAndReservedCodesAreFlaggedNotNumbers) {
  const double s = 0.01, o = -320.0;
  EXPECT_EQ(decode16(0xFFFF, s, o).state, ValueState::NotAvailable);
  EXPECT_EQ(decode16(0xFF00, s, o).state, ValueState::NotAvailable);
  EXPECT_EQ(decode16(0xFE00, s, o).state, ValueState::Error);
  EXPECT_EQ(decode16(0xFEFF, s, o).state, ValueState::Error);
  EXPECT_EQ(decode16(0xFB00, s, o).state, ValueState::Reserved);
  EXPECT_EQ(decode16(0xFAFF, s, o).state, ValueState::Valid);
  EXPECT_EQ(encode16(std::nan(""), s, o), 0xFFFF);
  EXPECT_EQ(encode16(400.0, s, o), 0xFE00) << "out of range is sent as the error indicator";
}

TEST(DriversJ1939, PairsRateAndAccelerationIntoOneFrdSample) {
  J1939ImuConfig c;
  c.source_address = 0xE2;
  J1939Imu imu(c);
  // Body FRD truth: rates p, q, r and specific force f; J1939 axes are x forward, y left, z up.
  const Vec3 w(0.1, -0.2, 0.7), f(0.3, -0.4, -9.7);
  const auto ari = encodeAngularRate(-w.y(), w.x(), -w.z(), kGood, 0.002);   // pitch about y(left), roll about x, yaw about z(up)
  const auto accs = encodeAcceleration(-f.y(), f.x(), -f.z(), kGood);        // lateral, longitudinal, vertical
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0xE2, ari, 1'000'000)));
  const auto r = imu.add(frame(kPgnAcceleration, 0xE2, accs, 1'000'900));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->utime, 1'000'000 - 2'000) << "stamped at the rate frame minus its reported latency";
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(r->gyro[i], w[i], 0.5 * units::deg / 128 + 1e-12) << i;
    EXPECT_NEAR(r->accel[i], f[i], 0.005 + 1e-9) << i;
  }
  EXPECT_TRUE(std::isnan(r->temperature_c));
  EXPECT_EQ(imu.counters().get(J1939Counter::samples), 1u);
}

// Found by fuzz_j1939: the pairing took the difference of two stamps, which overflowed (and then paired
// frames 2^64 us apart) for stamps at the ends of the int64 range.
TEST(DriversJ1939, StampsAtTheEndsOfTheRangeAreNotPaired) {
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
  constexpr std::int64_t kMax = std::numeric_limits<std::int64_t>::max();
  J1939Imu imu{J1939ImuConfig{}};
  const auto ari = encodeAngularRate(0.0, 0.0, 0.0, kGood, std::nullopt);
  const auto accs = encodeAcceleration(0.0, 0.0, 9.81, kGood);
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0xE2, ari, kMin + 10)));
  EXPECT_FALSE(imu.add(frame(kPgnAcceleration, 0xE2, accs, kMax - 10)));
  EXPECT_EQ(imu.counters().get(J1939Counter::unpaired), 1u);
  EXPECT_EQ(imu.counters().get(J1939Counter::samples), 0u);
}

// The latency is subtracted without going below the smallest stamp.
TEST(DriversJ1939, LatencyIsNotSubtractedPastTheSmallestStamp) {
  constexpr std::int64_t kMin = std::numeric_limits<std::int64_t>::min();
  J1939Imu imu{J1939ImuConfig{}};
  const auto ari = encodeAngularRate(0.0, 0.0, 0.0, kGood, 0.002);
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0xE2, ari, kMin + 1000)));
  const auto r = imu.add(frame(kPgnAcceleration, 0xE2, encodeAcceleration(0.0, 0.0, 9.81, kGood), kMin + 1500));
  ASSERT_TRUE(r);
  EXPECT_EQ(r->utime, kMin);
}

TEST(DriversJ1939, SourceFilterWrongPgnAndUnusableValues) {
  J1939ImuConfig c;
  c.source_address = 0xE2;
  J1939Imu imu(c);
  const auto ari = encodeAngularRate(0.1, 0.2, 0.3, kGood, std::nullopt);
  const auto accs = encodeAcceleration(0.0, 0.0, 9.8, kGood);
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0x17, ari, 0)));
  EXPECT_FALSE(imu.add(frame(kPgnAcceleration, 0x17, accs, 10)));
  EXPECT_EQ(imu.counters().get(J1939Counter::other_source), 2u);
  EXPECT_FALSE(imu.add(frame(65265, 0xE2, accs, 20)));  // CCVS, vehicle speed: not ours
  EXPECT_EQ(imu.counters().get(J1939Counter::other_pgn), 1u);

  // Not available on one axis: the pair is dropped, nothing is published as a number.
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0xE2, encodeAngularRate(0.1, std::nan(""), 0.3, kGood, std::nullopt), 1000)));
  EXPECT_FALSE(imu.add(frame(kPgnAcceleration, 0xE2, accs, 1100)));
  EXPECT_EQ(imu.counters().get(J1939Counter::not_available), 1u);
  // Error indicator.
  auto bad = accs;
  bad[4] = 0x00;
  bad[5] = 0xFE;
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0xE2, ari, 2000)));
  EXPECT_FALSE(imu.add(frame(kPgnAcceleration, 0xE2, bad, 2100)));
  EXPECT_EQ(imu.counters().get(J1939Counter::error_indicator), 1u);
  // A figure of merit "error" with a valid number: not used; "degraded": used, counted.
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0xE2, encodeAngularRate(0.1, 0.2, 0.3, {FigureOfMerit::Error, FigureOfMerit::FullyFunctional, FigureOfMerit::FullyFunctional}, std::nullopt), 3000)));
  EXPECT_FALSE(imu.add(frame(kPgnAcceleration, 0xE2, accs, 3100)));
  EXPECT_EQ(imu.counters().get(J1939Counter::merit_error), 1u);
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0xE2, encodeAngularRate(0.1, 0.2, 0.3, {FigureOfMerit::Degraded, FigureOfMerit::FullyFunctional, FigureOfMerit::FullyFunctional}, std::nullopt), 4000)));
  EXPECT_TRUE(imu.add(frame(kPgnAcceleration, 0xE2, accs, 4100)));
  EXPECT_EQ(imu.counters().get(J1939Counter::merit_degraded), 1u);
  // A short frame.
  CanFrame s = frame(kPgnAngularRate, 0xE2, ari, 5000);
  s.length = 6;
  EXPECT_FALSE(imu.add(s));
  EXPECT_EQ(imu.counters().get(J1939Counter::bad_length), 1u);
  // Frames too far apart do not pair.
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0xE2, ari, 10'000)));
  EXPECT_FALSE(imu.add(frame(kPgnAcceleration, 0xE2, accs, 30'000)));
  EXPECT_EQ(imu.counters().get(J1939Counter::unpaired), 1u);
  EXPECT_EQ(imu.counters().get(J1939Counter::samples), 1u);
}

// Cycle k of a 100 Hz sensor whose yaw rate is k/100 rad/s and vertical acceleration 9 + k/10 m/s^2, so a
// published sample names the cycles its two frames came from.
struct Cycle {
  int k;
  std::int64_t rate_utime, accel_utime;
};
std::optional<ImuReading> feedCycle(J1939Imu& imu, const Cycle& c, bool rate_first) {
  const auto ari = encodeAngularRate(0.0, 0.0, 0.01 * c.k, kGood, std::nullopt);
  const auto accs = encodeAcceleration(0.0, 0.0, 9.0 + 0.1 * c.k, kGood);
  const CanFrame r = frame(kPgnAngularRate, 0xE2, ari, c.rate_utime), a = frame(kPgnAcceleration, 0xE2, accs, c.accel_utime);
  const auto first = imu.add(rate_first ? r : a);
  EXPECT_FALSE(first) << "cycle " << c.k << ": a sample from the first frame of a pair";
  return imu.add(rate_first ? a : r);
}
int rateCycle(const ImuReading& s) { return static_cast<int>(std::lround(-s.gyro.z() / 0.01)); }
int accelCycle(const ImuReading& s) { return static_cast<int>(std::lround((-s.accel.z() - 9.0) / 0.1)); }

// Found in the VM on a loaded host: a pair split by 6 ms (window 5 ms) left its acceleration frame
// waiting, and the next cycle's rate frame 4 ms later completed it, publishing the rate of one instant
// with the acceleration of the one before.
TEST(DriversJ1939, APairSplitWiderThanTheWindowIsNotCompletedByTheNextCycle) {
  J1939Imu imu{J1939ImuConfig{}};
  for (int k = 0; k < 3; ++k) {
    const auto s = feedCycle(imu, {k, k * 10'000, k * 10'000 + 200}, true);
    ASSERT_TRUE(s) << k;
    EXPECT_EQ(rateCycle(*s), k);
    EXPECT_EQ(accelCycle(*s), k);
  }
  EXPECT_FALSE(feedCycle(imu, {3, 30'000, 36'000}, true)) << "6 ms apart: not a pair";
  const auto s = feedCycle(imu, {4, 40'000, 40'200}, true);
  ASSERT_TRUE(s);
  EXPECT_EQ(rateCycle(*s), 4);
  EXPECT_EQ(accelCycle(*s), 4) << "the late acceleration of cycle 3 must not complete cycle 4's rate";
  EXPECT_EQ(imu.counters().get(J1939Counter::unpaired), 2u) << "cycle 3's rate (window) and its acceleration (orphaned)";
  EXPECT_EQ(imu.counters().get(J1939Counter::samples), 4u);
}

// A sensor that sends the acceleration first is learned as such; when its order changes, a few cycles are
// lost as orphans, the order is forgotten and relearned, and no sample ever mixes two cycles.
TEST(DriversJ1939, TheFrameOrderIsLearnedAndRelearnedWhenItChanges) {
  J1939Imu imu{J1939ImuConfig{}};
  std::vector<int> published;
  for (int k = 0; k < 12; ++k) {
    const bool rate_first = k >= 5;
    const std::int64_t t = k * 10'000;
    const auto s = feedCycle(imu, {k, rate_first ? t : t + 200, rate_first ? t + 200 : t}, rate_first);
    if (!s) continue;
    EXPECT_EQ(rateCycle(*s), accelCycle(*s)) << "a sample mixing two cycles at k = " << k;
    published.push_back(rateCycle(*s));
  }
  EXPECT_EQ(published, (std::vector<int>{0, 1, 2, 3, 4, 9, 10, 11}));
}

// The same split in the first cycles, before the order is known: the frames kept from broken pairs
// complete two pairs that are dropped, and the first sample published is a whole cycle.
TEST(DriversJ1939, ASplitPairBeforeTheOrderIsKnownIsNotCompletedByTheNextCycle) {
  J1939Imu imu{J1939ImuConfig{}};
  EXPECT_FALSE(feedCycle(imu, {0, 0, 6'000}, true));
  std::vector<int> published;
  for (int k = 1; k < 6; ++k) {
    const auto s = imu.add(frame(kPgnAngularRate, 0xE2, encodeAngularRate(0.0, 0.0, 0.01 * k, kGood, std::nullopt), k * 10'000));
    if (s) published.push_back(-100 * accelCycle(*s) - rateCycle(*s));  // a mix, named by its two cycles
    const auto t = imu.add(frame(kPgnAcceleration, 0xE2, encodeAcceleration(0.0, 0.0, 9.0 + 0.1 * k, kGood), k * 10'000 + 200));
    if (!t) continue;
    EXPECT_EQ(rateCycle(*t), accelCycle(*t)) << "a sample mixing two cycles at k = " << k;
    published.push_back(rateCycle(*t));
  }
  EXPECT_EQ(published, (std::vector<int>{3, 4, 5}));
}

TEST(DriversJ1939, WithoutAConfiguredSourceTheFirstSourceIsKept) {
  J1939Imu imu(J1939ImuConfig{});
  const auto ari = encodeAngularRate(0.1, 0.2, 0.3, kGood, std::nullopt);
  const auto accs = encodeAcceleration(0.0, 0.0, 9.8, kGood);
  EXPECT_FALSE(imu.add(frame(kPgnAngularRate, 0x33, ari, 0)));
  EXPECT_FALSE(imu.add(frame(kPgnAcceleration, 0x44, accs, 100)));
  EXPECT_TRUE(imu.add(frame(kPgnAcceleration, 0x33, accs, 200)));
  EXPECT_EQ(*imu.source(), 0x33);
  EXPECT_EQ(imu.counters().get(J1939Counter::other_source), 1u);
}

TEST(DriversCandump, LogAndAsciiFormats) {
  CandumpLine l = parseCandumpLine("(1700000000.123456) vcan0 0CF02AE2#007D007D007D0005");
  ASSERT_TRUE(l.frame) << l.error;
  EXPECT_EQ(l.interface, "vcan0");
  EXPECT_EQ(l.frame->utime, 1700000000123456);
  EXPECT_TRUE(l.frame->extended);
  EXPECT_EQ(l.frame->id, 0x0CF02AE2u);
  EXPECT_EQ(l.frame->length, 8);
  EXPECT_EQ(l.frame->data[7], 0x05);
  l = parseCandumpLine(" (1700000000.500000)  can0  0CF02DE2   [8]  00 7D 00 7D D5 80 00 FF");
  ASSERT_TRUE(l.frame) << l.error;
  EXPECT_EQ(l.frame->data[4], 0xD5);
  EXPECT_EQ(l.frame->utime, 1700000000500000);
  l = parseCandumpLine("(1700000000.000001) can0 123#DEAD");
  ASSERT_TRUE(l.frame);
  EXPECT_FALSE(l.frame->extended);
  EXPECT_EQ(l.frame->length, 2);
  l = parseCandumpLine("(1700000000.000001) can0 0CF02AE2#R");
  ASSERT_TRUE(l.frame);
  EXPECT_TRUE(l.frame->remote);
  EXPECT_FALSE(parseCandumpLine("").frame);
  EXPECT_TRUE(parseCandumpLine("   ").error.empty());
}

// Feeds every frame of a log to the decoder; the number of samples it made.
int decodeAll(J1939Imu& imu, const CandumpLog& log) {
  int samples = 0;
  for (const auto& f : log.frames) samples += imu.add(f.frame) ? 1 : 0;
  return samples;
}

TEST(DriversCandump, BadLinesAreReportedWithTheirLineNumbers) {
  const std::string text =
      "(1700000000.000000) vcan0 0CF02AE2#007D007D007D0005\n"
      "this is not candump output\n"
      "(1700000000.010000) vcan0 0CF02AE2#007D007D007\n"
      "(1700000000.020000) vcan0 0CF02DE2#007D007DD58000\n"
      "(1700000000.030000)  vcan0  0CF02DE2   [8]  00 7D 00 7D D5\n"
      "  vcan0  0CF02DE2   [8]  00 7D 00 7D D5 80 00 FF\n"
      "(1700000000.040000) vcan0 0CF02DE2#007D007DD58000FFAABB\n"
      "(17000x0000.05) vcan0 0CF02DE2#00\n"
      "(1700000000.060000) vcan0 0CF02DE2##1007D\n"
      "(1700000000.002000) vcan0 0CF02DE2#007D007DD58000FF\n";
  const CandumpLog log = parseCandump(text, "run.log");
  ASSERT_EQ(log.frames.size(), 3u);  // lines 1, 4 (a 7-byte frame: the decoder rejects it) and 10
  EXPECT_EQ(log.frames[0].line, 1u);
  EXPECT_EQ(log.frames[1].line, 4u);
  EXPECT_EQ(log.frames[1].frame.length, 7);
  EXPECT_EQ(log.frames[2].line, 10u);
  ASSERT_EQ(log.errors.size(), 7u);
  EXPECT_EQ(log.errors[0], "run.log:2: no time stamp (record with candump -l or -ta to replay)");
  EXPECT_EQ(log.errors[1], "run.log:3: data '007D007D007' has an odd number of hex digits (truncated?)");
  EXPECT_EQ(log.errors[2], "run.log:5: data length [8] but 5 data bytes");
  EXPECT_EQ(log.errors[3], "run.log:6: no time stamp (record with candump -l or -ta to replay)");
  EXPECT_EQ(log.errors[4], "run.log:7: data has 10 bytes, a classic CAN frame at most 8");
  EXPECT_EQ(log.errors[5], "run.log:8: time stamp '(17000x0000.05)' is not (seconds)");
  EXPECT_EQ(log.errors[6], "run.log:9: CAN FD frame (##): J1939 uses classic CAN");

  // The short frame reaches the decoder and is counted there, not published; lines 1 and 10 pair.
  J1939Imu imu(J1939ImuConfig{});
  EXPECT_EQ(decodeAll(imu, log), 1);
  EXPECT_EQ(imu.counters().get(J1939Counter::bad_length), 1u);
}

TEST(DriversCandump, TimeStampBeyondAnyClockIsABadLineNotAnOverflow) {
  // The shared reproducer: a pair of frames stamped (1e300), then a good pair. 1e300 s once overflowed
  // the conversion to int64 microseconds, and every later sample was then dropped as going backwards.
  const std::string path = imucal::testing::hostile("candump_timestamp_1e300.log");
  const CandumpLog log = readCandumpFile(path);
  ASSERT_EQ(log.errors.size(), 2u);
  EXPECT_EQ(log.errors[0], path + ":1: time stamp '(1e300)' is beyond any clock (more than 1e11 s)");
  EXPECT_EQ(log.error_lines, 2u);
  ASSERT_EQ(log.frames.size(), 2u);
  EXPECT_EQ(log.frames[0].frame.utime, 1'700'000'000'010'000);
  EXPECT_EQ(log.frames[1].frame.utime, 1'700'000'000'011'000);
  J1939Imu imu(J1939ImuConfig{});
  EXPECT_EQ(decodeAll(imu, log), 1);
  EXPECT_EQ(imu.counters().get(J1939Counter::timestamp_backwards), 0u);
}

TEST(DriversCandump, StandardIdentifierBeyond11BitsIsRefused) {
  // Found by fuzzing: "FFF" was taken as a standard frame although 11 bits end at 7FF.
  EXPECT_EQ(parseCandumpLine("(1.000000) can0 FFF#00").error, "identifier FFF is beyond the 11-bit standard range");
  EXPECT_TRUE(parseCandumpLine("(1.000000) can0 7FF#00").frame.has_value());
}

TEST(DriversCandump, GarbageIsQuotedShortAndTheErrorListBounded) {
  std::string text;
  for (int i = 0; i < 1000; ++i) text += "(" + std::string(5000, '9') + ") can0 " + std::string(3000, 'Z') + "\n";
  const CandumpLog log = parseCandump(text, "junk.log");
  EXPECT_EQ(log.error_lines, 1000u);
  ASSERT_EQ(log.errors.size(), CandumpLog::kMaxErrorsKept);
  for (const auto& e : log.errors) EXPECT_LT(e.size(), 200u) << e.substr(0, 200);
}

TEST(DriversCandump, MissingFileIsAnInputError) {
  EXPECT_THROW(readCandumpFile("/nonexistent/run.log"), io::InputError);
}

TEST(DriversJ1939, ConfigErrorsNameTheKey) {
  const J1939FileConfig c = parseJ1939Config("interface: vcan0\nsource_address: 0xE2\npair_window_ms: 3\n", "j.yaml");
  EXPECT_EQ(c.interface, "vcan0");
  EXPECT_EQ(*c.imu.source_address, 0xE2);
  EXPECT_EQ(c.imu.pair_window_us, 3000);
  try {
    parseJ1939Config("interface: vcan0\nsource_address: 0xFF\n", "j.yaml");
    FAIL();
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("j.yaml:2"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("source_address"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parseJ1939Config("interface: vcan0\nsource_adress: 0xE2\n", "j.yaml"), io::InputError);
}

// pair_window_ms: 1e300 was accepted and its microseconds overflowed the int64 window.
TEST(DriversJ1939, PairWindowMustFitMicroseconds) {
  for (const char* yaml : {"pair_window_ms: 1e300\n", "pair_window_ms: 0.0001\n"}) {
    try {
      parseJ1939Config(yaml, "j.yaml");
      ADD_FAILURE() << yaml << " was accepted";
    } catch (const io::InputError& e) {
      EXPECT_NE(std::string(e.what()).find("j.yaml:1: pair_window_ms: must be between 0.001 and 1000"), std::string::npos)
          << e.what();
    }
  }
  EXPECT_EQ(parseJ1939Config("pair_window_ms: 1000\n", "j.yaml").imu.pair_window_us, 1'000'000);
}

}  // namespace
}  // namespace imucal::drivers

namespace imucal::drivers {
namespace {

TEST(DriversJ1939, SimulatedBusRoundTripsThroughCandumpToTheSimulatedSamples) {
  const sim::SimOutput out = sim::simulate(sim::paperScenario(5.0 * units::deg, true, 3), 3);
  emulation::J1939EmulationConfig c;
  c.epoch_utime = 1'700'000'000'000'000;
  c.latency_s = 0.0025;
  std::string log;
  for (const CanFrame& f : emulation::j1939FramesFromSimulation(out, c)) log += formatCandumpLine(f, "vcan0") + "\n";
  const CandumpLog parsed = parseCandump(log, "sim.log");
  EXPECT_TRUE(parsed.errors.empty());
  J1939ImuConfig dc;
  dc.source_address = 0xE2;
  J1939Imu imu(dc);
  std::size_t k = 0;
  for (const auto& f : parsed.frames) {
    const auto r = imu.add(f.frame);
    if (!r) continue;
    ASSERT_LT(k, out.imu.size());
    EXPECT_EQ(r->utime, c.epoch_utime + std::llround(out.imu[k].t * 1e6)) << "the rate frame was sent 2.5 ms after its sample and says so";
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(r->gyro[i], out.imu[k].gyro[i], 0.5 * units::deg / 128 + 1e-12);
      EXPECT_NEAR(r->accel[i], out.imu[k].accel[i], 0.005 + 1e-9);
    }
    ++k;
  }
  EXPECT_EQ(k, out.imu.size());
}

// Found by fuzzing: at 8.74e9 s a double no longer holds a microsecond, and the frame written back read
// one microsecond off. candump's digits.digits form is now read exactly, to 1e11 s.
TEST(Candump, TimeStampsRoundTripToTheMicrosecond) {
  for (const char* stamp : {"(8740000000.002000)", "(99999999999.999999)", "(1700000000.000001)", "(0.000001)"}) {
    const CandumpLine l = parseCandumpLine(std::string(stamp) + " can0 123#0102");
    ASSERT_TRUE(l.frame) << stamp << ": " << l.error;
    EXPECT_EQ(formatCandumpLine(*l.frame, "can0").substr(0, std::string(stamp).size()), stamp);
    const CandumpLine again = parseCandumpLine(formatCandumpLine(*l.frame, "can0"));
    ASSERT_TRUE(again.frame) << stamp;
    EXPECT_EQ(again.frame->utime, l.frame->utime) << stamp;
  }
  const CandumpLine l = parseCandumpLine("(1700000000.1234565) can0 123#0102");
  ASSERT_TRUE(l.frame);
  EXPECT_EQ(l.frame->utime, 1700000000123457);  // rounded at the seventh digit
  EXPECT_FALSE(parseCandumpLine("(100000000000.5) can0 123#0102").frame);
}

}  // namespace
}  // namespace imucal::drivers
