// A glossy floor (a polished hall, a wet street) mirrors each walker below their feet, and
// a background subtraction keeps the mirror image wherever it differs from the floor (MOG2's
// shadow test drops a reflection darker than the floor, not a brighter or coloured one).
// The masks then show a blob up to twice a person's height: the person locator read the
// reflection's bottom as the feet and placed the walker metres nearer and shorter, and the
// likelihood asked the body to explain the mirror image (`07_03`, 2 cameras, reflectance
// 0.3, the clip's observed masks: 1298-2237 mm against 35-37 without the reflection).
//
// The cut, per blob (body_blobs.h: a reflection broken at the feet is joined to its
// walker), by the camera. A row r of the blob is tried as where the feet touch the floor
// when an adult stands there: the blob's top, above the floor point under the blob's axis
// at r, is kMinAdultMm-kMaxAdultMm up, and nearer kAdultHeightMm by stature_margin standard
// deviations than the whole blob standing on its bottom row would be; the blob is one
// person wide there (max_width_mm) and reaches below r at least min_extent as far as
// above it (unless the image's bottom edge cuts it). The floor mirrors the vertical line
// through that floor point onto itself (height y to -y), so each of the blob's pixels
// below r has a mirror pixel above it; r's share is the mean, over those pixels, of how
// well their mirror lands on the blob (1 on it, falling to 0 at `grow`; 0 more than half
// a person's width from the line). The best row (the share, less kStaturePerSd2 per
// squared standard deviation of the adult's height from the mean) is the feet when its
// share is at least min_share, and the blob's pixels below it are taken out of the mask.
//
// Why a walker without a reflection is left alone: the whole walker standing on their
// feet is an adult already, and a row higher up (the knees, the hips) is an adult only
// from a camera near head height, and never nearer the mean by two standard deviations;
// what lies under a walker's feet that is not a reflection (a shadow cast towards the
// camera, someone nearer seen from above) mirrors onto them only now and then, which the
// glossy-floor decision below leaves alone. The rendered clips' feet sink up to 40 mm
// into the floor, below the mirror plane: those rows go with the reflection.
//
// What it does not do: from one camera between about 1.4 and 2.2 m up (a phone held at
// the chest) the whole blob standing on its bottom is itself an adult's height within two
// standard deviations (the ring's glossy 07_03: 1.58 m against 1.64 m with the reflection
// cut), so one view cannot tell a reflection from legs and nothing is cut; two cameras can
// (FloorReflectionSource). A guessed camera is not used (track_job.cc). The people are
// adults (a child with a reflection is not cut), and a reflection merged with another
// walker's blob is not cut.
#pragma once

#include <deque>
#include <limits>
#include <memory>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "calibration/camera.h"
#include "tracker/frames/body_blobs.h"
#include "tracker/frames/frame_source.h"

