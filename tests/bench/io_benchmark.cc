// Figures for the io layer: forward kinematics per frame (the tracker calls it per
// particle) and AMC parsing throughput.
#include <benchmark/benchmark.h>

#include "io/base/text_reader.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "test_support.h"

namespace jgpm {
namespace {

void BM_ForwardKinematics(benchmark::State& state) {
  const Skeleton s = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  const Motion m = ReadAmc(test::CmuRoot() / "subjects/35/35_01.amc", s);
  const Kinematics fk(s);
  Eigen::Matrix3Xd joints;
  int f = 0;
  for (auto _ : state) {
    fk.Compute(m.Frame(f), &joints);
    benchmark::DoNotOptimize(joints.data());
    f = (f + 1) % m.NumFrames();
  }
  state.SetItemsProcessed(state.iterations());
}
BENCHMARK(BM_ForwardKinematics);

void BM_ParseAmc(benchmark::State& state) {
  const Skeleton s = ReadAsf(test::CmuRoot() / "subjects/35/35.asf");
  const std::string text = ReadTextFile(test::CmuRoot() / "subjects/35/35_01.amc", "amc");
  for (auto _ : state) {
    const Motion m = ParseAmc(text, "35_01.amc", s);
    benchmark::DoNotOptimize(m.values.data());
  }
  state.SetBytesProcessed(state.iterations() * static_cast<int64_t>(text.size()));
}
BENCHMARK(BM_ParseAmc);

}  // namespace
}  // namespace jgpm

BENCHMARK_MAIN();
