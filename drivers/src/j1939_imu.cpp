#include "imucal/drivers/j1939_imu.hpp"

#include <cmath>
#include <limits>

namespace imucal::drivers {

using namespace j1939;

namespace {

// Receive times come from a socket or a log and may be anything: far-apart stamps must not overflow.
std::uint64_t distanceUs(std::int64_t a, std::int64_t b) {
  return a > b ? static_cast<std::uint64_t>(a) - static_cast<std::uint64_t>(b)
               : static_cast<std::uint64_t>(b) - static_cast<std::uint64_t>(a);
}

// Pairs in a row with the same frame order before the order is relied on, and orphans in a row (no pair
// between) before it is forgotten.
constexpr int kOrderEvidence = 3;

}  // namespace

J1939Imu::J1939Imu(const J1939ImuConfig& config)
    : config_(config),
      source_(config.source_address) {}

bool J1939Imu::acceptValues(const Value* values, const FigureOfMerit* merits) {
  bool ok = true;
  for (int i = 0; i < 3; ++i) {
    switch (values[i].state) {
      case ValueState::Valid: break;
      case ValueState::NotAvailable: counters_.increment(J1939Counter::not_available); ok = false; break;
      case ValueState::Error: counters_.increment(J1939Counter::error_indicator); ok = false; break;
      case ValueState::Reserved: counters_.increment(J1939Counter::reserved_value); ok = false; break;
    }
    // A figure of merit "not available" is what a sensor without that diagnostic sends: the value stands.
    if (merits[i] == FigureOfMerit::Error) {
      counters_.increment(J1939Counter::merit_error);
      ok = false;
    } else if (merits[i] == FigureOfMerit::Degraded) {
      counters_.increment(J1939Counter::merit_degraded);
    }
  }
  return ok;
}

std::optional<ImuReading> J1939Imu::add(const CanFrame& frame) {
  counters_.increment(J1939Counter::frames);
  if (!frame.extended || frame.remote) {
    counters_.increment(J1939Counter::not_extended);
    return std::nullopt;
  }
  const Identifier id = parseIdentifier(frame.id);
  if (id.pgn != kPgnAngularRate && id.pgn != kPgnAcceleration) {
    counters_.increment(J1939Counter::other_pgn);
    return std::nullopt;
  }
  if (!source_) source_ = id.source;
  if (id.source != *source_) {
    counters_.increment(J1939Counter::other_source);
    return std::nullopt;
  }
  if (frame.length != 8) {
    counters_.increment(J1939Counter::bad_length);
    return std::nullopt;
  }
  if (id.pgn == kPgnAngularRate) {
    dropOrphanedTrailer(Kind::Rate);
    if (rate_) counters_.increment(J1939Counter::unpaired);
    rate_ = PendingRate{frame.utime, arrivals_++, false, decodeAngularRate(frame.data)};
  } else {
    dropOrphanedTrailer(Kind::Accel);
    if (accel_) counters_.increment(J1939Counter::unpaired);
    accel_ = PendingAccel{frame.utime, arrivals_++, false, decodeAcceleration(frame.data)};
  }
  return pair();
}

void J1939Imu::dropOrphanedTrailer(Kind arriving) {
  if (!leader_ || arriving != *leader_) return;
  const bool trailer_waiting = arriving == Kind::Rate ? accel_ && !rate_ : rate_ && !accel_;
  if (!trailer_waiting) return;
  counters_.increment(J1939Counter::unpaired);
  if (arriving == Kind::Rate) accel_.reset();
  else rate_.reset();
  if (++orphans_in_a_row_ >= kOrderEvidence) {
    leader_.reset();
    order_agreeing_ = 0;
    orphans_in_a_row_ = 0;
  }
}

void J1939Imu::learnOrder(Kind first) {
  orphans_in_a_row_ = 0;
  if (first != order_candidate_) {
    order_candidate_ = first;
    order_agreeing_ = 0;
  }
  if (++order_agreeing_ >= kOrderEvidence) leader_ = first;
}

std::optional<ImuReading> J1939Imu::pair() {
  if (!rate_ || !accel_) return std::nullopt;
  if (config_.pair_window_us < 0 || distanceUs(rate_->utime, accel_->utime) > static_cast<std::uint64_t>(config_.pair_window_us)) {
    counters_.increment(J1939Counter::unpaired);  // the older frame's partner never came
    if (rate_->utime < accel_->utime) rate_.reset();
    else accel_.reset();
    // With the order not known, the frame kept may be the trailer of the pair just broken, and the next
    // frame would complete it with another cycle's leader.
    if (!leader_) (rate_ ? rate_->suspect : accel_->suspect) = true;
    return std::nullopt;
  }
  if (rate_->suspect || accel_->suspect) {
    counters_.increment(J1939Counter::unpaired);
    rate_.reset();
    accel_.reset();
    return std::nullopt;
  }
  learnOrder(rate_->arrival < accel_->arrival ? Kind::Rate : Kind::Accel);
  const AngularRate r = rate_->rate;
  const Acceleration a = accel_->accel;
  // The rate frame's own latency byte describes it: its receive time minus that latency is the sample time.
  std::int64_t utime = rate_->utime;
  rate_.reset();
  accel_.reset();
  const Value rates[3] = {r.roll, r.pitch, r.yaw};  // about x, y, z
  const FigureOfMerit rate_merits[3] = {r.merit[1], r.merit[0], r.merit[2]};
  const Value accels[3] = {a.longitudinal, a.lateral, a.vertical};  // along x, y, z
  const FigureOfMerit accel_merits[3] = {a.merit[1], a.merit[0], a.merit[2]};
  const bool rates_ok = acceptValues(rates, rate_merits);
  const bool accels_ok = acceptValues(accels, accel_merits);
  if (!rates_ok || !accels_ok) return std::nullopt;
  if (config_.subtract_latency && r.latency_s) {
    // At most 125 ms (one byte of 0.5 ms); a stamp that close to the smallest one stays there.
    const std::int64_t latency_us = std::llround(*r.latency_s * 1e6);
    utime = utime >= std::numeric_limits<std::int64_t>::min() + latency_us ? utime - latency_us
                                                                           : std::numeric_limits<std::int64_t>::min();
  }
  if (last_utime_ && utime <= *last_utime_) {
    counters_.increment(J1939Counter::timestamp_backwards);
    return std::nullopt;
  }
  last_utime_ = utime;
  ImuReading out;
  out.utime = utime;
  out.gyro = config_.gyro_axis_map.apply(Vec3(rates[0].si, rates[1].si, rates[2].si));
  out.accel = config_.accel_axis_map.apply(Vec3(accels[0].si, accels[1].si, accels[2].si));
  out.temperature_c = std::nan("");
  counters_.increment(J1939Counter::samples);
  return out;
}

}  // namespace imucal::drivers
