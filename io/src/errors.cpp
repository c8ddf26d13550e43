#include "imucal/io/errors.hpp"

namespace imucal::io {

std::string location(const std::string& file, long line) {
  if (line <= 0) return file + ": ";
  return file + ":" + std::to_string(line) + ": ";
}

void throwInputError(const std::string& file, long line, const std::string& message) {
  throw InputError(location(file, line) + message);
}

}  // namespace imucal::io
