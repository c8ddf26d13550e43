#include "imucal/core/closest_name.hpp"

#include <algorithm>

namespace imucal {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string closestName(const std::string& word, const std::vector<std::string>& names, std::size_t limit) {
  std::string best;
  for (const std::string& name : names) {
    const std::size_t d = editDistance(word, name);
    if (d < limit) {
      limit = d;
      best = name;
    }
  }
  return best;
}

}  // namespace imucal
