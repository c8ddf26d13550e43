#include "imucal/core/input_checks.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "imucal/core/rotation.hpp"
#include "imucal/core/static_detector.hpp"
#include "imucal/core/units.hpp"

namespace imucal {

namespace {

constexpr double kG = units::kStandardGravity;
// Samples on each side of a jump whose accelerometer must be quiet: a few, so a jump is seen between
// two short pauses as well as between two long stills.
constexpr std::size_t kJumpSide = 5;
// Quiet: each axis' spread within a side below this (a hand holding still, not a move).
constexpr double kQuietSpread = 0.05 * kG;
// What the accelerometer's direction may turn beyond what the gyro allows: tilt noise of a hand at rest.
constexpr double kJumpMargin = 10.0 * units::deg;
// Moves whose gravity turned less than this show little of the gyro's axes.
constexpr double kMinTilt = 20.0 * units::deg;
constexpr std::size_t kMaxMoves = 60;
// The accelerometer reads gravity's direction where its magnitude is within this fraction of the still's.
constexpr double kQuietLinear = 0.05;
// Axis sets whose errors differ by less than this fit the moves alike.
constexpr double kAxisTie = 1.0 * units::deg;
constexpr double kMaxMoveSeconds = 60.0;

std::string vec(const Vec3& v) {
  std::ostringstream out;
  out.precision(3);
  out << "(" << v.x() << ", " << v.y() << ", " << v.z() << ")";
  return out.str();
}

struct Side {
  Vec3 mean = Vec3::Zero();
  double spread = 0.0;
  double t = 0.0;  // mean time
};

Side side(const std::vector<ImuSample>& imu, std::size_t first, std::size_t count) {
  Side s;
  Vec3 sq = Vec3::Zero();
  for (std::size_t i = first; i < first + count; ++i) {
    s.mean += imu[i].accel;
    sq += imu[i].accel.cwiseAbs2();
    s.t += imu[i].t;
  }
  const double n = static_cast<double>(count);
  s.mean /= n;
  s.t /= n;
  s.spread = std::sqrt((sq / n - s.mean.cwiseAbs2()).cwiseMax(0.0).maxCoeff());
  return s;
}

// One move after a still: the gravity's direction at the still, and the accelerometer's direction where it
// reads about the still's magnitude (little linear acceleration), every few samples and at the next still,
// each with the gyro's angle increment (rate minus the still's mean, times dt) summed since the check before.
// A scale and an axis set act linearly on the summed increment, so each candidate integrates one rotation
// per check instead of one per sample (within a few samples the axis barely moves: the coning left out is
// far below the tens of degrees this check looks for).
struct TiltMove {
  Vec3 up_before;          // the still's specific force direction
  std::vector<Vec3> turn;  // angle increment since the previous check, rad in the gyro's axes
  std::vector<Vec3> seen;  // measured specific force direction (unit) at the check
  std::vector<int> weight; // samples the check stands for (the next still's are one check)
};

Mat3 signedPermutation(const std::array<int, 3>& axes) {
  Mat3 p = Mat3::Zero();
  for (int k = 0; k < 3; ++k) p(k, std::abs(axes[static_cast<std::size_t>(k)]) - 1) = axes[static_cast<std::size_t>(k)] > 0 ? 1.0 : -1.0;
  return p;
}

// The median angle between the gravity direction the gyro carries through the move and the measured one.
double carriedError(const TiltMove& m, const Mat3& axes, double scale) {
  Quat q = Quat::Identity();  // body at the move's start <- body now
  // Angle grows as its cosine falls: the median angle is that of the median cosine, with no arctangent
  // per check (this runs for every candidate axis set and scale).
  std::vector<std::pair<double, int>> minus_cos;
  minus_cos.reserve(m.seen.size());
  int total = 0;
  for (std::size_t k = 0; k < m.seen.size(); ++k) {
    const Vec3 angle = scale * (axes * m.turn[k]);
    const double a = angle.norm();
    if (a > 0.0) q = (q * Quat(Eigen::AngleAxisd(a, angle / a))).normalized();
    minus_cos.emplace_back(-(q.conjugate() * m.up_before).dot(m.seen[k]), m.weight[k]);
    total += m.weight[k];
  }
  std::sort(minus_cos.begin(), minus_cos.end());
  int below = 0;
  for (const auto& [c, w] : minus_cos) {
    below += w;
    if (2 * below > total) return std::acos(std::clamp(-c, -1.0, 1.0));
  }
  return 0.0;  // no checks: not reached, a move has at least ten
}

double medianError(const std::vector<TiltMove>& moves, const Mat3& axes, double scale) {
  std::vector<double> e;
  e.reserve(moves.size());
  for (const TiltMove& m : moves) e.push_back(carriedError(m, axes, scale));
  const auto mid = e.begin() + static_cast<std::ptrdiff_t>(e.size() / 2);
  std::nth_element(e.begin(), mid, e.end());
  return *mid;
}

// The smallest median error over one common gyro scale in 0.5..2 (a grid, then golden-section about its best).
double bestOverScale(const std::vector<TiltMove>& moves, const Mat3& axes, bool refine) {
  constexpr int kGrid = 9;
  double best = 1e9, best_log = 0.0;
  const double lo = std::log(0.5), hi = std::log(2.0), step = (hi - lo) / (kGrid - 1);
  for (int i = 0; i < kGrid; ++i) {
    const double e = medianError(moves, axes, std::exp(lo + i * step));
    if (e < best) {
      best = e;
      best_log = lo + i * step;
    }
  }
  if (!refine) return best;
  double a = best_log - step, b = best_log + step;
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int i = 0; i < 20; ++i) {
    const double c = b - r * (b - a), d = a + r * (b - a);
    if (medianError(moves, axes, std::exp(c)) < medianError(moves, axes, std::exp(d))) b = d;
    else a = c;
  }
  return std::min(best, medianError(moves, axes, std::exp(0.5 * (a + b))));
}

}  // namespace

