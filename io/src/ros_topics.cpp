#include "ros_topics.hpp"

#include <algorithm>

#include "imucal/core/units.hpp"
#include "imucal/io/errors.hpp"

namespace imucal::io::ros {

bool startsWith(const std::string& path, std::string_view magic) {
  std::ifstream in(path, std::ios::binary);
  std::string head(magic.size(), '\0');
  return in.read(head.data(), static_cast<std::streamsize>(head.size())) && head == magic;
}

std::uint64_t openWithMagic(std::ifstream& in, const std::string& path, std::string_view magic, const std::string& not_this) {
  in.open(path, std::ios::binary);
  if (!in) throw InputError(location(path, 0) + "cannot open");
  in.seekg(0, std::ios::end);
  const auto size = static_cast<std::uint64_t>(in.tellg());
  in.seekg(0);
  std::string head(magic.size(), '\0');
  if (size < magic.size() || !in.read(head.data(), static_cast<std::streamsize>(head.size())) || head != magic)
    throw InputError(location(path, 0) + not_this);
  return size;
}

std::string implausible(bool imu, const Stamped& s) {
  constexpr double kMaxAccel = 1000.0 * units::kStandardGravity, kMaxGyro = 1000.0, kMaxFieldUt = 1e6;
  // Finite first: Eigen's maxCoeff may step over a NaN, and a comparison with NaN is false either way.
  const auto within = [](const Vec3& v, double limit) { return v.allFinite() && v.cwiseAbs().maxCoeff() <= limit; };
  if (imu && !within(s.b, kMaxAccel)) return "linear_acceleration beyond 1000 g or not a number";
  if (imu && !within(s.a, kMaxGyro)) return "angular_velocity beyond 1000 rad/s or not a number";
  if (!imu && !within(s.a, kMaxFieldUt)) return "magnetic_field beyond 1 T or not a number";
  return "";
}

TopicCollector::TopicCollector(std::string path, std::string imu_type, std::string mag_type)
    : path_(std::move(path)), imu_type_(std::move(imu_type)), mag_type_(std::move(mag_type)) {}

void TopicCollector::topic(const std::string& name, const std::string& type) {
  if (topic_type_.emplace(name, type).second) topic_order_.push_back(name);
}

RosRecording TopicCollector::result(const TopicChoice& choice) const {
  RosRecording out;
  for (const std::string& name : topic_order_) {
    RosTopic t;
    t.name = name;
    t.type = topic_type_.at(name);
    const auto it = samples_.find(name);
    t.messages = it == samples_.end() ? 0 : static_cast<long>(it->second.size());
    out.topics.push_back(t);
  }
  out.imu_topic = choice.imu_required ? choose(imu_type_, choice.imu_topic, choice.imu_option, true) : "";
  out.mag_topic = choose(mag_type_, choice.mag_topic, choice.mag_option, !choice.imu_required);
  if (out.imu_topic.empty()) return magnetometerOnly(std::move(out));
  const auto found = samples_.find(out.imu_topic);
  if (found == samples_.end() || found->second.empty())
    throw InputError(location(path_, 0) + "topic " + out.imu_topic + " holds no message");
  const std::vector<Stamped>& imu = found->second;
  // A driver that leaves header.stamp zero: the time the recorder received each message is all there is.
  const bool use_record_time = std::all_of(imu.begin(), imu.end(), [](const Stamped& s) { return s.ns == 0; });
  const auto stamp = [&](const Stamped& s) { return use_record_time ? s.record_ns : s.ns; };
  out.stamps_from_record_time = use_record_time;
  const std::int64_t origin = stamp(imu.front());
  out.first_stamp_ns = origin;
  for (const Stamped& s : imu) {
    ImuSample x;
    x.t = static_cast<double>(stamp(s) - origin) * 1e-9;
    x.gyro = s.a;
    x.accel = s.b;
    out.imu.push_back(x);
    out.imu_messages.push_back(s.message);
  }
  const auto mag = samples_.find(out.mag_topic);
  if (mag != samples_.end()) {
    for (const Stamped& s : mag->second) {
      MagSample m;
      m.t = static_cast<double>(stamp(s) - origin) * 1e-9;
      m.field = s.a;
      out.mag.push_back(m);
      out.mag_messages.push_back(s.message);
    }
  }
  return out;
}

RosRecording TopicCollector::magnetometerOnly(RosRecording out) const {
  const auto mag = samples_.find(out.mag_topic);
  if (mag == samples_.end() || mag->second.empty())
    throw InputError(location(path_, 0) + "topic " + out.mag_topic + " holds no message");
  out.first_stamp_ns = mag->second.front().ns;
  for (const Stamped& s : mag->second) {
    MagSample m;
    m.t = static_cast<double>(s.ns - out.first_stamp_ns) * 1e-9;
    m.field = s.a;
    out.mag.push_back(m);
    out.mag_messages.push_back(s.message);
  }
  return out;
}

std::string TopicCollector::choose(const std::string& type, const std::string& asked, const std::string& option,
                                   bool required) const {
  std::vector<std::string> of_type;
  for (const std::string& name : topic_order_)
    if (topic_type_.at(name) == type) of_type.push_back(name);
  std::string list;
  for (const std::string& name : of_type) list += (list.empty() ? "" : ", ") + name;
  if (!asked.empty()) {
    const auto it = topic_type_.find(asked);
    if (it == topic_type_.end())
      throw InputError(location(path_, 0) + "no topic " + excerpt(asked) + " (" + type + " topics: " +
                       (list.empty() ? "none" : list) + ")");
    if (it->second != type)
      throw InputError(location(path_, 0) + "topic " + asked + " is a " + excerpt(it->second) + ", not a " + type);
    return asked;
  }
  if (of_type.size() > 1)
    throw InputError(location(path_, 0) + "several " + type + " topics (" + list + "): choose one with " + option);
  if (of_type.empty()) {
    if (required) throw InputError(location(path_, 0) + "no " + type + " topic in the file");
    return "";
  }
  return of_type.front();
}

}  // namespace imucal::io::ros
