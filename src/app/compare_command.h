// `caustica compare IMAGE REFERENCE [REFERENCE...] [--diff OUT.png] [--json]`: several
// references are independent renders of one scene, compared against as their mean, whose own
// noise (the floor) they estimate.
#pragma once
#include <string>
#include <vector>
#include "core/metrics.h"

namespace caustica {

struct CompareArgs {
  std::string image, diff;
  std::vector<std::string> references;
  bool json = false;
};

int run_compare(const CompareArgs& args);
// Reads the reference images and combines them (combine_references).
Reference read_references(const std::vector<std::string>& files);
// "a.exr" for one file, "mean of a.exr, b.exr" for several.
std::string describe_references(const std::vector<std::string>& files);
// The figures as text lines ("rmse: ...") or as one JSON object. With a reference of two or
// more renders, also its floor and the relMSE with the floor subtracted.
std::string format_metrics(const ErrorMetrics& m, bool json, const Reference* reference = nullptr);

}  // namespace caustica