std::string SampleJump::what() const {
  std::ostringstream out;
  out.precision(3);
  out << "the accelerometer turns " << turn / units::deg << " deg in " << dt * 1e3 << " ms between two still moments, from "
      << vec(before) << " to " << vec(after) << ", while the gyro allows at most " << allowed / units::deg
      << " deg there: no motion does that; the data were spliced or samples lost here";
  return out.str();
}

SampleJump findImpossibleJump(const std::vector<ImuSample>& imu) {
  SampleJump out;
  if (imu.size() < 2 * kJumpSide) return out;
  for (std::size_t i = kJumpSide; i + kJumpSide <= imu.size(); ++i) {
    // Cheap rejection first: a jump shows between the two samples themselves.
    if ((imu[i].accel - imu[i - 1].accel).norm() < 0.3 * kG) continue;
    const Side before = side(imu, i - kJumpSide, kJumpSide), after = side(imu, i, kJumpSide);
    // Values no accelerometer reads (their spread overflows) are not a hand's pause: checked elsewhere.
    if (!(before.spread <= kQuietSpread && after.spread <= kQuietSpread)) continue;
    if ((after.mean - before.mean).norm() < 0.3 * kG || before.mean.norm() < 0.3 * kG || after.mean.norm() < 0.3 * kG)
      continue;
    double rate = 0.0;
    bool saturated = false;
    for (std::size_t j = i - kJumpSide; j < i + kJumpSide; ++j) {
      rate = std::max(rate, imu[j].gyro.norm());
      saturated = saturated || (imu[j].saturated & (7 * kSaturatedGyro)) != 0;
    }
    if (saturated) continue;  // the gyro's true rate is beyond what it read: it allows anything
    const double allowed = rate * (after.t - before.t) + kJumpMargin;
    const double turn = angleBetween(before.mean, after.mean);
    if (turn <= allowed) continue;
    out.found = true;
    out.index = i;
    out.dt = imu[i].t - imu[i - 1].t;
    out.turn = turn;
    out.allowed = allowed;
    out.before = before.mean;
    out.after = after.mean;
    return out;
  }
  return out;
}

long SaturationCount::total() const {
  long n = 0;
  for (long c : samples) n += c;
  return n;
}

std::string SaturationCount::channels() const {
  static const char* const kNames[6] = {"accel x", "accel y", "accel z", "gyro x", "gyro y", "gyro z"};
  std::ostringstream out;
  for (std::size_t k = 0; k < 6; ++k) {
    if (samples[k] == 0) continue;
    if (out.tellp() > 0) out << ", ";
    out << kNames[k] << ": " << samples[k] << (samples[k] == 1 ? " sample" : " samples");
  }
  return out.str();
}

SaturationCount countSaturated(const std::vector<ImuSample>& imu) {
  SaturationCount c;
  bool any = false;
  for (const ImuSample& s : imu) {
    if (s.saturated == 0) continue;
    for (std::size_t k = 0; k < 6; ++k)
      if ((s.saturated & (1u << k)) != 0) ++c.samples[k];
    if (!any) c.first_t = s.t;
    c.last_t = s.t;
    any = true;
  }
  return c;
}

bool GyroAxisCheck::axes_wrong() const {
  const bool given = best == std::array<int, 3>{{1, 2, 3}};
  return moves >= 1 && !given && error_as_given > 20.0 * units::deg &&
         error_best < std::min(10.0 * units::deg, error_as_given / 3.0);
}

