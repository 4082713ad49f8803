#include "tracker/frames/floor_reflection.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "tracker/frames/body_blobs.h"
#include "tracker/frames/working_resolution.h"

namespace jgpm {
namespace {

// How much mirror share one standard deviation of stature is worth, squared: a tie-break
// between rows whose mirrors fit within a few hundredths (a trunk or a leg is straight, so
// its mirror fits at any row along it).
constexpr double kStaturePerSd2 = 0.02;

// Cameras' readings of one person's place agree within this (the person locator's error
// between cameras, TrackerOptions' other_floors_mm).
constexpr double kAgreeMm = 300;

// The largest distance between two of `points`.
double Spread(const std::vector<Eigen::Vector2d>& points) {
  double spread = 0;
  for (size_t i = 0; i < points.size(); ++i)
    for (size_t j = i + 1; j < points.size(); ++j) spread = std::max(spread, (points[i] - points[j]).norm());
  return spread;
}

// The mirror across the floor of the image rows below row r: for each row v in
// (r, last], the row and column shift of its mirror pixel on the vertical line through
// the feet's floor point, and the line's column there.
struct RowMirror {
  std::vector<int> row;       // mirror row (-1: the mirror is beyond what was sampled)
  std::vector<double> shift;  // mirror column minus the line's column at v
  std::vector<double> line;   // the line's column at v
};

// The image of the vertical line through `floor` from height -reach to reach (mm), sampled
// in steps; the rows below r are mapped by interpolating the line's negative half.
std::optional<RowMirror> MirrorRows(const Camera& camera, const Eigen::Vector3d& floor, double reach, int r, int last) {
  constexpr int kSamples = 64;
  std::vector<Eigen::Vector2d> down(kSamples + 1), up(kSamples + 1);
  for (int k = 0; k <= kSamples; ++k) {
    const double y = reach * k / kSamples;
    if (!camera.Project(Eigen::Vector3d(floor.x(), -y, floor.z()), &down[k]) ||
        !camera.Project(Eigen::Vector3d(floor.x(), y, floor.z()), &up[k]))
      return std::nullopt;
  }
  RowMirror mirror;
  mirror.row.assign(std::max(0, last - r), -1);
  mirror.shift.assign(mirror.row.size(), 0);
  mirror.line.assign(mirror.row.size(), 0);
  int k = 0;
  for (int v = r + 1; v <= last; ++v) {
    const double centre = v;  // the row's pixel centre
    while (k < kSamples && down[k + 1].y() < centre) ++k;
    if (k >= kSamples || down[k + 1].y() <= down[k].y()) break;  // beyond the sampled reach
    const double t = std::clamp((centre - down[k].y()) / (down[k + 1].y() - down[k].y()), 0.0, 1.0);
    const Eigen::Vector2d at = down[k] + t * (down[k + 1] - down[k]);
    const Eigen::Vector2d image = up[k] + t * (up[k + 1] - up[k]);
    mirror.row[v - r - 1] = static_cast<int>(std::lround(image.y()));
    mirror.shift[v - r - 1] = image.x() - at.x();
    mirror.line[v - r - 1] = at.x();
  }
  return mirror;
}

}  // namespace

ReflectionCut CutFloorReflections(const Camera& camera, cv::Mat* mask, const FloorReflectionOptions& o) {
  ReflectionCut cut;
  JGPM_CHECK(mask);
  const Eigen::Vector3d eye = camera.CentreInWorld();
  if (mask->empty() || !(eye.y() > 0)) return cut;
  cv::Mat labels;
  std::vector<int> areas;
  std::vector<cv::Rect> boxes;
  const int n = BodyBlobs(*mask, &labels, &areas, &boxes);
  bool copied = false;
  for (int l = 1; l < n; ++l) {
    const cv::Rect box = boxes[l];
    // A blob cut by the image's top or side edges has no head to measure a height by (a
    // webcam's walker close by, someone entering).
    if (areas[l] < o.min_blob_px || box.height < 8 || box.y <= 0 || box.x <= 0 || box.x + box.width >= mask->cols)
      continue;
    ++cut.tried;
    // The body's axis: the median column of the blob's top quarter (the head and
    // shoulders, with or without a reflection under them); the head's column.
    std::vector<int> columns;
    double top_u = 0;
    int top_count = 0;
    for (int v = box.y; v < box.y + std::max(1, box.height / 4); ++v) {
      const int* row = labels.ptr<int>(v);
      for (int u = box.x; u < box.x + box.width; ++u) {
        if (row[u] != l) continue;
        columns.push_back(u);
        if (v == box.y) top_u += u, ++top_count;
      }
    }
    std::nth_element(columns.begin(), columns.begin() + columns.size() / 2, columns.end());
    const double axis = columns[columns.size() / 2];
    top_u = top_count ? top_u / top_count : axis;
    Eigen::Matrix2Xd head(2, 1);
    head << top_u, box.y - 0.5;
    const Eigen::Vector3d head_ray = camera.PixelRaysInWorld(head).col(0);
    const Eigen::Vector2d head_horizontal(head_ray.x(), head_ray.z());
    if (head_horizontal.squaredNorm() < 1e-12) continue;
    // Per row: the blob's pixel count (to count what lies below a row quickly), and the
    // columns the blob spans from its top down to the row.
    const int last = box.y + box.height - 1;
    std::vector<int> row_count(box.height, 0), left(box.height), right(box.height);
    for (int v = box.y, lo = box.x + box.width, hi = box.x - 1; v <= last; ++v) {
      const int* row = labels.ptr<int>(v);
      for (int u = box.x; u < box.x + box.width; ++u) {
        if (row[u] != l) continue;
        ++row_count[v - box.y];
        lo = std::min(lo, u), hi = std::max(hi, u);
      }
      left[v - box.y] = lo, right[v - box.y] = hi;
    }
    // The height of an adult whose feet are at row r, by the camera (NaN: row r's ray
    // does not meet the floor, or the head is behind the camera).
    Eigen::Matrix2Xd feet(2, box.height);  // every row's, at once (the lens is inverted iteratively)
    for (int k = 0; k < box.height; ++k) feet.col(k) << axis, box.y + k + 0.5;
    const Eigen::Matrix3Xd foot_rays = camera.PixelRaysInWorld(feet);
    const auto height_at = [&](int r, Eigen::Vector3d* floor) {
      const Eigen::Vector3d ray = foot_rays.col(r - box.y);
      if (!(ray.y() < -1e-6)) return std::numeric_limits<double>::quiet_NaN();
      *floor = eye + ray * (-eye.y() / ray.y());
      const Eigen::Vector2d to_floor(floor->x() - eye.x(), floor->z() - eye.z());
      const double along = head_horizontal.dot(to_floor) / head_horizontal.squaredNorm();
      return along > 0 ? eye.y() + along * head_ray.y() : std::numeric_limits<double>::quiet_NaN();
    };
    // Standing on the blob's bottom, how far from an adult's mean the person would be
    // (infinite: not standing on the floor at all).
    Eigen::Vector3d floor = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    const double whole = height_at(last, &floor);
    const Eigen::Vector2d whole_mm = std::isfinite(whole) ? Eigen::Vector2d(floor.x(), floor.z()) : cut.whole_mm;
    const double whole_off = std::isfinite(whole) ? std::abs(whole - kAdultHeightMm) : std::numeric_limits<double>::infinity();
    const bool bottom_cut = last >= mask->rows - 1;
    // How well a mirror pixel lands: 1 on the blob, falling to 0 at `grow` from it (a peak
    // at the mirror's best alignment rather than a plateau as wide as the tolerance). Made
    // when a row is first tried.
    const int grow = std::max(1, static_cast<int>(std::lround(o.grow * box.height)));
    const cv::Rect window = (box + cv::Size(2 * grow, 2 * grow) - cv::Point(grow, grow)) &
                            cv::Rect(0, 0, mask->cols, mask->rows);
    cv::Mat fit;
    // How well blob m's pixels in `in` below row r mirror onto this blob (each 1 on it,
    // falling to 0 at `grow`; 0 more than half a person's width from the line), summed, and
    // how many pixels there are.
    const auto mirrored = [&](const RowMirror& mirror, int r, int m, const cv::Rect& in, double half_width_px,
                              int* count) {
      if (fit.empty()) {
        cv::distanceTransform(labels(window) != l, fit, cv::DIST_L2, cv::DIST_MASK_3);
        fit = 1 - fit / (grow + 1);  // negative beyond the tolerance: counted as 0 below
      }
      double landed = 0;
      for (int v = std::max(r + 1, in.y); v < in.y + in.height; ++v) {
        const int* row = labels.ptr<int>(v);
        const int mv = v - r - 1 < static_cast<int>(mirror.row.size()) ? mirror.row[v - r - 1] : -1;
        const float* on = mv >= window.y && mv < window.y + window.height ? fit.ptr<float>(mv - window.y) : nullptr;
        const int shift = on ? static_cast<int>(std::lround(mirror.shift[v - r - 1])) : 0;
        const double line = on ? mirror.line[v - r - 1] : 0;
        for (int u = in.x; u < in.x + in.width; ++u) {
          if (row[u] != m) continue;
          ++*count;
          const int mu = u + shift - window.x;
          if (on && std::abs(u - line) <= half_width_px && mu >= 0 && mu < window.width) landed += std::max(0.0f, on[mu]);
        }
      }
      return landed;
    };
    int best_row = -1, below_total = 0;
    double best_share = 0, best_score = -std::numeric_limits<double>::infinity();
    double best_height = 0, best_half_width = 0;
    Eigen::Vector3d best_floor;
    double proposed_score = -std::numeric_limits<double>::infinity();
    Eigen::Vector3d proposed = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
    for (int r = last - 1; r > box.y; --r) {
      below_total += row_count[r + 1 - box.y];
      const int above_total = areas[l] - below_total;
      // Far enough below (the box's last row is the blob's; a blob cut by the image's
      // bottom edge may go on below it), and enough of it: a tenth of what is above.
      if ((!bottom_cut && last - r < o.min_extent * (r - box.y)) || 10 * below_total < above_total) continue;
      // An adult standing at r, and more of one than the whole blob standing on the floor
      // (unless only proposing).
      const double height = height_at(r, &floor);
      if (!(height >= kMinAdultMm && height <= kMaxAdultMm)) continue;
      const bool nearer = std::abs(height - kAdultHeightMm) + o.stature_margin * kAdultSpreadMm <= whole_off;
      if (!nearer && !o.propose) continue;
      // And one person wide there: people side by side or one behind another, merged into
      // one blob, are not one person and their reflection.
      const double depth = camera.ToCamera(floor).z();
      if (!(depth > 0)) continue;
      const double half_width_px = 0.5 * o.max_width_mm * camera.fx / depth;
      if (right[r - box.y] - left[r - box.y] + 1 > 2 * half_width_px) continue;
      const std::optional<RowMirror> mirror = MirrorRows(camera, floor, 1.25 * height, r, last);
      if (!mirror) continue;
      // Only within half a person's width of the line can a pixel be this person's mirror
      // (not another's legs, or a shadow cast sideways, in the same blob).
      int count = 0;
      const double share = mirrored(*mirror, r, l, box, half_width_px, &count) / below_total;
      const double off = (height - kAdultHeightMm) / kAdultSpreadMm;
      const double score = share - kStaturePerSd2 * off * off;
      if (nearer && score > best_score) {
        best_score = score, best_share = share, best_row = r;
        best_height = height, best_half_width = half_width_px, best_floor = floor;
      }
      if (o.propose && share >= o.min_share && score > proposed_score) proposed_score = score, proposed = floor;
    }
    cut.best_share = std::max(cut.best_share, best_share);
    if (o.propose) cut.whole_mm = whole_mm, cut.proposed_mm = Eigen::Vector2d(proposed.x(), proposed.z());
    if (best_row < 0 || best_share < o.min_share) continue;
    if (!copied) *mask = mask->clone(), copied = true;
    const auto erase = [&](int m, const cv::Rect& in) {
      for (int v = std::max(best_row + 1, in.y); v < in.y + in.height; ++v) {
        const int* row = labels.ptr<int>(v);
        uchar* out = mask->ptr<uchar>(v);
        for (int u = in.x; u < in.x + in.width; ++u)
          if (row[u] == m) out[u] = 0, ++cut.pixels;
      }
    };
    erase(l, box);
    ++cut.blobs;
    // The reflection's pieces that are blobs of their own (a raised foot's, a shin's, apart
    // from the rest where the floor shows through): blobs wholly below the feet that
    // mirror onto the person as well.
    const std::optional<RowMirror> below = MirrorRows(camera, best_floor, 1.25 * best_height, best_row, mask->rows - 1);
    if (!below) continue;
    for (int m = 1; m < n; ++m) {
      if (m == l || boxes[m].y <= best_row) continue;
      int count = 0;
      const double landed = mirrored(*below, best_row, m, boxes[m], best_half_width, &count);
      if (count > 0 && landed >= o.min_share * count) erase(m, boxes[m]);
    }
  }
  return cut;
}

FloorReflectionSource::FloorReflectionSource(std::unique_ptr<FrameSource> inner, bool live,
                                             const GlossyFloorOptions& glossy, const FloorReflectionOptions& options)
    : inner_(std::move(inner)), glossy_(glossy), options_(options) {
  JGPM_CHECK(inner_);
  at_mask_size_ = inner_->cameras();
  tried_.assign(at_mask_size_.size(), 0);
  found_.assign(at_mask_size_.size(), 0);
  Frame frame;
  while (!live && static_cast<int>(ahead_.size()) < glossy_.lookahead_frames && inner_->Next(&frame))
    ahead_.push_back(ReadOne(std::move(frame)));
}

bool FloorReflectionSource::Glossy() const {
  int voting = 0, glossy = 0;
  for (size_t c = 0; c < tried_.size(); ++c) {
    if (tried_[c] < glossy_.min_glossy_frames) continue;
    ++voting;
    glossy += found_[c] >= glossy_.glossy_share * tried_[c];
  }
  return (glossy > 0 && glossy >= glossy_.glossy_share * voting) ||
         (agreed_ >= glossy_.min_glossy_frames && agreed_ >= glossy_.glossy_share * proposed_);
}

FloorReflectionSource::Read FloorReflectionSource::ReadOne(Frame frame) {
  Read read{std::move(frame), {}};
  const bool ahead = read_++ < glossy_.lookahead_frames;
  if (read.frame.dropped || (!ahead && !Glossy() && read_ % std::max(1, glossy_.try_every) != 0)) return read;
  read.cut.resize(read.frame.masks.size());
  FloorReflectionOptions options = options_;
  options.propose = at_mask_size_.size() >= 2;
  std::vector<size_t> proposing;
  std::vector<Eigen::Vector2d> wholes, feet;
  for (size_t c = 0; c < read.frame.masks.size() && c < at_mask_size_.size(); ++c) {
    const cv::Mat& mask = read.frame.masks[c];
    if (mask.empty()) continue;
    Camera& camera = at_mask_size_[c];
    if (camera.width != mask.cols || camera.height != mask.rows) {
      camera = ScaleCamera(inner_->cameras()[c], static_cast<double>(mask.cols) / inner_->cameras()[c].width);
    }
    cv::Mat cut = mask;
    const ReflectionCut found = CutFloorReflections(camera, &cut, options);
    tried_[c] += found.tried > 0;
    found_[c] += found.blobs > 0;
    if (found.blobs > 0) read.cut[c] = cut;
    if (found.tried == 1 && found.whole_mm.allFinite() && found.proposed_mm.allFinite()) {
      proposing.push_back(c);
      wholes.push_back(found.whole_mm);
      feet.push_back(found.proposed_mm);
    }
  }
  // The cameras checked against each other (above).
  if (proposing.size() < 2) return read;
  ++proposed_;
  if (!(Spread(feet) <= kAgreeMm && Spread(wholes) >= 2 * kAgreeMm)) return read;
  ++agreed_;
  FloorReflectionOptions waived = options_;
  waived.stature_margin = -std::numeric_limits<double>::infinity();
  for (const size_t c : proposing) {
    if (!read.cut[c].empty()) continue;
    cv::Mat cut = read.frame.masks[c];
    if (CutFloorReflections(at_mask_size_[c], &cut, waived).blobs > 0) read.cut[c] = cut;
  }
  return read;
}

bool FloorReflectionSource::Next(Frame* frame) {
  Read read;
  if (!ahead_.empty()) {
    read = std::move(ahead_.front());
    ahead_.pop_front();
  } else {
    if (!inner_->Next(frame)) return false;
    read = ReadOne(std::move(*frame));
  }
  *frame = std::move(read.frame);
  bool any = false;
  const bool glossy = Glossy();
  for (size_t c = 0; c < read.cut.size(); ++c) {
    if (read.cut[c].empty() || !glossy) continue;
    frame->masks[c] = read.cut[c];
    any = true;
  }
  frames_cut_ += any;
  return true;
}

}  // namespace jgpm
