// `caustica compare IMAGE REFERENCE [--diff OUT.png] [--json]`.
#pragma once
#include <string>
#include "core/metrics.h"

namespace caustica {

struct CompareArgs {
  std::string image, reference, diff;
  bool json = false;
};

int run_compare(const CompareArgs& args);
// The figures as text lines ("rmse: ...") or as one JSON object.
std::string format_metrics(const ErrorMetrics& m, bool json);

}  // namespace caustica
