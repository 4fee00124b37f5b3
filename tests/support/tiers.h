// The test tiers. Every test case carries exactly one of these tags (tests/support/tiers.cpp
// checks it), and CMake registers each tier with CTest under its label (ctest -L unit):
//   TIER_UNIT     maths, sampling, chi-square tests, readers, errors, small renders: seconds;
//   TIER_FIGURE   images held to figures: photon against path, media against references,
//                 convergence;
//   TIER_PROCESS  runs of the caustica executable, MPI, the browser, the notebook.
// Built with the sanitizers (CAUSTICA_FIGURES_REDUCED), the figure tier runs reduced: its
// renders are cut down to what exercises the code (figure_reduced_spp and the photon counts in
// render_text), and its figures are reported but do not fail ([!mayfail]); the Release suite
// holds them to their figures.
#pragma once
#include <string>

#define TIER_UNIT "[unit]"
#define TIER_PROCESS "[process]"
#ifdef CAUSTICA_FIGURES_REDUCED
#define TIER_FIGURE "[figure][!mayfail]"
#else
#define TIER_FIGURE "[figure]"
#endif

namespace caustica::test {

#ifdef CAUSTICA_FIGURES_REDUCED
constexpr bool kFiguresReduced = true;
#else
constexpr bool kFiguresReduced = false;
#endif

// True while a figure-tier test case runs in a reduced build: renders are then cut down.
bool figure_reduced();
// The samples per pixel a test render takes: `spp`, or at most 2 while figure_reduced().
int figure_spp(int spp);
// Integrator settings with their photon counts cut to at most 20000 while figure_reduced().
std::string figure_settings(const std::string& settings_json);

}  // namespace caustica::test
