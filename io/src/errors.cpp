#include "imucal/io/errors.hpp"

namespace imucal::io {

std::string location(const std::string& file, long line) {
  if (line <= 0) return file + ": ";
  return file + ":" + std::to_string(line) + ": ";
}

void throwInputError(const std::string& file, long line, const std::string& message) {
  throw InputError(location(file, line) + message);
}

std::string excerpt(std::string_view text, std::size_t max) {
  static const char* hex = "0123456789abcdef";
  std::string out;
  std::size_t shown = 0;
  for (; shown < text.size() && out.size() < max; ++shown) {
    const auto c = static_cast<unsigned char>(text[shown]);
    if (c >= 0x20 && c < 0x7f) {
      out += static_cast<char>(c);
    } else {
      out += "\\x";
      out += hex[c >> 4];
      out += hex[c & 0xF];
    }
  }
  if (shown < text.size()) out += "... (" + std::to_string(text.size()) + " bytes)";
  return out;
}

}  // namespace imucal::io
