// Chi-square goodness-of-fit tests for sampling routines (pbrt-v4 / Nori style): cell pooling,
// p-values from the regularized incomplete gamma function, and cell histograms with expected
// counts integrated from a density.
#pragma once
#include <functional>
#include <string>
#include <vector>
#include "core/math.h"

namespace caustica::test {

constexpr double kPi64 = 3.14159265358979323846;

// Regularized upper incomplete gamma function Q(a, x) = Gamma(a, x) / Gamma(a), a > 0, x >= 0
// (Numerical Recipes 6.2: series for x < a + 1, Lentz continued fraction otherwise).
double gamma_q(double a, double x);
// P(X >= statistic) for a chi-square variable with `dof` degrees of freedom.
double chi2_p_value(double statistic, int dof);
// Per-test significance so that `tests` independent tests keep `alpha` overall (Sidak).
double sidak_alpha(double alpha, int tests);

struct Chi2Result {
  double statistic = 0;
  int dof = 0;
  double p_value = 1;
  size_t pooled_cells = 0;  // cells with expected < min_expected merged into one
  std::string message;      // summary plus the worst cells, for INFO()
  bool accepts(double alpha) const { return p_value >= alpha; }
};

// Observed against expected counts. Cells with expected < min_expected are pooled into one
// cell (the smallest first); a sample in a cell of expected count 0 rejects outright.
Chi2Result chi2_test(const std::vector<double>& observed, const std::vector<double>& expected,
                     double min_expected = 5.0);

// Counts of 2D points in an nx x ny grid over [x0, x1) x [y0, y1), plus one last cell for
// points outside the grid (its expected count is 0, so any point there fails the test).
class Histogram2D {
 public:
  Histogram2D(double x0, double x1, int nx, double y0, double y1, int ny);
  void add(double x, double y);
  size_t cell_count() const { return counts_.size(); }
  const std::vector<double>& counts() const { return counts_; }
  double total() const { return total_; }
  // n_samples times the integral of `density` (per unit x, per unit y) over each cell, by the
  // midpoint rule on sub x sub points; 0 for the outside cell.
  std::vector<double> expected(const std::function<double(double, double)>& density, double n_samples,
                               int sub = 8) const;

 private:
  double x0_, x1_, y0_, y1_;
  int nx_, ny_;
  std::vector<double> counts_;
  double total_ = 0;
};

// Directions binned in (cos theta, phi) cells: equal solid angle, since dw = dcos dphi.
class SphereHistogram {
 public:
  SphereHistogram(int n_cos, int n_phi) : grid_(-1.0, 1.0, n_cos, 0.0, 2.0 * kPi64, n_phi) {}
  void add(const Vec3& w);
  const std::vector<double>& counts() const { return grid_.counts(); }
  // Expected counts for a solid-angle density pdf(w).
  std::vector<double> expected(const std::function<double(const Vec3&)>& pdf, double n_samples,
                               int sub = 8) const;

 private:
  Histogram2D grid_;
};

inline double sum(const std::vector<double>& v) {
  double s = 0;
  for (double x : v) s += x;
  return s;
}

}  // namespace caustica::test
