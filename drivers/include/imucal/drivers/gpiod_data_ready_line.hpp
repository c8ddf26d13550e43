#pragma once
// DataReadyLine on a GPIO line through libgpiod 1.6 (the v1 API in Debian 12): rising-edge events with the
// kernel's time stamp of the interrupt.
#include <memory>

#include "imucal/drivers/data_ready_line.hpp"

namespace imucal::drivers {

// Throws std::runtime_error naming the chip and line when they cannot be opened or requested.
std::unique_ptr<DataReadyLine> openGpiodDataReadyLine(const DataReadyConfig& config, const std::string& consumer);

}  // namespace imucal::drivers
