// The self-contained HTML report of `caustica converge` (DIR/index.html).
#pragma once
#include <string>
#include <utility>
#include <vector>

namespace caustica {

struct ReportImage {
  std::string label;  // e.g. "reference", "photon", "photon error"
  std::string file;   // a PNG file inside the report folder (relative name)
};

struct ReportPoint {
  double seconds = 0;
  double relmse = 0;
  double rmse = 0;
  long passes = 0;
};

struct ReportSeries {
  std::string integrator;
  std::vector<ReportPoint> points;  // in time order
};

struct ReportData {
  std::string title;                                      // e.g. "cornell-spheres.json, 60 s per integrator"
  std::vector<std::pair<std::string, std::string>> facts;  // key/value lines shown in a table
  std::vector<ReportImage> images;
  std::vector<ReportSeries> series;
};

// How fast a series still converges: the least-squares slope of log relMSE against log time
// over its points from a quarter of its last time on (relMSE ~ t^slope; -1 for pure noise,
// near 0 where a bias floor is reached). NaN with fewer than two such points.
double convergence_slope(const ReportSeries& series);

// Writes DIR/index.html: opens from the file system with no server and no network.
// Throws InputError when the folder cannot be written.
void write_report(const std::string& dir, const ReportData& data);

}  // namespace caustica
