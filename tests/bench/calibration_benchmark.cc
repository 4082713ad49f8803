// Figures for calibration from walkers (calibration/walker_calibration.h): the fit of a
// crowd of 12 synthetic walkers, 60 frames each, seen by a camera 6 m over a plaza
// (tests/calibration/observed_walkers.h), with the jackknife over groups of walkers
// (WalkerCalibrationOptions::jackknife_groups, the argument) and without it (0): the
// jackknife's cost is the difference. One thread.
#include <benchmark/benchmark.h>

#include "calibration/walker_calibration.h"
#include "tests/calibration/observed_walkers.h"

namespace jgpm {
namespace {

void BM_CalibrateFromWalkers(benchmark::State& state) {
  const Camera truth = test::Placed(640, 480, 700, 6000, 28, 2.5);
  const std::vector<HeadFoot> points = test::Observe(truth, test::PlazaWalks(), 60, 0.7, 1);
  WalkerCalibrationOptions options;
  options.jackknife_groups = static_cast<int>(state.range(0));
  for (auto _ : state) benchmark::DoNotOptimize(CalibrateFromWalkers(points, 640, 480, options));
  state.counters["points"] = static_cast<double>(points.size());
}
BENCHMARK(BM_CalibrateFromWalkers)->Arg(0)->Arg(10)->Unit(benchmark::kMillisecond);

}  // namespace
}  // namespace jgpm

BENCHMARK_MAIN();