std::string GyroAxisCheck::advice() const {
  std::ostringstream out;
  out << "gyro x, y, z should read (";
  for (std::size_t k = 0; k < 3; ++k)
    out << (k == 0 ? "" : ", ") << (best[k] < 0 ? "-" : "+") << "xyz"[std::abs(best[k]) - 1];
  out << ") of the axes given";
  return out.str();
}

GyroAxisCheck checkGyroAxes(const std::vector<ImuSample>& imu, const std::vector<bool>& still) {
  GyroAxisCheck out;
  const auto runs = stillRuns(still);
  std::vector<TiltMove> moves;
  for (std::size_t r = 0; r < runs.size() && moves.size() < kMaxMoves; ++r) {
    const auto [a0, a1] = runs[r];
    // The move runs to the next still (included) or, after the last, to the recording's end.
    std::size_t end = r + 1 < runs.size() ? runs[r + 1].second : imu.size() - 1;
    while (end > a1 && imu[end].t - imu[a1].t > kMaxMoveSeconds) --end;
    if (end <= a1 + 1) continue;
    Vec3 f_before = Vec3::Zero(), bias = Vec3::Zero();
    for (std::size_t i = a0; i <= a1; ++i) {
      f_before += imu[i].accel;
      bias += imu[i].gyro;
    }
    const double n = static_cast<double>(a1 - a0 + 1);
    TiltMove m;
    f_before /= n;
    bias /= n;
    const double g = f_before.norm();
    m.up_before = f_before / g;
    double tilt = 0.0;
    bool saturated = false;
    Vec3 turn = Vec3::Zero();
    // The next still reads one direction: its quiet samples are one check, weighted by their number.
    Vec3 still_sum = Vec3::Zero();
    int still_checks = 0, checks = 0;
    for (std::size_t i = a1 + 1; i <= end; ++i) {
      saturated = saturated || imu[i].saturated != 0;
      turn += (imu[i].t - imu[i - 1].t) * (0.5 * (imu[i].gyro + imu[i - 1].gyro) - bias);
      const bool quiet = std::abs(imu[i].accel.norm() - g) < kQuietLinear * g;
      if (still[i]) {
        if (quiet) {
          still_sum += imu[i].accel;
          ++still_checks;
        }
      } else if ((i - a1) % 5 == 0 && quiet) {
        m.turn.push_back(turn);
        m.seen.push_back(imu[i].accel.normalized());
        m.weight.push_back(1);
        ++checks;
        turn.setZero();
        tilt = std::max(tilt, angleBetween(f_before, imu[i].accel));
      }
    }
    if (still_checks > 0) {
      m.turn.push_back(turn);
      m.seen.push_back(still_sum.normalized());
      m.weight.push_back(still_checks);
      checks += still_checks;
      tilt = std::max(tilt, angleBetween(f_before, still_sum));
    }
    if (!saturated && tilt >= kMinTilt && checks >= 10) moves.push_back(std::move(m));
  }
  out.moves = static_cast<int>(moves.size());
  if (moves.empty()) return out;
  const std::array<int, 3> given{{1, 2, 3}};
  out.error_as_given = bestOverScale(moves, signedPermutation(given), true);
  out.error_best = out.error_as_given;
  out.best = given;
  // An axis the moves never turned about can read either way: among the sets that agree about as well as
  // the best, the one that changes the fewest axes is advised.
  const auto changes = [&given](const std::array<int, 3>& axes) {
    int n = 0;
    for (std::size_t k = 0; k < 3; ++k) n += axes[k] != given[k];
    return n;
  };
  std::vector<std::pair<double, std::array<int, 3>>> tried;
  std::array<int, 3> perm{{1, 2, 3}};
  do {
    for (int signs = 0; signs < 8; ++signs) {
      std::array<int, 3> axes = perm;
      for (int k = 0; k < 3; ++k)
        if ((signs >> k) & 1) axes[static_cast<std::size_t>(k)] = -axes[static_cast<std::size_t>(k)];
      if (axes != given) tried.push_back({bestOverScale(moves, signedPermutation(axes), false), axes});
    }
  } while (std::next_permutation(perm.begin(), perm.end()));
  double lowest = out.error_best;
  for (const auto& t : tried) lowest = std::min(lowest, t.first);
  if (lowest < out.error_as_given) {
    for (const auto& [e, axes] : tried) {
      if (e > lowest + kAxisTie) continue;
      if (out.best == given || changes(axes) < changes(out.best) || (changes(axes) == changes(out.best) && e < out.error_best)) {
        out.best = axes;
        out.error_best = e;
      }
    }
  }
  if (out.best != given) out.error_best = std::min(out.error_best, bestOverScale(moves, signedPermutation(out.best), true));
  return out;
}

}  // namespace imucal
