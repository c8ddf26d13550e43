#pragma once
// Readers that only take a path get the fuzz input through a file in a scratch directory of this process
// (two fuzzing processes never share a file); the directory is removed when the process exits normally.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace imucal::fuzz {

class ScratchDir {
 public:
  ScratchDir() {
    const char* tmp = std::getenv("TMPDIR");
    path_ = std::filesystem::path(tmp != nullptr && *tmp != '\0' ? tmp : "/tmp") /
            ("imucal-fuzz-" + std::to_string(::getpid()));
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }

  // Replaces `name` in the directory by the bytes; returns its path.
  std::string write(const std::string& name, const std::uint8_t* data, std::size_t size) const {
    const std::filesystem::path file = path_ / name;
    std::ofstream out(file, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out.flush()) std::abort();  // a full /tmp would otherwise look like a reader bug
    return file.string();
  }

  // One directory for the whole run: the same path every input, so a reader's message does not vary.
  static const ScratchDir& instance() {
    static const ScratchDir dir;
    return dir;
  }

 private:
  std::filesystem::path path_;
};

}  // namespace imucal::fuzz
