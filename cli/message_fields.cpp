#include "message_fields.hpp"

namespace imucal::cli {

std::size_t Field::size() const {
  return std::visit([](const auto& v) { return v.size(); }, values);
}

void MessageRecord::integer(std::string_view name, std::int64_t value) {
  fields.push_back({name, Shape::Scalar, std::vector<std::int64_t>{value}});
}
void MessageRecord::real(std::string_view name, double value) {
  fields.push_back({name, Shape::Scalar, std::vector<double>{value}});
}
void MessageRecord::flag(std::string_view name, std::int8_t value) {
  fields.push_back({name, Shape::Scalar, std::vector<bool>{value != 0}});
}
void MessageRecord::text(std::string_view name, const std::string& value) {
  fields.push_back({name, Shape::Scalar, std::vector<std::string>{value}});
}
void MessageRecord::variable(std::string_view name, const std::vector<std::int64_t>& values) {
  fields.push_back({name, Shape::Variable, values});
}
void MessageRecord::variable(std::string_view name, const std::vector<std::int32_t>& values) {
  fields.push_back({name, Shape::Variable, std::vector<std::int64_t>(values.begin(), values.end())});
}
void MessageRecord::variable(std::string_view name, const std::vector<double>& values) {
  fields.push_back({name, Shape::Variable, values});
}
void MessageRecord::variable(std::string_view name, const std::vector<std::string>& values) {
  fields.push_back({name, Shape::Variable, values});
}
void MessageRecord::flags(std::string_view name, const std::vector<std::int8_t>& values) {
  std::vector<bool> b;
  b.reserve(values.size());
  for (std::int8_t v : values) b.push_back(v != 0);
  fields.push_back({name, Shape::Variable, std::move(b)});
}

MessageRecord describe(const imucal::imu_sample_t& m) {
  MessageRecord r{"imu_sample_t", {}};
  r.integer("utime", m.utime);
  r.integer("seq", m.seq);
  r.integer("device_time_us", m.device_time_us);
  r.fixed("accel", m.accel);
  r.fixed("gyro", m.gyro);
  r.real("temperature_c", m.temperature_c);
  r.integer("status", m.status);
  r.text("sensor_id", m.sensor_id);
  return r;
}

MessageRecord describe(const imucal::imu_batch_t& m) {
  MessageRecord r{"imu_batch_t", {}};
  r.integer("utime", m.utime);
  r.integer("period_ns", m.period_ns);
  r.integer("first_seq", m.first_seq);
  r.integer("count", m.count);
  r.integer("stamp_count", m.stamp_count);
  r.variable("sample_utime", m.sample_utime);
  r.variable("device_time_us", m.device_time_us);
  r.variable("accel_x", m.accel_x);
  r.variable("accel_y", m.accel_y);
  r.variable("accel_z", m.accel_z);
  r.variable("gyro_x", m.gyro_x);
  r.variable("gyro_y", m.gyro_y);
  r.variable("gyro_z", m.gyro_z);
  r.variable("status", m.status);
  r.real("temperature_c", m.temperature_c);
  r.text("sensor_id", m.sensor_id);
  return r;
}

MessageRecord describe(const imucal::heading_sample_t& m) {
  MessageRecord r{"heading_sample_t", {}};
  r.integer("utime", m.utime);
  r.real("heading", m.heading);
  r.real("heading_sigma", m.heading_sigma);
  r.integer("source", m.source);
  return r;
}

MessageRecord describe(const imucal::mag_field_t& m) {
  MessageRecord r{"mag_field_t", {}};
  r.integer("utime", m.utime);
  r.integer("seq", m.seq);
  r.integer("device_time_us", m.device_time_us);
  r.fixed("field_ut", m.field_ut);
  r.integer("status", m.status);
  r.text("sensor_id", m.sensor_id);
  return r;
}

MessageRecord describe(const imucal::calibration_t& m) {
  MessageRecord r{"calibration_t", {}};
  r.integer("utime", m.utime);
  r.text("sensor_id", m.sensor_id);
  r.integer("state", m.state);
  r.flag("restored", m.restored);
  r.integer("calibrated_utime", m.calibrated_utime);
  r.text("model", m.model);
  r.fixed("accel_bias", m.accel_bias);
  r.fixed("accel_bias_sigma", m.accel_bias_sigma);
  r.fixed("gyro_bias", m.gyro_bias);
  r.fixed("gyro_bias_sigma", m.gyro_bias_sigma);
  r.flag("scale_estimated", m.scale_estimated);
  r.fixed("accel_scale", m.accel_scale);
  r.fixed("accel_scale_sigma", m.accel_scale_sigma);
  r.fixed("gyro_scale", m.gyro_scale);
  r.fixed("gyro_scale_sigma", m.gyro_scale_sigma);
  r.integer("num_params", m.num_params);
  r.variable("param_names", m.param_names);
  r.variable("values", m.values);
  r.variable("sigmas", m.sigmas);
  r.flags("converged", m.converged);
  r.variable("convergence_time_s", m.convergence_time_s);
  r.variable("information_age_s", m.information_age_s);
  return r;
}

MessageRecord describe(const imucal::daemon_status_t& m) {
  MessageRecord r{"daemon_status_t", {}};
  r.integer("utime", m.utime);
  r.text("sensor_id", m.sensor_id);
  r.real("uptime_s", m.uptime_s);
  r.integer("state", m.state);
  r.real("imu_age_s", m.imu_age_s);
  r.real("heading_age_s", m.heading_age_s);
  r.flag("heading_stale", m.heading_stale);
  r.real("imu_rate_hz", m.imu_rate_hz);
  r.real("heading_rate_hz", m.heading_rate_hz);
  r.integer("imu_accepted", m.imu_accepted);
  r.integer("heading_accepted", m.heading_accepted);
  r.integer("imu_dropped", m.imu_dropped);
  r.integer("rejected_nan", m.rejected_nan);
  r.integer("rejected_time_backwards", m.rejected_time_backwards);
  r.integer("rejected_duplicate", m.rejected_duplicate);
  r.integer("rejected_out_of_range", m.rejected_out_of_range);
  r.integer("rejected_unknown_sensor", m.rejected_unknown_sensor);
  r.integer("gaps", m.gaps);
  r.integer("heading_rejected", m.heading_rejected);
  r.real("heading_nis_mean", m.heading_nis_mean);
  r.integer("heading_nis_count", m.heading_nis_count);
  r.real("velocity_nis_mean", m.velocity_nis_mean);
  r.integer("velocity_nis_count", m.velocity_nis_count);
  r.integer("handler_errors", m.handler_errors);
  r.integer("decode_errors", m.decode_errors);
  r.text("restore_error", m.restore_error);
  r.integer("triggers", m.triggers);
  r.integer("config_reloads", m.config_reloads);
  r.integer("config_errors", m.config_errors);
  return r;
}

MessageRecord describe(const imucal::session_progress_t& m) {
  MessageRecord r{"session_progress_t", {}};
  r.integer("utime", m.utime);
  r.text("sensor_id", m.sensor_id);
  r.integer("phase", m.phase);
  r.real("phase_time_s", m.phase_time_s);
  r.real("turned_deg", m.turned_deg);
  r.fixed("turn_axis", m.turn_axis);
  r.text("hint", m.hint);
  r.text("last_rejection", m.last_rejection);
  r.integer("rejected", m.rejected);
  r.integer("num_params", m.num_params);
  r.variable("param_names", m.param_names);
  r.variable("values", m.values);
  r.variable("sigmas", m.sigmas);
  r.variable("prior_sigmas", m.prior_sigmas);
  r.real("estimate_time_s", m.estimate_time_s);
  r.text("advice", m.advice);
  return r;
}

MessageRecord describe(const imucal::calibration_trigger_t& m) {
  MessageRecord r{"calibration_trigger_t", {}};
  r.integer("utime", m.utime);
  r.text("sensor_id", m.sensor_id);
  r.text("requester", m.requester);
  return r;
}

}  // namespace imucal::cli
