// Chi-square statistic with pooling, incomplete gamma p-values, and histograms.
#include "support/chi2.h"
#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>

namespace caustica::test {

namespace {
constexpr int kMaxIterations = 100000;
constexpr double kEpsilon = 1e-15;
constexpr double kTiny = 1e-300;

// P(a, x) by its series, valid (and fast) for x < a + 1.
double gamma_p_series(double a, double x) {
  double ap = a, del = 1.0 / a, total = del;
  for (int n = 0; n < kMaxIterations; ++n) {
    ap += 1.0;
    del *= x / ap;
    total += del;
    if (std::abs(del) < std::abs(total) * kEpsilon) break;
  }
  return total * std::exp(-x + a * std::log(x) - std::lgamma(a));
}

// Q(a, x) by its continued fraction (modified Lentz), valid for x >= a + 1.
double gamma_q_fraction(double a, double x) {
  double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
  for (int i = 1; i < kMaxIterations; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double del = d * c;
    h *= del;
    if (std::abs(del - 1.0) < kEpsilon) break;
  }
  return std::exp(-x + a * std::log(x) - std::lgamma(a)) * h;
}
}  // namespace

double gamma_q(double a, double x) {
  if (!(a > 0.0) || !(x >= 0.0)) return std::nan("");
  if (x == 0.0) return 1.0;
  if (x < a + 1.0) return 1.0 - gamma_p_series(a, x);
  return gamma_q_fraction(a, x);
}

double chi2_p_value(double statistic, int dof) {
  if (dof <= 0) return 1.0;
  return gamma_q(0.5 * dof, 0.5 * std::max(0.0, statistic));
}

double sidak_alpha(double alpha, int tests) { return 1.0 - std::pow(1.0 - alpha, 1.0 / tests); }

Chi2Result chi2_test(const std::vector<double>& observed, const std::vector<double>& expected, double min_expected) {
  Chi2Result r;
  std::ostringstream msg;
  if (observed.size() != expected.size() || observed.empty()) {
    r.p_value = 0;
    r.message = "chi2_test: observed and expected differ in size or are empty";
    return r;
  }
  // Smallest expected first, so pooling merges the sparsest cells (Nori chi2test).
  std::vector<size_t> order(observed.size());
  std::iota(order.begin(), order.end(), size_t(0));
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return expected[a] < expected[b]; });

  double pooled_obs = 0, pooled_exp = 0;
  int cells = 0;
  std::vector<std::pair<double, size_t>> contributions;
  for (size_t i : order) {
    const double o = observed[i], e = expected[i];
    if (e <= 0.0) {
      if (o > 0.0) {
        r.statistic = INFINITY;
        r.p_value = 0;
        msg << "cell " << i << " has " << o << " samples but expected count 0";
        r.message = msg.str();
        return r;
      }
      continue;
    }
    if (e < min_expected || (pooled_exp > 0.0 && pooled_exp < min_expected)) {
      pooled_obs += o;
      pooled_exp += e;
      ++r.pooled_cells;
      continue;
    }
    const double d = o - e;
    contributions.emplace_back(d * d / e, i);
    r.statistic += d * d / e;
    ++cells;
  }
  if (pooled_exp > 0.0 || pooled_obs > 0.0) {
    const double d = pooled_obs - pooled_exp;
    r.statistic += pooled_exp > 0.0 ? d * d / pooled_exp : INFINITY;
    ++cells;
  }
  r.dof = cells - 1;
  r.p_value = chi2_p_value(r.statistic, r.dof);

  std::sort(contributions.rbegin(), contributions.rend());
  msg << "chi2 = " << r.statistic << ", dof = " << r.dof << ", p = " << r.p_value << ", pooled cells = "
      << r.pooled_cells << " (observed " << pooled_obs << ", expected " << pooled_exp << ")\n"
      << "largest contributions:";
  for (size_t k = 0; k < std::min<size_t>(5, contributions.size()); ++k) {
    const size_t i = contributions[k].second;
    msg << "\n  cell " << i << ": observed " << observed[i] << ", expected " << expected[i];
  }
  r.message = msg.str();
  return r;
}

Histogram2D::Histogram2D(double x0, double x1, int nx, double y0, double y1, int ny)
    : x0_(x0), x1_(x1), y0_(y0), y1_(y1), nx_(nx), ny_(ny), counts_(size_t(nx) * ny + 1, 0.0) {}

void Histogram2D::add(double x, double y) {
  total_ += 1;
  if (!(x >= x0_ && x <= x1_ && y >= y0_ && y <= y1_)) {
    counts_.back() += 1;
    return;
  }
  // The upper edge belongs to the last cell.
  const int i = std::min(nx_ - 1, int((x - x0_) / (x1_ - x0_) * nx_));
  const int j = std::min(ny_ - 1, int((y - y0_) / (y1_ - y0_) * ny_));
  counts_[size_t(j) * nx_ + i] += 1;
}

std::vector<double> Histogram2D::expected(const std::function<double(double, double)>& density, double n_samples,
                                          int sub) const {
  std::vector<double> e(counts_.size(), 0.0);
  const double dx = (x1_ - x0_) / nx_, dy = (y1_ - y0_) / ny_;
  for (int j = 0; j < ny_; ++j) {
    for (int i = 0; i < nx_; ++i) {
      double integral = 0;
      for (int b = 0; b < sub; ++b) {
        for (int a = 0; a < sub; ++a) {
          const double x = x0_ + (i + (a + 0.5) / sub) * dx;
          const double y = y0_ + (j + (b + 0.5) / sub) * dy;
          integral += density(x, y);
        }
      }
      e[size_t(j) * nx_ + i] = n_samples * integral * dx * dy / (double(sub) * sub);
    }
  }
  return e;
}

void SphereHistogram::add(const Vec3& w) {
  const glm::dvec3 d = glm::normalize(glm::dvec3(w));
  double phi = std::atan2(d.y, d.x);
  if (phi < 0.0) phi += 2.0 * kPi64;
  if (phi >= 2.0 * kPi64) phi = 0.0;
  grid_.add(std::clamp(d.z, -1.0, 1.0), phi);
}

std::vector<double> SphereHistogram::expected(const std::function<double(const Vec3&)>& pdf, double n_samples,
                                              int sub) const {
  return grid_.expected(
      [&](double z, double phi) {
        const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
        return double(pdf(Vec3(float(r * std::cos(phi)), float(r * std::sin(phi)), float(z))));
      },
      n_samples, sub);
}

}  // namespace caustica::test
