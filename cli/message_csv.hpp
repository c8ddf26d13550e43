#pragma once
// The CSV layout of a message type (`imucal log2csv`), derived from its fields so it cannot disagree with
// `imucal echo`: a scalar is one column named as in the .lcm file; a fixed array of N is N columns name_0 ..
// name_N-1. A message with variable-length arrays (imu_batch_t's samples, calibration_t's and
// session_progress_t's parameters) takes one row per element: row k holds element k of every such array (an
// empty cell where an array is shorter: sample_utime of an evenly spaced batch), the other fields repeated,
// and a last column `element` = k. A message whose arrays are all empty is one row with those cells and
// `element` empty. So every value of every message is in the file, and rows group back into messages by
// `element` restarting at 0.
#include <ostream>
#include <string>
#include <vector>

#include "message_fields.hpp"

namespace imucal::cli {

std::vector<std::string> csvHeader(const MessageRecord& record);

// Writes the message's rows, each ending in '\n'; returns how many.
std::size_t writeCsvRows(const MessageRecord& record, std::ostream& out);

}  // namespace imucal::cli
