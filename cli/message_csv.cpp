#include "message_csv.hpp"

#include <algorithm>

#include "message_text.hpp"

namespace imucal::cli {

namespace {

bool hasVariable(const MessageRecord& record) {
  return std::any_of(record.fields.begin(), record.fields.end(), [](const Field& f) { return f.shape == Shape::Variable; });
}

}  // namespace

std::vector<std::string> csvHeader(const MessageRecord& record) {
  std::vector<std::string> header;
  for (const Field& f : record.fields) {
    if (f.shape != Shape::Fixed) {
      header.emplace_back(f.name);
      continue;
    }
    for (std::size_t i = 0; i < f.size(); ++i) header.push_back(std::string(f.name) + '_' + std::to_string(i));
  }
  if (hasVariable(record)) header.emplace_back("element");
  return header;
}

std::size_t writeCsvRows(const MessageRecord& record, std::ostream& out) {
  std::size_t elements = 0;
  for (const Field& f : record.fields)
    if (f.shape == Shape::Variable) elements = std::max(elements, f.size());
  const std::size_t rows = std::max<std::size_t>(elements, 1);
  const bool variable = hasVariable(record);
  for (std::size_t row = 0; row < rows; ++row) {
    bool first = true;
    const auto cell = [&](const std::string& text) {
      if (!first) out << ',';
      out << text;
      first = false;
    };
    for (const Field& f : record.fields) {
      if (f.shape == Shape::Scalar) {
        cell(elementText(f, 0, TextStyle::Csv));
      } else if (f.shape == Shape::Fixed) {
        for (std::size_t i = 0; i < f.size(); ++i) cell(elementText(f, i, TextStyle::Csv));
      } else {
        cell(row < f.size() ? elementText(f, row, TextStyle::Csv) : std::string());
      }
    }
    if (variable) cell(elements > 0 ? std::to_string(row) : std::string());
    out << '\n';
  }
  return rows;
}

}  // namespace imucal::cli
