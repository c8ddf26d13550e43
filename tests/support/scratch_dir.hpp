#pragma once
// A fresh directory for one test, removed with everything in it when the test ends. Named after the process
// and the running test, so tests run in parallel (ctest -j) never share one.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <memory>
#include <string>

namespace imucal::testing {

class ScratchDir {
 public:
  explicit ScratchDir(const std::string& tag = "") : ScratchDir(ProcessWide{}, testName(tag)) {}
  // For files several tests of one process share (see processScratchDir): named after the process only.
  struct ProcessWide {};
  ScratchDir(ProcessWide, const std::string& tag) {
    std::string name = "imucal_" + std::to_string(::getpid()) + "_" + tag;
    for (char& c : name)
      if (c == '/') c = '_';  // parameterized test names
    path_ = std::filesystem::temp_directory_path() / name;
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  const std::filesystem::path& path() const { return path_; }
  std::string string() const { return path_.string(); }
  std::string operator/(const std::string& name) const { return (path_ / name).string(); }
  // Writes `text` to NAME in the directory; returns its path.
  std::string write(const std::string& name, const std::string& text) const {
    const std::string p = *this / name;
    std::ofstream(p, std::ios::binary) << text;
    return p;
  }

 private:
  static std::string testName(const std::string& tag) {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string name = info ? std::string(info->test_suite_name()) + "_" + info->name() : "global";
    return tag.empty() ? name : name + "_" + tag;
  }
  std::filesystem::path path_;
};

// One directory per tag for the whole test process, removed when it exits.
inline const std::filesystem::path& processScratchDir(const std::string& tag) {
  static std::map<std::string, std::unique_ptr<ScratchDir>> dirs;
  auto& dir = dirs[tag];
  if (!dir) dir = std::make_unique<ScratchDir>(ScratchDir::ProcessWide{}, tag);
  return dir->path();
}

inline std::string readFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// A file of tests/data/hostile/: inputs that once crashed, stopped or fooled a program (see SOURCE.md there).
inline std::string hostile(const std::string& name) { return std::string(IMUCAL_TEST_DATA_DIR) + "/hostile/" + name; }

}  // namespace imucal::testing
