#pragma once
// The Monte Carlo study as a Markdown table (for people) and JSON (for scripts), in human units.
#include <nlohmann/json.hpp>
#include <string>

#include "imucal/sim/montecarlo.hpp"

namespace imucal::cli {

std::string monteCarloMarkdown(const sim::MonteCarloReport& report);
nlohmann::json monteCarloJson(const sim::MonteCarloReport& report);

}  // namespace imucal::cli
