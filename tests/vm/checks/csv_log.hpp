#pragma once
// Reads the feeders' logs (CSV with a header) into columns by name, and prints the checks' verdict lines
// in the one format the host script parses: "VMCHECK PASS|FAIL <name>: <numbers>".
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace imucal::vmtest {

class CsvLog {
 public:
  explicit CsvLog(const std::string& path) : path_(path) {
    std::ifstream in(path);
    if (!in) throw std::runtime_error("cannot read '" + path + "'");
    std::string line;
    if (!std::getline(in, line)) throw std::runtime_error(path + ": empty");
    header_ = split(line);
    while (std::getline(in, line)) {
      if (!line.empty()) rows_.push_back(split(line));
    }
  }
  std::size_t size() const { return rows_.size(); }
  const std::string& text(std::size_t row, const std::string& column) const {
    const auto& r = rows_.at(row);
    const std::size_t c = index(column);
    if (c >= r.size()) throw std::runtime_error(path_ + ":" + std::to_string(row + 2) + ": no column '" + column + "'");
    return r[c];
  }
  double number(std::size_t row, const std::string& column) const { return std::stod(text(row, column)); }

 private:
  static std::vector<std::string> split(const std::string& line) {
    std::vector<std::string> out;
    std::istringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) out.push_back(cell);
    return out;
  }
  std::size_t index(const std::string& column) const {
    for (std::size_t i = 0; i < header_.size(); ++i) {
      if (header_[i] == column) return i;
    }
    throw std::runtime_error(path_ + ": no column '" + column + "'");
  }
  std::string path_;
  std::vector<std::string> header_;
  std::vector<std::vector<std::string>> rows_;
};

inline int verdict(bool ok, const std::string& name, const std::string& numbers) {
  std::printf("VMCHECK %s %s: %s\n", ok ? "PASS" : "FAIL", name.c_str(), numbers.c_str());
  std::fflush(stdout);
  return ok ? 0 : 1;
}

}  // namespace imucal::vmtest
