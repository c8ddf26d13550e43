#pragma once
// Test helper: while alive, the default spdlog logger writes its lines, formatted as the programs format
// them (imucal_app, plain style), into a string the test reads.
#include <spdlog/sinks/ostream_sink.h>
#include <spdlog/spdlog.h>

#include <memory>
#include <sstream>
#include <string>

#include "imucal/app/log_format.hpp"

namespace imucal::testing {

class SpdlogCapture {
 public:
  SpdlogCapture() : previous_(spdlog::default_logger()) {
    auto logger = std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(out_));
    logger->set_formatter(app::makeLogFormatter("test", app::LogStyle::Plain));
    logger->set_level(spdlog::level::trace);
    spdlog::set_default_logger(std::move(logger));
  }
  ~SpdlogCapture() { spdlog::set_default_logger(previous_); }
  SpdlogCapture(const SpdlogCapture&) = delete;
  SpdlogCapture& operator=(const SpdlogCapture&) = delete;
  std::string text() const { return out_.str(); }

 private:
  std::ostringstream out_;
  std::shared_ptr<spdlog::logger> previous_;
};

}  // namespace imucal::testing
