// `caustica compare`.
#include "app/compare_command.h"
#include <iomanip>
#include <iostream>
#include <sstream>
#include <nlohmann/json.hpp>

namespace caustica {

std::string format_metrics(const ErrorMetrics& m, bool json) {
  if (json) {
    auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    nlohmann::json j = {{"rmse", m.rmse},
                        {"relmse", m.relmse},
                        {"mae", m.mae},
                        {"psnr", finite(m.psnr)},
                        {"max_error", m.max_error},
                        {"mean_image", {m.mean_image.r, m.mean_image.g, m.mean_image.b}},
                        {"mean_reference", {m.mean_reference.r, m.mean_reference.g, m.mean_reference.b}}};
    return j.dump() + "\n";
  }
  std::ostringstream s;
  s << std::setprecision(6);
  s << "rmse: " << m.rmse << "\nrelmse: " << m.relmse << "\nmae: " << m.mae << "\npsnr: " << m.psnr << " dB\n";
  s << "mean image: " << m.mean_image.r << " " << m.mean_image.g << " " << m.mean_image.b << "\n";
  s << "mean reference: " << m.mean_reference.r << " " << m.mean_reference.g << " " << m.mean_reference.b << "\n";
  return s.str();
}

int run_compare(const CompareArgs& args) {
  if (!args.diff.empty()) check_output_path(args.diff);
  const Image image = read_image(args.image);
  const Image reference = read_image(args.reference);
  const ErrorMetrics m = compare_images(image, reference, args.image, args.reference);
  if (!args.diff.empty()) write_image(args.diff, error_map(image, reference));
  std::cout << format_metrics(m, args.json);
  return 0;
}

}  // namespace caustica
