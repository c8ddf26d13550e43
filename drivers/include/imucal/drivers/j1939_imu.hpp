#pragma once
// A J1939 IMU as one sample stream: frames filtered by source address and PGN, an angular-rate frame and
// an acceleration frame paired into one ImuReading (body FRD, SI). A reading is published only when all six
// values are numbers and no figure of merit says error; not-available codes and error indicators are
// counted, never turned into numbers.
// Pairing is by receive time, and a sensor sends its two frames of a cycle in a fixed order: once a few
// pairs in a row have shown that order, a trailing frame still waiting when the next leading frame comes
// has lost its own leader and is dropped, so a pair split by bus or scheduler jitter wider than the pair
// window is never completed with the next cycle's leader (a sample mixing two instants). Before the order
// is known, a pair completed by a frame kept from such a split is dropped instead.
#include <cstdint>
#include <optional>

#include "imucal/drivers/can_frame.hpp"
#include "imucal/drivers/counters.hpp"
#include "imucal/drivers/imu_reading.hpp"
#include "imucal/drivers/j1939.hpp"

namespace imucal::drivers {

// The counters; the table's order is the log line's (summary()).
enum class J1939Counter {
  frames, samples, not_extended, other_pgn, other_source, bad_length, not_available, error_indicator,
  reserved_value, merit_error, merit_degraded, unpaired, timestamp_backwards
};
inline constexpr CounterName<J1939Counter> kJ1939Counters[] = {
    {J1939Counter::frames, "frames"},
    {J1939Counter::samples, "samples"},
    {J1939Counter::not_extended, "not_extended"},
    {J1939Counter::other_pgn, "other_pgn"},
    {J1939Counter::other_source, "other_source"},
    {J1939Counter::bad_length, "bad_length"},
    {J1939Counter::not_available, "not_available"},
    {J1939Counter::error_indicator, "error_indicator"},
    {J1939Counter::reserved_value, "reserved_value"},
    {J1939Counter::merit_error, "merit_error"},
    {J1939Counter::merit_degraded, "merit_degraded"},
    {J1939Counter::unpaired, "unpaired"},
    {J1939Counter::timestamp_backwards, "timestamp_backwards"}};
constexpr const auto& counterNames(J1939Counter) { return kJ1939Counters; }

struct J1939ImuConfig {
  std::optional<std::uint8_t> source_address;  // nullopt: lock onto the first IMU source seen
  std::int64_t pair_window_us = 5000;          // rate and acceleration frames this close belong together
  // body FRD from the J1939 axes (x longitudinal, y lateral, z vertical; roll, pitch, yaw rate about them).
  // J1939's y points left and z up, so FRD is (+x, -y, -z).
  io::AxisMap accel_axis_map{{0, 1, 2}, {1, -1, -1}};
  io::AxisMap gyro_axis_map{{0, 1, 2}, {1, -1, -1}};
  bool subtract_latency = true;  // stamp = receive time of the rate frame - its reported latency
};

class J1939Imu {
 public:
  explicit J1939Imu(const J1939ImuConfig& config);
  // Feeds one frame; returns a reading when it completes a pair.
  std::optional<ImuReading> add(const CanFrame& frame);
  const Counters<J1939Counter>& counters() const { return counters_; }
  std::optional<std::uint8_t> source() const { return source_; }

 private:
  bool acceptValues(const j1939::Value* values, const j1939::FigureOfMerit* merits);
  std::optional<ImuReading> pair();

  J1939ImuConfig config_;
  Counters<J1939Counter> counters_;
  std::optional<std::uint8_t> source_;
  enum class Kind { Rate, Accel };
  void dropOrphanedTrailer(Kind arriving);
  void learnOrder(Kind first);

  struct PendingRate {
    std::int64_t utime;
    std::uint64_t arrival;
    bool suspect;  // kept from a pair broken by the window while the order was unknown
    j1939::AngularRate rate;
  };
  struct PendingAccel {
    std::int64_t utime;
    std::uint64_t arrival;
    bool suspect;
    j1939::Acceleration accel;
  };
  std::optional<PendingRate> rate_;
  std::optional<PendingAccel> accel_;
  std::optional<std::int64_t> last_utime_;
  std::uint64_t arrivals_ = 0;
  // The sensor's frame order: the kind that came first in the last pairs, how many pairs in a row agreed,
  // and the learned leader once enough did. Orphans dropped in a row without a pair unlearn it (a sensor
  // whose order changed would otherwise never pair again).
  Kind order_candidate_ = Kind::Rate;
  int order_agreeing_ = 0;
  std::optional<Kind> leader_;
  int orphans_in_a_row_ = 0;
};

}  // namespace imucal::drivers
