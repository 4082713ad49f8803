// The person's build, learnt from the silhouettes and kept as slowly varying state beside
// the particles: one width scale per region of the body (tracker/body/body_model.h: torso,
// head, arms, thighs, shins) and the limbs' lengths for the height
// (tracker/state/proportions.h: legs, arms). The particles' own width (state_model.h) is
// one scale on every part; with it alone, a coat's wide torso and thighs could only be
// explained by a body wide everywhere, whose fat shins then fit the gap between the legs
// badly; and their size is one scale on every bone, so a walker of short legs was drawn
// with the hips too high.
//
// The torso is the reference: the particles' width is the torso's width, their size its
// length, and the build gives the other regions' widths and the limbs' lengths relative
// to it (fitting the torso too would leave one direction free, all regions wider and the
// particles' width narrower, along which the fit drifts where the silhouettes are flat).
// After each frame explained well, each of these is tried `probe` larger and smaller on
// the frame's estimate. The parabola through the three costs (in the scale's logarithm)
// gives the step to its minimum (at most one probe; the probe's direction downhill when
// the parabola has no minimum), and the scale moves by `rate` of it.
//
// The floor under the person (a ramp, a floor the calibration puts a little off) is learnt
// the same way, in millimetres, when two cameras or more see the person: in one view a
// lower floor and a person farther away look alike.
//
// The garment (tracker/body/body_model.h: a cone from the hips round both thighs) is
// learnt the same way from 0, additively: without it a skirt's or a coat's cloth between
// the thighs could only be explained by legs spread apart and frozen there, and by
// thighs and shins at their widest bound (the skirted tuning walker: root-relative 54 ->
// 116 mm against the same walk bare). Its probe is a fifth of the scale at which the hem
// is 0.4 m across; it moves by half the step (garment_rate) so that it is grown within
// the start window (15 frames) before the legs are fitted to the cloth. It is drawn for the
// particles and the estimate (drawn()) only from garment_drawn on: below 0.5 the cone lies
// within what the thighs and the pelvis already cover and only fills the crotch, as mask
// blur does; bare walkers' garments wander there (a mean of 0.1, at most 0.5), and drawn,
// those small differences in cost sent some runs elsewhere (8 seeds, a bare 4-camera walk
// 36.2 -> 41.5 mm, a bare webcam walk 81.8 -> 93.9).
//
// Rule for the constants: a probe is about half the spread of what it measures, beyond
// the silhouettes' noise from one frame to the next: widths 10% (the realism clips' builds
// spread +-25%, tracker/clip/clip_body.h), lengths 4% (the CMU subjects' limbs, +-7%), the
// floor 20 mm (a floor calibration's error at 5 m: 0.25 degrees). The rate is 0.1, so the
// build settles in about ten frames, inside the start window (15 frames). The bounds:
// widths the builds' range widened by what a coat or a skirt adds (30%), lengths twice the
// subjects' spread, the floor 300 mm (a few steps).
#pragma once

#include <functional>
#include <string>
#include <vector>

#include "tracker/body/body_model.h"
#include "tracker/filter/likelihood.h"
#include "tracker/state/proportions.h"

namespace jgpm {

struct BodyShapeOptions {
  bool enabled = true;
  bool lengths = true;  // false: the limbs' lengths are known (the subject's own skeleton)
  double width_probe = 0.1, length_probe = 0.04;
  double rate = 0.1;
  double min_width = 0.7, max_width = 1.4;
  double min_length = 0.85, max_length = 1.15;
  double floor_probe_mm = 20, max_floor_mm = 300;
  bool garment = true;  // false: no garment is learnt (the build of the bare body)
  double garment_probe = 0.2, garment_rate = 0.5, max_garment = 1.5, garment_drawn = 0.5;

  bool Check(std::string* why) const;
};

struct Build {
  RegionScales widths = kUnitRegionScales;  // widths[torso] stays 1
  Proportions lengths;
  double floor_mm = 0;  // the floor's height under the person
  double garment = 0;   // tracker/body/body_model.h's garment scale (0: none)
  bool operator==(const Build&) const = default;
};

// What the fit minimises: over the cameras, the pixels where body and mask disagree,
// |S xor (O n R)|, as a share of the mask. Not the tracker's cost: its outline term charges
// a body a pixel too wide and not one a pixel too narrow (the outline then lies inside the
// mask, at distance 0), and its area term forgives a pixel either way, so on it every thin
// part narrows to its bound (seen on exact silhouettes: arms and shins at 0.70 for 0.83
// and 0.74). The plain disagreement is lowest at the true width.
double ShapeCost(const std::vector<CameraScore>& scores);

class BodyShape {
 public:
  explicit BodyShape(const BodyShapeOptions& options = {});

  const Build& build() const { return build_; }
  // The build as drawn: its garment 0 while under garment_drawn.
  Build drawn() const;
  // Back to the model's proportions and the average adult's widths (a new start).
  void Reset();
  // The frame's estimate's cost with each of the builds given (in any order; e.g. in
  // parallel).
  using Costs = std::function<std::vector<double>(const std::vector<Build>& builds)>;
  // One frame: asks the costs of the build as it is and of it with each scale fitted
  // larger and smaller (4 widths, 2 lengths unless known, the floor when `several_views`:
  // two cameras or more see the person, the garment; a garment probed below 0 draws none),
  // once. Costs that are not finite leave the build as it is.
  void Update(const Costs& costs, bool several_views = false);
  // The same, one build at a time.
  void Update(const std::function<double(const Build&)>& cost, bool several_views = false);

 private:
  BodyShapeOptions options_;
  Build build_;
};

}  // namespace jgpm
