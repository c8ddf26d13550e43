#pragma once
// A motion study (many seeds of one simulated motion) as a Markdown table and JSON, in human units.
#include <nlohmann/json.hpp>
#include <string>

#include "imucal/sim/motion_study.hpp"

namespace imucal::cli {

std::string motionStudyMarkdown(const sim::MotionStudyReport& report, const std::string& title);
nlohmann::json motionStudyJson(const sim::MotionStudyReport& report);

}  // namespace imucal::cli
