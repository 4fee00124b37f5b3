// `caustica compare`.
#include "app/compare_command.h"
#include "app/stop_signals.h"
#include "io/image_io.h"
#include <iomanip>
#include <iostream>
#include <sstream>
#include <nlohmann/json.hpp>

namespace caustica {

Reference read_references(const std::vector<std::string>& files) {
  std::vector<Image> renders;
  for (const std::string& f : files) renders.push_back(read_image(f));
  Reference reference = combine_references(renders, files);
  if (reference.has_floor() && !(reference.floor > 0)) {
    std::cerr << "warning: the references (" << describe_references(files)
              << ") do not differ, so their floor cannot be estimated: give renders with different seeds\n";
  }
  return reference;
}

std::string describe_references(const std::vector<std::string>& files) {
  if (files.size() == 1) return files[0];
  std::string s = "mean of ";
  for (size_t i = 0; i < files.size(); ++i) s += (i ? ", " : "") + files[i];
  return s;
}

std::string format_metrics(const ErrorMetrics& m, bool json, const Reference* reference) {
  const bool floor = reference && reference->has_floor();
  if (json) {
    auto finite = [](double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
    nlohmann::json j = {{"rmse", m.rmse},
                        {"relmse", m.relmse},
                        {"mae", m.mae},
                        {"psnr", finite(m.psnr)},
                        {"max_error", m.max_error},
                        {"mean_image", {m.mean_image.r, m.mean_image.g, m.mean_image.b}},
                        {"mean_reference", {m.mean_reference.r, m.mean_reference.g, m.mean_reference.b}}};
    if (floor) {
      j["references"] = reference->renders;
      j["reference_floor"] = reference->floor;
      j["relmse_floor_free"] = m.relmse - reference->floor;
    }
    return j.dump() + "\n";
  }
  std::ostringstream s;
  s << std::setprecision(6);
  s << "rmse: " << m.rmse << "\nrelmse: " << m.relmse << "\nmae: " << m.mae << "\npsnr: " << m.psnr << " dB\n";
  s << "mean image: " << m.mean_image.r << " " << m.mean_image.g << " " << m.mean_image.b << "\n";
  s << "mean reference: " << m.mean_reference.r << " " << m.mean_reference.g << " " << m.mean_reference.b << "\n";
  if (floor) {
    s << "reference floor: " << reference->floor << " (the relMSE of the mean of " << reference->renders
      << " references, from their spread)\n";
    s << "relmse without the floor: " << m.relmse - reference->floor << "\n";
  }
  return s.str();
}

int run_compare(const CompareArgs& args) {
  if (!args.diff.empty()) check_output_path(args.diff);
  const Image image = read_image(args.image);
  const Reference reference = read_references(args.references);
  const ErrorMetrics m = compare_images(image, reference.mean, args.image, describe_references(args.references));
  if (!args.diff.empty()) {
    // A signal while the error map is written waits for it to be complete.
    StopSignals stop_signals;
    write_image(args.diff, error_map(image, reference.mean));
    stop_signals.restore();
    if (StopSignals::stopped()) return StopSignals::exit_code();
  }
  std::cout << format_metrics(m, args.json, &reference);
  return 0;
}

}  // namespace caustica
