#include "tracker/filter/likelihood.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "io/base/error.h"
#include "tracker/body/cast_shadow.h"
#include "tracker/filter/occluder_layers.h"

namespace jgpm {
namespace {

// |S|, |S n M| and |S n grow(M)| over `rows` rows of `words` words, `stride` words apart.
// Compiled for the POPCNT instruction too (jgpm's baseline x86-64 lacks it; every x86-64
// CPU since 2008 has it), picked at load time, as prior/numerics/rbf_row.h does for its
// vector width.
__attribute__((target_clones("popcnt", "default"))) void CountBits(const uint64_t* s, const uint64_t* m,
                                                                   const uint64_t* grown_m, int rows, int words,
                                                                   int stride, int* model, int* overlap,
                                                                   int* inside_grown) {
  int a = 0, b = 0, c = 0;
  for (int v = 0; v < rows; ++v) {
    const size_t row = static_cast<size_t>(v) * stride;
    for (int k = 0; k < words; ++k) {
      a += __builtin_popcountll(s[row + k]);
      b += __builtin_popcountll(s[row + k] & m[row + k]);
      c += __builtin_popcountll(s[row + k] & grown_m[row + k]);
    }
  }
  *model += a;
  *overlap += b;
  *inside_grown += c;
}

// |grow(S) n M| of one row, from grow(S)'s row.
__attribute__((target_clones("popcnt", "default"))) int CountAnd(const uint64_t* a, const uint64_t* b, int words) {
  int n = 0;
  for (int k = 0; k < words; ++k) n += __builtin_popcountll(a[k] & b[k]);
  return n;
}

}  // namespace

bool LikelihoodOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(outline_weight >= 0)) problem = "outline_weight must be >= 0";
  else if (!(truncation_px > 0)) problem = "truncation_px must be > 0";
  else if (!(outline_step_px > 0)) problem = "outline_step_px must be > 0";
  else if (!(min_foreground_px > 0)) problem = "min_foreground_px must be > 0";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

double CameraScore::Iou() const {
  const int joined = model_px + observed_px - overlap_px;
  return joined > 0 ? static_cast<double>(overlap_px) / joined : 0.0;
}

SilhouetteLikelihood::SilhouetteLikelihood(const std::vector<Camera>& cameras, const LikelihoodOptions& options)
    : options_(options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("likelihood options", why);
  for (const Camera& camera : cameras) {
    renderers_.emplace_back(camera);
    centres_.push_back(camera.CentreInWorld());
  }
}

SilhouetteLikelihood::Workspace SilhouetteLikelihood::NewWorkspace() const {
  Workspace w;
  for (const BitSilhouetteRenderer& r : renderers_) w.canvas.emplace_back(r.camera().width, r.camera().height);
  w.outline.reserve(2048);
  return w;
}

CameraObservation SilhouetteLikelihood::Observe(const cv::Mat& mask, const cv::Rect& region,
                                                const cv::Mat& hidden) const {
  return CameraObservation(mask, region, options_.truncation_px, options_.max_hole_px, hidden);
}

const CameraObservation& SilhouetteLikelihood::Seen(const CameraObservation& observation,
                                                   const Eigen::Vector3d& feet, size_t camera) const {
  const std::vector<PaintedObject>& objects = observation.painted_objects();
  unsigned subset = 0;
  for (size_t j = 0; j < objects.size(); ++j)
    if (Hides(objects[j], feet, centres_[camera])) subset |= 1u << j;
  return observation.WithHidden(subset);
}

double SilhouetteLikelihood::Cost(const std::vector<Capsule>& capsules,
                                  const std::vector<CameraObservation>& observations, Workspace* w,
                                  std::vector<CameraScore>* scores) const {
  return CostUnder(light_ ? &*light_ : nullptr, capsules, observations, w, scores);
}

