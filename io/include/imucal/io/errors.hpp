#pragma once
// Errors for files that cannot be used. Every message starts with where the problem is ("imu.csv:17: ..."),
// as a compiler would, so a user can jump straight to it.
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>

namespace imucal::io {

// Bad content or a file that cannot be read: the user must fix the input.
struct InputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A result could not be written (missing directory, full disk, no permission).
struct OutputError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// "file:line: " with a 1-based line, or "file: " when line <= 0 (no single line is to blame).
std::string location(const std::string& file, long line);

[[noreturn]] void throwInputError(const std::string& file, long line, const std::string& message);

// Text from an input, fit to quote in a message: at most `max` characters, control and non-ASCII bytes as
// \xHH, and "... (N bytes)" when cut, so a binary file or a forged id cannot flood a message or a log.
std::string excerpt(std::string_view text, std::size_t max = 60);

}  // namespace imucal::io