namespace jgpm {

// An adult's height, the mean +- 3.5 standard deviations (body_blobs.h).
constexpr double kMinAdultMm = kAdultHeightMm - 3.5 * kAdultSpreadMm;
constexpr double kMaxAdultMm = kAdultHeightMm + 3.5 * kAdultSpreadMm;

struct FloorReflectionOptions {
  // The share below the feet that must mirror onto the person. The glossy suite's frames
  // tried score 0.8-1.0 at their best row (mostly above 0.9), the shadows of the realism
  // and crowd suites 0.75-0.98; the glossy-floor decision, not this, tells them apart.
  double min_share = 0.8;
  // How far below the feet the blob must reach, against how far above: a walker's shins
  // are about a third of the rest, a mirror image's extent the person's own.
  double min_extent = 0.5;
  // A mirror pixel counts within this share of the blob's height of the blob: each foot
  // is mirrored about its own contact row, and the legs stand at other depths than the
  // body's axis (a leg 0.3 m nearer at 4 m: 5 px of 200 off).
  double grow = 0.04;
  int min_blob_px = 60;   // the person locator's smallest blob
  // How much nearer an adult's mean height (in standard deviations) the person above the
  // cut must be than the whole blob standing on the floor (below).
  double stature_margin = 2;
  // A person's widest: a stride seen from the side with the arms swinging is 0.8-1 m.
  double max_width_mm = 1200;
  // Also find each blob's best row with the stature margin waived (ReflectionCut's
  // proposed_mm), for several cameras to check against each other (FloorReflectionSource).
  bool propose = false;
};

struct ReflectionCut {
  int tried = 0;   // blobs tried (a person's size, clear of the top and side edges)
  int blobs = 0;   // blobs whose reflection was cut
  int pixels = 0;  // pixels taken out
  double best_share = 0;  // the best row's share of any blob, cut or not (0: no row tried)
  // With FloorReflectionOptions::propose, the last blob tried: where it stands on the
  // floor (x, z, mm) on its bottom row, and at its best row whose mirror fits with the
  // stature margin waived (NaN: none).
  Eigen::Vector2d whole_mm = Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector2d proposed_mm = whole_mm;
};

// Takes each blob's reflection in the floor out of `mask` (CV_8UC1, nonzero foreground) seen
// by `camera` (of the mask's size). The mask is written only when something is cut (a
// fresh copy then: frames share their masks).
ReflectionCut CutFloorReflections(const Camera& camera, cv::Mat* mask, const FloorReflectionOptions& options = {});

// A glossy floor is the scene's, not a frame's, nor one camera's: the masks are cut once
// the floor is taken for glossy, when at least `glossy_share` of the cameras that had a
// blob to try in min_glossy_frames frames or more found a reflection in at least
// `glossy_share` of those frames (counted over the frames so far and, unless live, the
// first lookahead_frames read ahead, so that a clip is cut from its first frame). A glossy
// floor shows every walker's reflection to every camera in nearly every frame (the glossy
// suite's cameras: 81-100% of the frames tried); a shadow cast towards one camera looks
// like one to that camera alone (35_33-all-surveillance: 98% in one camera of four, 0%
// in the others; 3-crossing-surveillance: 82% and 0%), two people one behind the other
// only now and then (the plaza clip 5%; `vtest.avi` about 1%, where the cut took the legs
// of walkers passing in front of others). One camera alone cannot tell a shadow cast
// towards it from a reflection, and cuts it: what lies below the feet either way.
//
// Cameras near head height (about 1.4-2.2 m up) find no row nearer an adult than the whole
// blob (above), but two of them can tell: where each one's blob stands on its bottom row
// is pulled towards that camera by a reflection, differently for each, while the feet
// under the mirror rows are one place. So with two cameras or more, each one's single
// blob also proposes its best mirror row with the stature margin waived (propose), and
// when the proposed feet agree within kAgreeMm while the bottoms disagree by twice that,
// the proposals are cut too. The floor is also taken for glossy when such frames are
// glossy_share of the frames with two proposals or more (min_glossy_frames at least):
// the glossy suite's 2- and 4-camera clips 57-100% of their frames, all of the frames
// with two proposals; the clean, realism, tuning, held-out and crowd suites none (the
// ring clips propose the hips or the knees in up to every frame, whose feet disagree).
struct GlossyFloorOptions {
  double glossy_share = 2.0 / 3;
  int min_glossy_frames = 10;
  int lookahead_frames = 30;  // 1 s at 30 fps, as the working resolution's
  // Past the frames read ahead, while the floor is not glossy, every this many frames are
  // tried (a floor does not change by the frame; trying one 320x240 mask costs about 0.4
  // ms, most of it its connected components, BM_CutFloorReflections).
  int try_every = 5;
};

// `inner`'s frames with every glossy camera's reflections cut from its masks.
class FloorReflectionSource : public FrameSource {
 public:
  FloorReflectionSource(std::unique_ptr<FrameSource> inner, bool live, const GlossyFloorOptions& glossy = {},
                        const FloorReflectionOptions& options = {});

  const std::vector<Camera>& cameras() const override { return inner_->cameras(); }
  double fps() const override { return inner_->fps(); }
  int NumFrames() const override { return inner_->NumFrames(); }
  bool Next(Frame* frame) override;
  double mask_scale(size_t camera) const override { return inner_->mask_scale(camera); }
  FrameSource* inner() const { return inner_.get(); }
  // Frames in which some camera had a reflection cut.
  int frames_cut() const { return frames_cut_; }
  // Whether the floor is taken for glossy now.
  bool Glossy() const;

 private:
  struct Read {
    Frame frame;
    std::vector<cv::Mat> cut;  // per camera: the masks with reflections cut (empty: none found)
  };
  Read ReadOne(Frame frame);

  std::unique_ptr<FrameSource> inner_;
  GlossyFloorOptions glossy_;
  FloorReflectionOptions options_;
  std::vector<Camera> at_mask_size_;  // per camera, scaled to its masks
  std::vector<int> tried_, found_;    // per camera: frames with a blob tried, with a reflection
  int proposed_ = 0, agreed_ = 0;     // frames with two proposals or more, with them agreeing
  std::deque<Read> ahead_;
  int frames_cut_ = 0;
  long read_ = 0;  // frames read from `inner_`
};

}  // namespace jgpm
