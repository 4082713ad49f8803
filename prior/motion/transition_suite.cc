#include "prior/motion/transition_suite.h"

#include <cmath>
#include <cstdio>
#include <optional>
#include <sstream>

#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "io/gait/split.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"

namespace jgpm {
namespace {

struct Trial {
  MotionInput whole;  // the whole trial at its own rate
  int event = 0;      // row of the event in whole.motion
};

Trial ReadTrial(const TransitionEvent& event, const std::filesystem::path& root, const TransitionRules& rules) {
  TrialId id;
  ParseTrialId(event.trial, &id);
  Trial t;
  const std::filesystem::path asf = TrialAsfPath(root, id), amc = TrialAmcPath(root, id);
  t.whole.asf_text = ReadTextFile(asf, "an ASF skeleton");
  t.whole.skeleton = ParseAsf(t.whole.asf_text, asf.string());
  t.whole.motion = ReadAmc(amc, t.whole.skeleton);
  t.whole.source = amc.string();
  if (event.frame_number) {
    t.event = *event.frame_number - t.whole.motion.first_frame_number;
    if (t.event < 0 || t.event >= t.whole.motion.NumFrames()) {
      ThrowInputError(amc.string(), "has no frame " + std::to_string(*event.frame_number) + " (line " +
                                        std::to_string(event.line) + " of the event list)");
    }
  } else {
    t.event = FindTransitionFrame(t.whole.skeleton, t.whole.motion, event.kind, rules, amc.string());
  }
  return t;
}

// Rows [first, first + count * step) every `step`-th, as a motion input.
MotionInput Cut(const MotionInput& whole, int first, int count, int step) {
  MotionInput in{whole.skeleton, whole.asf_text, {}, whole.source};
  in.motion.values = RowMatrixXd(count, whole.motion.values.cols());
  for (int i = 0; i < count; ++i) in.motion.values.row(i) = whole.motion.values.row(first + i * step);
  in.motion.frames_per_second = whole.motion.frames_per_second / step;
  in.motion.first_frame_number = whole.motion.first_frame_number + first;
  return in;
}

// Frames [first - 8, first + n + 8) of a motion at 30 fps.
Motion Around(const RowMatrixXd& frames, int first, int n, double fps) {
  const int from = std::max(0, first - 8), to = std::min<int>(static_cast<int>(frames.rows()), first + n + 8);
  Motion m;
  m.values = frames.middleRows(from, to - from);
  m.frames_per_second = fps;
  return m;
}

void Accumulate(TransitionMeasures* sum, const TransitionMeasures& m, double w) {
  sum->eq23_mean_mm += w * m.eq23_mean_mm;
  sum->eq23_root_aligned_mean_mm += w * m.eq23_root_aligned_mean_mm;
  sum->l2p_m += w * m.l2p_m;
  sum->l2q += w * m.l2q;
  sum->npss += w * m.npss;
  sum->foot_skate_mps += w * m.foot_skate_mps;
  sum->true_foot_skate_mps = m.true_foot_skate_mps;
  for (int s = 0; s < 2; ++s) {
    sum->seam_jump_mps[s] += w * m.seam_jump_mps[s];
    sum->true_seam_jump_mps[s] = m.true_seam_jump_mps[s];
  }
  if (sum->eq23_mm.empty()) sum->eq23_mm.assign(m.eq23_mm.size(), 0.0);
  if (sum->eq23_root_aligned_mm.empty()) sum->eq23_root_aligned_mm.assign(m.eq23_root_aligned_mm.size(), 0.0);
  for (size_t i = 0; i < m.eq23_mm.size(); ++i) {
    sum->eq23_mm[i] += w * m.eq23_mm[i];
    sum->eq23_root_aligned_mm[i] += w * m.eq23_root_aligned_mm[i];
  }
}

}  // namespace

TransitionSuiteResult RunTransitionSuite(const std::vector<TransitionEvent>& events,
                                         const std::filesystem::path& data_root,
                                         const TransitionSuiteOptions& options,
                                         const TransitionSuiteProgress& progress) {
  if (options.random_seeds < 1 || options.context < 3) {
    ThrowInputError("transition suite options", "random_seeds must be >= 1 and context >= 3");
  }
  const int total = static_cast<int>(events.size() * options.shifts.size() * options.frames.size());
  int done = 0;
  TransitionSuiteResult result;
  for (const TransitionEvent& event : events) {
    const Trial trial = ReadTrial(event, data_root, options.rules);
    const int step =
        ResampleStep(trial.whole.motion.frames_per_second, options.transition.frames_per_second, trial.whole.source);
    const Skeleton& skeleton = trial.whole.skeleton;
    const std::vector<int> feet = skeleton.FootBones();
    const Kinematics kinematics(skeleton);
    // First row of the 30 fps window (A, the truth's N, B) of a case, when it is within the trial.
    const auto window_start = [&](int shift, int n) -> std::optional<int> {
      const int first_a = trial.event + shift * step - (n / 2 + options.context) * step;
      const int count = 2 * options.context + n;
      if (first_a < 0 || first_a + (count - 1) * step >= trial.whole.motion.NumFrames()) return std::nullopt;
      return first_a;
    };
    // The strip's case: shift 0 and the middle N, else the first N that fits.
    int strip_n = -1;
    for (const int n : options.frames) {
      if (window_start(0, n) && (strip_n < 0 || n == options.frames[options.frames.size() / 2])) strip_n = n;
    }
    for (const int shift : options.shifts) {
      for (const int n : options.frames) {
        const std::string label = event.trial + " " + std::string(TransitionKindName(event.kind)) + " shift " +
                                  std::to_string(shift) + " N " + std::to_string(n);
        if (progress) progress(done, total, label);
        ++done;
        // Rows of the 30 fps window: A, the truth's N, B.
        const std::optional<int> start = window_start(shift, n);
        if (!start) {
          ++result.skipped;
          continue;
        }
        const int first_a = *start, count = 2 * options.context + n;
        const MotionInput window = Cut(trial.whole, first_a, count, step);
        const MotionInput a = Cut(trial.whole, first_a, options.context, step);
        const MotionInput b = Cut(trial.whole, first_a + (options.context + n) * step, options.context, step);
        const RowMatrixXd truth = window.motion.values.middleRows(options.context, n);  // for the oracle
        TransitionWindow measure;
        measure.first = options.context;
        measure.frames = n;
        measure.frames_per_second = options.transition.frames_per_second;
        measure.floor_mm = 1e300;
        for (int f = 0; f < count; ++f) {
          const Eigen::Matrix3Xd joints = kinematics.Compute(window.motion.Frame(f));
          for (int foot : feet) measure.floor_mm = std::min(measure.floor_mm, joints(1, foot));
        }
        if (feet.empty()) measure.floor_mm = -1e9;
        const bool strip = shift == 0 && n == strip_n;
        if (strip) {
          result.strips.push_back({event.trial, event.kind, skeleton, {}});
          result.strips.back().motions.emplace_back(
              "truth", Around(window.motion.values, options.context, n, measure.frames_per_second));
        }
        for (const TransitionMethod method : options.methods) {
          const int seeds = method == TransitionMethod::kRandom ? options.random_seeds : 1;
          TransitionSuiteRow row;
          row.trial = event.trial;
          row.kind = event.kind;
          row.tune = event.tune;
          row.event_frame = trial.whole.motion.first_frame_number + trial.event;
          row.shift = shift;
          row.frames = n;
          row.method = method;
          std::vector<double> eq23;
          for (int seed = 1; seed <= seeds; ++seed) {
            MotionTransitionOptions o = options.transition;
            o.method = method;
            o.context = options.context;
            o.transition.path.frames = n;
            o.transition.seed = static_cast<uint64_t>(seed);
            const MotionTransitionResult generated = TransitionBetween(a, b, o, &truth);
            const TransitionMeasures m = MeasureTransition(skeleton, window.motion.values, generated.motion.values, measure);
            Accumulate(&row.measures, m, 1.0 / seeds);
            row.seconds += generated.seconds / seeds;
            row.retrain_change_deg = generated.retrain_change_deg;
            row.retrain_latent_shift = generated.retrain_latent_shift;
            eq23.push_back(m.eq23_root_aligned_mean_mm);
            if (strip && seed == 1) {
              result.strips.back().motions.emplace_back(
                  std::string(TransitionMethodName(method)),
                  Around(generated.motion.values, options.context, n, measure.frames_per_second));
            }
          }
          double var = 0;
          for (double v : eq23) {
            const double d = v - row.measures.eq23_root_aligned_mean_mm;
            var += d * d / eq23.size();
          }
          row.eq23_std_mm = std::sqrt(var);
          result.rows.push_back(std::move(row));
        }
      }
    }
  }
  if (progress) progress(done, total, "done");
  return result;
}

std::string TransitionSuiteCsv(const TransitionSuiteResult& result) {
  std::ostringstream csv;
  csv << "trial,kind,tune,event_frame,shift,N,method,eq23_mm,eq23_std_mm,eq23_world_mm,l2p_m,l2q,npss,"
         "foot_skate_mps,true_foot_skate_mps,seam1_jump_mps,seam2_jump_mps,true_seam1_jump_mps,true_seam2_jump_mps,"
         "seconds,retrain_change_deg,retrain_latent_shift\n";
  char line[512];
  for (const TransitionSuiteRow& r : result.rows) {
    const TransitionMeasures& m = r.measures;
    std::snprintf(line, sizeof line,
                  "%s,%s,%s,%d,%d,%d,%s,%.3f,%.3f,%.3f,%.5f,%.5f,%.5f,%.4f,%.4f,%.4f,%.4f,%.4f,%.4f,%.3f,%.4f,%.5f\n",
                  r.trial.c_str(), std::string(TransitionKindName(r.kind)).c_str(), r.tune ? "yes" : "no", r.event_frame, r.shift,
                  r.frames, std::string(TransitionMethodName(r.method)).c_str(), m.eq23_root_aligned_mean_mm, r.eq23_std_mm,
                  m.eq23_mean_mm, m.l2p_m, m.l2q, m.npss, m.foot_skate_mps, m.true_foot_skate_mps,
                  m.seam_jump_mps[0], m.seam_jump_mps[1], m.true_seam_jump_mps[0], m.true_seam_jump_mps[1], r.seconds,
                  r.retrain_change_deg, r.retrain_latent_shift);
    csv << line;
  }
  return csv.str();
}

}  // namespace jgpm
