#include "imucal/core/free_moves.hpp"

#include <limits>

namespace imucal {

std::vector<Move> findMoves(const std::vector<ImuSample>& imu, const std::vector<bool>& still) {
  std::vector<Move> moves;
  const std::size_t n = std::min(imu.size(), still.size());
  for (std::size_t k = 0; k < n; ++k) {
    if (still[k]) continue;
    Move m;
    m.first = k;
    while (k + 1 < n && !still[k + 1]) ++k;
    m.last = k;
    m.t0 = imu[m.first].t;
    m.t1 = imu[m.last].t;
    moves.push_back(m);
  }
  return moves;
}

void classifyMoves(std::vector<Move>& moves, const std::vector<StepNis>& steps, double limit) {
  std::size_t s = 0;
  for (Move& m : moves) {
    double sum = 0.0;
    int count = 0;
    while (s < steps.size() && steps[s].t <= m.t0) ++s;
    for (std::size_t k = s; k < steps.size() && steps[k].t <= m.t1; ++k) {
      sum += steps[k].nis;
      ++count;
    }
    m.velocity_nis = count > 0 ? sum / count : std::numeric_limits<double>::quiet_NaN();
    m.held = count > 0 && m.velocity_nis <= limit;
  }
}

std::vector<bool> heldSamples(const std::vector<bool>& still, const std::vector<Move>& moves) {
  std::vector<bool> held = still;
  for (const Move& m : moves)
    if (m.held)
      for (std::size_t k = m.first; k <= m.last && k < held.size(); ++k) held[k] = true;
  return held;
}

}  // namespace imucal
