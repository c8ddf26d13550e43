#pragma once
// A diagnosis as JSON (effects in the order found, values and sigmas in human units and SI, the gap after
// each step) and as a Markdown report with SVG plots (residuals and Allan curves, model against data,
// before and after).
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "imucal/core/diagnose.hpp"

namespace imucal::io {

nlohmann::json diagnosisToJson(const Diagnosis& d);

struct NamedPlot {
  std::string name;  // file name stem, e.g. "residuals_accel"
  std::string title;
  std::string svg;
};
std::vector<NamedPlot> diagnosisPlots(const Diagnosis& d);

// plot_files: paths relative to the report, in the order of diagnosisPlots. input: what was diagnosed.
std::string diagnosisMarkdown(const Diagnosis& d, const std::vector<NamedPlot>& plots,
                              const std::vector<std::string>& plot_files, const std::string& input);

}  // namespace imucal::io