double SilhouetteLikelihood::CostUnder(const Eigen::Vector3d* light, const std::vector<Capsule>& capsules,
                                       const std::vector<CameraObservation>& observations, Workspace* w,
                                       std::vector<CameraScore>* scores) const {
  JGPM_CHECK(observations.size() == renderers_.size());
  if (scores) scores->assign(renderers_.size(), CameraScore());
  double total = 0;
  std::optional<Eigen::Vector3d> feet;  // where the body stands, once a camera has painted objects
  for (size_t c = 0; c < renderers_.size(); ++c) {
    // Painted occluders hide only a body behind them (occluder_layers.h).
    if (observations[c].layered() && !feet) feet = FloorPointUnder(capsules);
    const CameraObservation& o = observations[c].layered() ? Seen(observations[c], *feet, c) : observations[c];
    BitMask& canvas = w->canvas[c];
    w->outline.clear();
    renderers_[c].Draw(capsules, &canvas, &w->outline, options_.outline_step_px);
    // The shadow only where the person is expected: the area term counts nothing beyond.
    if (light && !o.empty()) DrawCastShadow(renderers_[c].projector(), capsules, *light, floor_mm_, o.region(), &canvas);
    // |S|, |S n O n R|, |S n grow(O n R)| over the rows drawn, |grow(S) n O n R| over them
    // and a row either side; then the canvas is blank again.
    int model = 0, overlap = 0, inside = 0, explained = 0;
    const int rows_drawn = canvas.last_row() - canvas.first_row();
    const int words = canvas.words_per_row();
    const bool observed = !o.empty();
    if (canvas.last_row() > canvas.first_row()) {
      if (observed) {
        // Over the words the body touched, and for grow(S) a word either side.
        const int w0 = canvas.first_word(), w1 = canvas.last_word();
        const int v0 = canvas.first_row();
        CountBits(canvas.row(v0) + w0, o.region_bits().row(v0) + w0, o.region_bits_grown().row(v0) + w0, rows_drawn,
                  w1 - w0, words, &model, &overlap, &inside);
        w->grown_row.resize(words);
        const int g0 = std::max(0, w0 - 1), g1 = std::min(words, w1 + 1);
        for (int v = std::max(0, canvas.first_row() - 1); v < std::min(canvas.height(), canvas.last_row() + 1); ++v) {
          canvas.DilatedRow(v, g0, g1, w->grown_row.data());
          explained += CountAnd(w->grown_row.data() + g0, o.region_bits().row(v) + g0, g1 - g0);
        }
      } else {
        model = canvas.Count();
      }
    }
    canvas.Clear();
    CameraScore score;
    score.model_px = model;
    score.model_rows = rows_drawn;
    score.overlap_px = overlap;
    score.observed_px = observed ? o.region_count() : 0;
    score.outside_px = model - inside;
    score.unexplained_px = score.observed_px - explained;
    const double normaliser = std::max<double>(score.observed_px, options_.min_foreground_px);
    score.area = (score.outside_px + score.unexplained_px) / normaliser;
    // Only the outline's points in the image (likelihood.h): counted beyond its edges as far
    // from any foreground, they pulled a walker leaving a webcam's view back into it.
    int outline_seen = 0;
    double sum = 0;
    if (observed) {
      for (const Eigen::Vector2f& p : w->outline) {
        if (!o.InImage(p.x(), p.y())) continue;
        sum += o.DistanceToForeground(p.x(), p.y());
        ++outline_seen;
      }
    }
    if (outline_seen > 0) {
      score.outline = sum / (outline_seen * o.truncation_px());
    } else {
      score.outline = score.observed_px > 0 ? 1.0 : 0.0;  // nothing drawn: no outline near the person
    }
    score.raw = score.area + options_.outline_weight * score.outline;
    const double bound = 2 + options_.outline_weight;
    if (!options_.bound_cameras) {
      score.cost = score.raw;
    } else if (model == 0 && score.observed_px >= options_.min_foreground_px) {
      score.cost = bound;  // the body left a view that sees someone where it was expected
    } else {
      score.cost = bound * -std::expm1(-score.raw / bound);
    }
    total += score.cost;
    if (scores) (*scores)[c] = score;
  }
  return total;
}

}  // namespace jgpm
