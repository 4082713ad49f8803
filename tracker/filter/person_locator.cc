#include "tracker/filter/person_locator.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include <opencv2/imgproc.hpp>

#include "tracker/frames/body_blobs.h"

namespace jgpm {
namespace {

double Median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// Where a standing adult's head is when the feet cannot be seen: the mean adult height
// (kAdultHeightMm, body_blobs.h), the person's own unknown; from a camera near head height
// their spread (kAdultSpreadMm) is most of what the head says about the distance.
// What of a person above someone nearer must show to be taken for one (mm): a head and
// shoulders, about a fifth of an adult's height (a sliver of the nearer one's own head
// that their estimate leaves over is placed where they stand, and the births skip it).
constexpr double kHeadAndShouldersMm = 350;
// How wide a standing person's upper half is at most, as a share of their height: the
// median over its rows of the blob's pixels in the row (head, neck, trunk and the arms
// beside it; a thin thing joined to the blob, a tape or a pole, spans a few rows and does
// not count). An adult's shoulders are about a quarter of their height, so one person
// gives 0.15-0.35 and two abreast in one blob up to about 0.65, while a round blob gives
// 0.8-0.9. Measured on the observed masks of every clip of the six suites (every 3rd
// frame; blobs clear of the image's edges and 1-2.3 m tall where they stand): walkers 0.19
// at the median, 0.36 at the 99th percentile and 0.58 at most (ducking, 131_06), other
// blobs as tall (clutter, shadows) 0.81 at the median, 66% of them over 0.7; on
// vtest.avi's masks (400 frames, people merged with a flapping tape or walking in pairs)
// 0.25 at the median, 0.64 at most but for a blob on a building's front (0.91).
constexpr double kMaxUpperWidth = 0.7;
// How much of its convex hull a person's blob fills at most: the neck, the gaps between
// the arms and the trunk and between the legs leave some of it empty, where a ball, a
// bag or a clutter blob fills it (solidity, its pixels over the hull's area and half its
// perimeter, the pixels its outline runs through). On the same masks walkers reach 0.90,
// vtest.avi's blobs 0.89, while 86% of the other blobs are over 0.93 (clutter ellipses
// 0.97-0.99, however thin: the upright rule passes those); on the harsh clips
// (datasets_scripts/harsh_suite.txt) walkers reach 0.95, a coated one merged with a
// passing blob, and 0.947 one 26 px tall.
constexpr double kMaxSolidity = 0.96;

// Blob `label`'s solidity in `box` (kMaxSolidity), `area` its pixels there.
double Solidity(const cv::Mat& labels, int label, const cv::Rect& box, int area) {
  std::vector<std::vector<cv::Point>> outlines;
  cv::findContours(labels(box) == label, outlines, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_SIMPLE);
  std::vector<cv::Point> points, hull;
  for (const auto& o : outlines) points.insert(points.end(), o.begin(), o.end());
  if (points.size() < 3) return 1;
  cv::convexHull(points, hull);
  return area / (cv::contourArea(hull) + 0.5 * cv::arcLength(hull, true) + 1);
}

struct BlobEnds {
  double foot_u = 0, foot_v = 0;  // the feet: column, and the lowest row
  double top_u = 0;               // the head: column of the top row
  double axis = 0;                // the body's axis: median column of the upper half
  double upper_width = 0;         // the upper half's rows' median width in pixels
  double reach = 0;               // how far from the axis the feet are looked for, pixels
};

// The ends of blob `label` in `box`. The body's axis is the median column of the blob's
// upper half (head and trunk: a shadow on the floor and the legs' spread lie below it);
// the feet are its pixels within 0.3 of the blob's height of that axis (a stride seen
// from the side puts the feet up to about 0.4 of a person's height apart), in their
// lowest 4 rows. A shadow cast sideways along the floor is not the feet.
BlobEnds FindBlobEnds(const cv::Mat& labels, int label, const cv::Rect& box) {
  std::vector<double> columns, widths;
  for (int v = box.y; v < box.y + (box.height + 1) / 2; ++v) {
    const int* row = labels.ptr<int>(v);
    const size_t before = columns.size();
    for (int u = box.x; u < box.x + box.width; ++u)
      if (row[u] == label) columns.push_back(u);
    if (columns.size() > before) widths.push_back(static_cast<double>(columns.size() - before));
  }
  const double axis = columns.empty() ? box.x + 0.5 * (box.width - 1) : Median(columns);
  const double reach = 0.3 * box.height;
  int bottom = -1;
  for (int v = box.y + box.height - 1; v >= box.y && bottom < 0; --v) {
    const int* row = labels.ptr<int>(v);
    for (int u = box.x; u < box.x + box.width; ++u)
      if (row[u] == label && std::abs(u - axis) <= reach) {
        bottom = v;
        break;
      }
  }
  BlobEnds ends;
  if (bottom < 0) bottom = box.y + box.height - 1;
  double foot_u = 0, top_u = 0;
  int foot_count = 0, top_count = 0;
  for (int v = std::max(box.y, bottom - 3); v <= bottom; ++v) {
    const int* row = labels.ptr<int>(v);
    for (int u = box.x; u < box.x + box.width; ++u)
      if (row[u] == label && std::abs(u - axis) <= reach) foot_u += u, ++foot_count;
  }
  const int* top_row = labels.ptr<int>(box.y);
  for (int u = box.x; u < box.x + box.width; ++u)
    if (top_row[u] == label) top_u += u, ++top_count;
  ends.foot_u = foot_count > 0 ? foot_u / foot_count : axis;
  ends.foot_v = bottom;
  ends.top_u = top_count > 0 ? top_u / top_count : axis;
  ends.axis = axis;
  ends.upper_width = widths.empty() ? 0 : Median(widths);
  ends.reach = reach;
  return ends;
}

// How much nearer an adult's height the top must read at the reading's place than at the
// feet above a shadow's tip for the reading to be kept (FeetAboveShadow): the spread of
// adults' heights, so that only a camera looking down enough to tell the two places apart
// by the head overrules the light.
constexpr double kShadowTieMm = kAdultSpreadMm;

// Where the feet are when the blob holds the person's shadow, cast by `light` (unit,
// towards it) on the floor: a point h above the feet p casts its shadow at p + h s, s =
// -(light_x, light_z) / light_y, so the shadow runs from the feet along s's image. Its
// far end, the head's shadow, is the blob's pixels farthest along that direction; its
// floor point T = p + h(p) s, with h(p) the height the top ray reads above p (linear in
// p; an adult's when the head is cut), gives p. A shadow running up the image (away from
// the camera, over 30 degrees above the image's rows) leaves the reading as it is: it
// does not move the lowest pixels, and its far end may be the head. So does an answer
// whose feet are not below the body's axis (within `ends.reach`) and above the blob's
// bottom, or that reads no person's height (a mask without the shadow: the far end is a
// foot or a hand). On the surveillance clips a low light towards a camera put one
// camera's reading 0.9-1.1 m nearer than the feet, farther than a tracked person's
// prediction is looked for; in the locator's test the shadow towards the camera hid the
// walker (read over 2.3 m tall) or put them 1.1 m off, one cast sideways 250-470 mm
// (FindBlobEnds keeps the feet within reach of the axis, where the shadow's near edge
// still is); with the light, 25-134 mm.
Eigen::Vector3d FeetAboveShadow(const Camera& camera, const cv::Mat& labels, int label, const cv::Rect& box,
                                const BlobEnds& ends, const Eigen::Vector3d& top_ray, bool head_cut,
                                const Eigen::Vector3d& reading, const Eigen::Vector3d& light) {
  if (!(light.y() > 0.05)) return reading;  // a light along the floor casts no readable shadow
  const Eigen::Vector2d s(-light.x() / light.y(), -light.z() / light.y());  // per mm up
  Eigen::Vector2d from, to;
  if (!camera.Project(reading, &from) || !camera.Project(reading + 1000 * Eigen::Vector3d(s.x(), 0, s.y()), &to))
    return reading;
  const Eigen::Vector2d d = (to - from).normalized();
  if (!(d.y() > -0.5)) return reading;
  // The far end: the mean of the pixels within a pixel of the farthest along d.
  double farthest = -std::numeric_limits<double>::infinity();
  for (int v = box.y; v < box.y + box.height; ++v) {
    const int* row = labels.ptr<int>(v);
    for (int u = box.x; u < box.x + box.width; ++u)
      if (row[u] == label) farthest = std::max(farthest, d.x() * u + d.y() * v);
  }
  Eigen::Vector2d end = Eigen::Vector2d::Zero();
  int count = 0;
  for (int v = box.y; v < box.y + box.height; ++v) {
    const int* row = labels.ptr<int>(v);
    for (int u = box.x; u < box.x + box.width; ++u)
      if (row[u] == label && d.x() * u + d.y() * v >= farthest - 1) end += Eigen::Vector2d(u + 0.5, v + 0.5), ++count;
  }
  if (count == 0) return reading;
  const Eigen::Matrix2Xd far_edge = end / count + 0.5 * d;
  const Eigen::Vector3d eye = camera.CentreInWorld();
  const Eigen::Vector3d ray = camera.PixelRaysInWorld(far_edge).col(0);
  if (!(ray.y() < -1e-6)) return reading;
  const Eigen::Vector3d tip3 = eye + ray * (-eye.y() / ray.y());
  const Eigen::Vector2d tip(tip3.x(), tip3.z()), eye_floor(eye.x(), eye.z());
  // h(p) = a + b.p: the top ray's height above the floor point p (an adult's, head cut).
  const Eigen::Vector2d horizontal(top_ray.x(), top_ray.z());
  if (horizontal.squaredNorm() < 1e-12) return reading;
  const Eigen::Vector2d b = head_cut ? Eigen::Vector2d::Zero() : Eigen::Vector2d(top_ray.y() * horizontal / horizontal.squaredNorm());
  const double a = head_cut ? kAdultHeightMm : eye.y() - b.dot(eye_floor);
  // p = tip - (a + b.p) s, solved for p (Sherman-Morrison on I + s b^T).
  const Eigen::Vector2d q = tip - a * s;
  const double denominator = 1 + b.dot(s);
  if (std::abs(denominator) < 0.1) return reading;
  const Eigen::Vector2d p = q - s * (b.dot(q) / denominator);
  const double h = a + b.dot(p);
  const Eigen::Vector3d feet(p.x(), 0, p.y());
  Eigen::Vector2d pixel;
  if (!(h > 1000 && h < 2300) || !camera.Project(feet, &pixel) || std::abs(pixel.x() - ends.axis) > ends.reach ||
      pixel.y() > ends.foot_v + 1.5)
    return reading;
  return feet;
}

// Whether the feet of blob `label` are hidden by someone nearer: at least half of its
// lowest row's pixels near the body's axis (FindBlobEnds' feet) have a `hidden` pixel (a
// nearer person's drawing) right below them. Seen from above the floor, a nearer person
// is drawn lower in the image than a farther one's feet, so a blob resting on someone's
// drawing is behind them, cut by them, not standing there. Unless the top's pixels have
// `painted` right above them too.
bool FeetHidden(const cv::Mat& labels, int label, const cv::Rect& box, const BlobEnds& ends, const cv::Mat& hidden,
                const cv::Mat& painted) {
  const int below = static_cast<int>(ends.foot_v) + 1;
  if (hidden.empty() || hidden.size() != labels.size() || below >= hidden.rows) return false;
  const int* row = labels.ptr<int>(below - 1);
  const uchar* under = hidden.ptr<uchar>(below);
  int feet = 0, on_hidden = 0;
  for (int u = box.x; u < box.x + box.width; ++u) {
    if (row[u] != label || std::abs(u - ends.axis) > ends.reach) continue;
    ++feet;
    on_hidden += under[u] != 0;
  }
  if (!(feet > 0 && 2 * on_hidden >= feet)) return false;
  // A painted object above its top as well (a clutter blob passing in front of a pillar)
  // cannot be nearer than the top, which is seen: the blob is in front of it.
  if (box.y == 0 || painted.empty() || painted.size() != labels.size()) return true;
  const int* top = labels.ptr<int>(box.y);
  const uchar* above = painted.ptr<uchar>(box.y - 1);
  int tops = 0, covered = 0;
  for (int u = box.x; u < box.x + box.width; ++u)
    if (top[u] == label) ++tops, covered += above[u] != 0;
  return 2 * covered < tops;
}

// How near the feet of a blob whose feet are hidden (FeetHidden) can be: where the floor
// meets the lower edge of the hidden run below the feet, in the feet's column (the feet
// lower in the image would show). 0 when the run reaches the image's bottom or the ray
// does not meet the floor.
double HiddenRunNear(const Camera& camera, const cv::Mat& hidden, const BlobEnds& ends, const Eigen::Vector3d& eye) {
  const int u = std::clamp(static_cast<int>(std::lround(ends.foot_u)), 0, hidden.cols - 1);
  int v = static_cast<int>(ends.foot_v) + 1;
  while (v < hidden.rows && hidden.at<uchar>(v, u)) ++v;
  if (v >= hidden.rows) return 0;
  Eigen::Matrix2Xd edge(2, 1);
  edge << ends.foot_u, v - 0.5;
  const Eigen::Vector3d ray = camera.PixelRaysInWorld(edge).col(0);
  if (!(ray.y() < -1e-6)) return 0;
  return Eigen::Vector2d(ray.x(), ray.z()).norm() * (-eye.y() / ray.y());
}

// People side by side merged into one blob (walking together, passing one another) split
// at their heads. A blob's top profile (each column's highest pixel) has one peak per
// head near the blob's top; one person's profile falls from the head to the shoulders
// (0.15-0.2 of their height) and has no second peak there (a hand is low, the shoulders
// are below the head). So the blob is split at the column where the profile dips deepest
// between a peak on each side, when both peaks are within kPeak of the blob's height of
// its top (two adults' heights differ by up to a tenth), the dip falls at least kDip below
// the lower peak (the neck and shoulders between two heads), and each side is at least
// kSide as wide as the blob is tall (a person's shoulders are a quarter of their height)
// with at least a fifth of its pixels; each side is split again the same way. A blob cut
// by the image's top edge has no heads to go by (its top row is a body's cut, arms and
// trunk apart) and is not split. Returns the parts' boxes (the blob's own when it is one
// person).
constexpr double kPeak = 0.12, kDip = 0.12, kSide = 0.15;
std::vector<cv::Rect> SplitAtHeads(const cv::Mat& labels, int label, const cv::Rect& box, int depth = 0) {
  const int h = box.height, w = box.width;
  const int side = static_cast<int>(std::ceil(kSide * h));
  if (depth >= 3 || side < 1 || w < 2 * side || box.y <= 0) return {box};
  std::vector<int> top(w, box.y + h), count(w, 0);
  int total = 0;
  for (int v = box.y; v < box.y + h; ++v) {
    const int* row = labels.ptr<int>(v);
    for (int u = 0; u < w; ++u) {
      if (row[box.x + u] != label) continue;
      top[u] = std::min(top[u], v);
      ++count[u], ++total;
    }
  }
  std::vector<int> left_peak(w), right_peak(w), left_count(w + 1, 0);
  for (int u = 0; u < w; ++u) {
    left_peak[u] = std::min(top[u], u > 0 ? left_peak[u - 1] : box.y + h);
    left_count[u + 1] = left_count[u] + count[u];
  }
  for (int u = w - 1; u >= 0; --u) right_peak[u] = std::min(top[u], u + 1 < w ? right_peak[u + 1] : box.y + h);
  const double near_top = box.y + kPeak * h;
  int split = -1;
  double deepest = 0;
  for (int u = side; u + side <= w; ++u) {
    const int l = left_peak[u - 1], r = right_peak[u];
    if (l > near_top || r > near_top) continue;
    const double dip = top[u] - std::max(l, r);
    const int left_px = left_count[u];
    if (dip < kDip * h || 5 * left_px < total || 5 * (total - left_px) < total) continue;
    if (dip > deepest) deepest = dip, split = u;
  }
  if (split < 0) return {box};
  std::vector<cv::Rect> parts;
  for (const auto& [from, to] : {std::pair{0, split}, std::pair{split, w}}) {
    int y0 = box.y + h, y1 = box.y - 1;
    for (int v = box.y; v < box.y + h; ++v) {
      const int* row = labels.ptr<int>(v);
      for (int u = from; u < to; ++u)
        if (row[box.x + u] == label) {
          y0 = std::min(y0, v), y1 = std::max(y1, v);
          break;
        }
    }
    for (const cv::Rect& r : SplitAtHeads(labels, label, cv::Rect(box.x + from, y0, to - from, y1 - y0 + 1), depth + 1))
      parts.push_back(r);
  }
  return parts;
}

// Blob `label` in `box` cut across at its narrowest row between 30% and 70% of its height
// (ties: the nearest the middle): the parts above and below it, each trimmed to its pixels.
std::vector<cv::Rect> CutAcross(const cv::Mat& labels, int label, const cv::Rect& box) {
  int cut = -1, narrowest = std::numeric_limits<int>::max();
  const int middle = box.y + box.height / 2;
  for (int v = box.y + box.height * 3 / 10; v <= box.y + box.height * 7 / 10; ++v) {
    const int* row = labels.ptr<int>(v);
    int width = 0;
    for (int u = box.x; u < box.x + box.width; ++u) width += row[u] == label;
    if (width < narrowest || (width == narrowest && std::abs(v - middle) < std::abs(cut - middle)))
      narrowest = width, cut = v;
  }
  std::vector<cv::Rect> parts;
  if (cut < 0) return parts;
  for (const auto& [from, to] : {std::pair{box.y, cut}, std::pair{cut + 1, box.y + box.height}}) {
    int x0 = box.x + box.width, x1 = box.x - 1, y0 = to, y1 = from - 1;
    for (int v = from; v < to; ++v) {
      const int* row = labels.ptr<int>(v);
      for (int u = box.x; u < box.x + box.width; ++u)
        if (row[u] == label) x0 = std::min(x0, u), x1 = std::max(x1, u), y0 = std::min(y0, v), y1 = std::max(y1, v);
    }
    if (x1 >= x0) parts.emplace_back(x0, y0, x1 - x0 + 1, y1 - y0 + 1);
  }
  return parts;
}

}  // namespace

std::vector<PersonSighting> LocatePeople(const std::vector<Camera>& cameras, const std::vector<cv::Mat>& masks,
                                         int min_blob_px, bool split_merged, const std::vector<cv::Mat>& hidden,
                                         const std::vector<cv::Mat>& painted,
                                         const std::optional<Eigen::Vector3d>& light) {
  // Per camera, every blob big enough, with where it stands and how tall it is there.
  struct Candidate {
    int area;
    cv::Rect box;
    Eigen::Vector2d floor;
    double height;
    bool feet;  // the feet in view (else the place is the adult-height guess)
    bool whole;  // clear of the side edges
    bool behind;  // the feet hidden by someone nearer (`hidden`), not by the image's edge
  };
  std::vector<std::vector<Candidate>> candidates(cameras.size());
  for (size_t c = 0; c < cameras.size() && c < masks.size(); ++c) {
    if (masks[c].empty()) continue;
    const Eigen::Vector3d eye = cameras[c].CentreInWorld();
    if (eye.y() <= 0) continue;
    cv::Mat labels;
    std::vector<int> areas;
    std::vector<cv::Rect> boxes;
    const int n = BodyBlobs(masks[c], &labels, &areas, &boxes);
    // A part of blob `l` in `box` considered as a person; true when it is too tall for one
    // (over 2.3 m where it stands).
    const auto consider = [&](int l, const cv::Rect& box, int area) -> bool {
      if (area < min_blob_px) return false;
      const BlobEnds ends = FindBlobEnds(labels, l, box);
      const bool edge_cut = box.y + box.height >= masks[c].rows;  // at the image's bottom edge
      const bool feet_cut = edge_cut || FeetHidden(labels, l, box, ends, c < hidden.size() ? hidden[c] : cv::Mat(),
                                                c < painted.size() ? painted[c] : cv::Mat());
      const bool head_cut = box.y <= 0;
      // Cut by a side edge: a slice of someone entering or leaving (an arm, a leg, the
      // back), whose top is not a head.
      const bool side_cut = box.x <= 0 || box.x + box.width >= masks[c].cols;
      Eigen::Matrix2Xd pixels(2, 2);
      pixels << ends.foot_u, ends.top_u, ends.foot_v + 0.5, box.y - 0.5;
      const Eigen::Matrix3Xd rays = cameras[c].PixelRaysInWorld(pixels);
      const Eigen::Vector3d r = rays.col(1);
      const Eigen::Vector2d horizontal(r.x(), r.z());
      if (horizontal.squaredNorm() < 1e-12) return false;
      Eigen::Vector3d floor;
      double height = 0;  // unknown unless both ends are in view
      if (!feet_cut) {
        if (!(rays(1, 0) < -1e-6)) return false;  // the foot ray must go down to the floor
        floor = eye + rays.col(0) * (-eye.y() / rays(1, 0));
        // Height: the top ray's point nearest the vertical line through a floor point
        // (`along` the top ray's horizontal part).
        const auto top_at = [&](const Eigen::Vector3d& at, double* along) {
          *along = horizontal.dot(Eigen::Vector2d(at.x() - eye.x(), at.z() - eye.z())) / horizontal.squaredNorm();
          return eye.y() + *along * r.y();
        };
        if (light) {
          // The segmentation may have removed the shadow after all (MOG2 marks the lighter
          // part of one as shadow): of the two places, the one where the top reads nearer
          // an adult's height, the shadow's when they are within kShadowTieMm (a camera
          // at head height, whose top ray is level, cannot tell).
          const Eigen::Vector3d feet = FeetAboveShadow(cameras[c], labels, l, box, ends, r, head_cut, floor, *light);
          double along_feet = 0, along_reading = 0;
          const double off_feet = std::abs(top_at(feet, &along_feet) - kAdultHeightMm);
          const double off_reading = std::abs(top_at(floor, &along_reading) - kAdultHeightMm);
          if (head_cut || along_reading <= 0 || (along_feet > 0 && off_feet <= off_reading + kShadowTieMm))
            floor = feet;
        }
        if (!head_cut) {
          double along = 0;
          height = top_at(floor, &along);
          // A person stands 1-2.3 m tall; clutter (a blob in the air, a shadow) does not.
          if (!(along > 0 && height > 1000 && height < 2300)) return along > 0 && height >= 2300;
          // And is upright, the upper half no wider than kMaxUpperWidth of the height there,
          // and not convex. (A slice cut by a side edge is not a whole person's shape.)
          if (!side_cut) {
            const double depth = cameras[c].ToCamera(floor).z();
            if (ends.upper_width * depth / cameras[c].fx > kMaxUpperWidth * height) return false;
            if (Solidity(labels, l, box, area) > kMaxSolidity) return false;
          }
        }
      } else {
        // The feet below the image (a camera near the walk) or behind someone nearer: the
        // person stands where the top ray is an adult's height above the floor, but no
        // farther than where the image's bottom edge, or the blob's, meets the floor (the
        // feet are below it, so nearer). From a camera at head height the first alone can
        // put a person tens of metres away.
        if (head_cut) return false;
        // Resting on something that hides the feet, a person's head and shoulders are not
        // convex either (the neck); a clutter disc resting on a painted pillar's top is.
        if (!edge_cut && !side_cut && Solidity(labels, l, box, area) > kMaxSolidity) return false;
        Eigen::Matrix2Xd edge(2, 1);
        edge << ends.foot_u, edge_cut ? masks[c].rows - 0.5 : ends.foot_v + 0.5;
        const Eigen::Vector3d down = cameras[c].PixelRaysInWorld(edge).col(0);
        const Eigen::Vector2d horizontal_down(down.x(), down.z());
        double reach = std::numeric_limits<double>::infinity();  // horizontal distance
        if (down.y() < -1e-6) reach = horizontal_down.norm() * (-eye.y() / down.y());
        const double t = std::abs(r.y()) > 1e-6 ? (kAdultHeightMm - eye.y()) / r.y() : -1;
        double distance = t > 0 ? horizontal.norm() * t : reach;
        distance = std::min(distance, reach);
        if (!edge_cut) {
          // Hidden by something whose lower edge shows: the feet are on the floor between
          // the blob's bottom and that edge, and the head at an adult's height give or take
          // kAdultSpreadMm. Where both hold, the middle; else the feet's bound nearest.
          const double near = HiddenRunNear(cameras[c], hidden[c], ends, eye);
          double lo = 0, hi = std::numeric_limits<double>::infinity();
          if (std::abs(r.y()) > 1e-9) {
            const double d1 = (kAdultHeightMm - kAdultSpreadMm - eye.y()) / r.y() * horizontal.norm();
            const double d2 = (kAdultHeightMm + kAdultSpreadMm - eye.y()) / r.y() * horizontal.norm();
            lo = std::max(0.0, std::min(d1, d2));
            hi = std::max(d1, d2);
          }
          const double from = std::max(lo, near), to = std::min(hi, reach);
          if (from <= to && std::isfinite(to)) distance = 0.5 * (from + to);
          else if (hi < near) distance = near;
        }
        if (!std::isfinite(distance)) return false;
        // What it shows there must be a standing person's upper body: from the head (at
        // most 2.3 m up) down at least 0.8 m to the image's edge (a ball or a bag is not);
        // above someone nearer, a head and shoulders (kHeadAndShouldersMm).
        const double top = eye.y() + r.y() * distance / horizontal.norm();
        const double bottom = eye.y() + down.y() * distance / horizontal_down.norm();
        if (!(top < 2300 && top - bottom >= (edge_cut ? 800 : kHeadAndShouldersMm))) return false;
        const Eigen::Vector2d along = horizontal.normalized() * distance;
        floor = Eigen::Vector3d(eye.x() + along.x(), 0, eye.z() + along.y());
      }
      candidates[c].push_back(
          {area, box, Eigen::Vector2d(floor.x(), floor.z()), side_cut ? 0.0 : height, !feet_cut, !side_cut,
           feet_cut && !edge_cut});
      return false;
    };
    for (int l = 1; l < n; ++l) {
      if (areas[l] < min_blob_px) continue;
      const std::vector<cv::Rect> parts =
          split_merged ? SplitAtHeads(labels, l, boxes[l]) : std::vector<cv::Rect>{boxes[l]};
      for (const cv::Rect& box : parts) {
        const int area = parts.size() == 1 ? areas[l] : cv::countNonZero(labels(box) == l);
        if (!consider(l, box, area) || !split_merged) continue;
        // Too tall for one person: one standing behind another, their feet hidden by the
        // nearer one's head (a camera looking down on a plaza), or the two joined across a
        // gap. Cut at the blob's narrowest row in its middle (the gap, or where the far
        // one's legs meet the near one's head) and each part considered on its own.
        for (const cv::Rect& piece : CutAcross(labels, l, box))
          consider(l, piece, cv::countNonZero(labels(piece) == l));
      }
    }
  }
  // A blob whose feet are seen is better evidence than a guess from a head: when any
  // camera has one, the guesses do not vote (clutter at the image's edge is not a person).
  // A head above someone nearer is not clutter: it is someone, whoever else is seen.
  bool any_feet = false;
  for (const auto& own : candidates)
    for (const Candidate& q : own) any_feet = any_feet || q.feet;
  if (any_feet) {
    for (auto& own : candidates)
      own.erase(std::remove_if(own.begin(), own.end(), [](const Candidate& q) { return !q.feet && !q.behind; }), own.end());
  }
  // One person at a time, the best evidence first: the candidate place most cameras
  // agree on (a candidate within 1 m), ties going to the larger total blob area, so a
  // ghost blob that only one camera sees cannot outvote cameras that agree, even when it
  // is that camera's largest blob. Each camera's blob nearest that place (within 1 m) is
  // that person's, and is not looked at again.
  constexpr double kAgreeMm = 1000;
  std::vector<PersonSighting> people;
  while (true) {
    Eigen::Vector2d centre;
    int best_cameras = 0;
    long best_area = -1;
    for (const auto& own : candidates) {
      for (const Candidate& hypothesis : own) {
        int agreeing = 0;
        long area = 0;
        for (const auto& other : candidates) {
          int largest = 0;
          for (const Candidate& q : other)
            if ((q.floor - hypothesis.floor).norm() < kAgreeMm) largest = std::max(largest, q.area);
          agreeing += largest > 0;
          area += largest;
        }
        if (agreeing > best_cameras || (agreeing == best_cameras && area > best_area))
          best_cameras = agreeing, best_area = area, centre = hypothesis.floor;
      }
    }
    if (best_cameras == 0) break;
    PersonSighting sighting;
    sighting.whole = false;
    sighting.boxes.assign(cameras.size(), cv::Rect());
    sighting.areas.assign(cameras.size(), 0);
    sighting.camera_floor_mm.assign(cameras.size(), Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
    std::vector<double> agreeing_x, agreeing_z, heights, guessed_x, guessed_z;
    for (size_t c = 0; c < candidates.size(); ++c) {
      // The blob nearest that place, if near enough.
      int best = -1;
      double nearest = kAgreeMm;
      for (size_t k = 0; k < candidates[c].size(); ++k) {
        const double d = (candidates[c][k].floor - centre).norm();
        if (d < nearest) nearest = d, best = static_cast<int>(k);
      }
      if (best < 0) continue;
      const Candidate p = candidates[c][best];
      candidates[c].erase(candidates[c].begin() + best);
      sighting.boxes[c] = p.box;
      sighting.areas[c] = p.area;
      sighting.whole = sighting.whole || p.whole;
      if (p.feet) sighting.camera_floor_mm[c] = p.floor;
      (p.feet ? agreeing_x : guessed_x).push_back(p.floor.x());
      (p.feet ? agreeing_z : guessed_z).push_back(p.floor.y());
      if (p.height > 0) heights.push_back(p.height);
    }
    // Places read from feet when any camera saw them; the adult-height guesses otherwise.
    sighting.feet_seen = !agreeing_x.empty();
    sighting.cameras = static_cast<int>(agreeing_x.size() + guessed_x.size());
    if (!sighting.feet_seen) agreeing_x.swap(guessed_x), agreeing_z.swap(guessed_z);
    if (agreeing_x.empty()) break;  // cannot happen: the centre is some camera's blob
    sighting.found = true;
    sighting.floor_mm = Eigen::Vector2d(Median(agreeing_x), Median(agreeing_z));
    sighting.height_mm = heights.empty() ? 0 : Median(heights);
    people.push_back(std::move(sighting));
  }
  return people;
}

PersonSighting ChoosePerson(const std::vector<PersonSighting>& people, const PersonPreference& prefer) {
  const PersonSighting* chosen = nullptr;
  double nearest = std::numeric_limits<double>::infinity();
  for (const PersonSighting& person : people) {
    double d = 0;
    switch (prefer.kind) {
      case PersonPreference::Kind::kStrongest:
        return person;
      case PersonPreference::Kind::kNearPlace:
        d = (person.floor_mm - prefer.floor_mm).norm();
        if (d > prefer.within_mm) continue;
        break;
      case PersonPreference::Kind::kNearPixel: {
        if (prefer.camera < 0 || prefer.camera >= static_cast<int>(person.boxes.size())) continue;
        const cv::Rect& box = person.boxes[prefer.camera];
        if (box.empty()) continue;
        // From the pixel to the box (0 inside it).
        const double du = std::max({box.x - prefer.pixel.x(), 0.0, prefer.pixel.x() - (box.x + box.width)});
        const double dv = std::max({box.y - prefer.pixel.y(), 0.0, prefer.pixel.y() - (box.y + box.height)});
        d = std::hypot(du, dv);
        break;
      }
    }
    if (d < nearest) nearest = d, chosen = &person;
  }
  if (chosen) return *chosen;
  return PersonSighting();
}

bool FuseReadings(const std::vector<Camera>& cameras, const std::vector<Eigen::Vector2d>& readings,
                  Eigen::Vector2d* place) {
  // The spreads of a reading (FuseReadings, person_locator.h): along the line of sight a
  // quarter of the distance (a feet row moved by a tenth of the blob's height, a camera
  // 1.5 m up), across it 0.05 (3 degrees: a blob's column moved by a merged blob of a
  // fifth of its width, 60 degrees over 320 px).
  constexpr double kAlong = 0.25, kAcross = 0.05;
  Eigen::Matrix2d information = Eigen::Matrix2d::Zero();
  Eigen::Vector2d weighted = Eigen::Vector2d::Zero();
  int count = 0;
  for (size_t c = 0; c < cameras.size() && c < readings.size(); ++c) {
    if (!readings[c].allFinite()) continue;
    const Eigen::Vector3d eye = cameras[c].CentreInWorld();
    const Eigen::Vector2d sight = readings[c] - Eigen::Vector2d(eye.x(), eye.z());
    const double distance = sight.norm();
    if (!(distance > 1)) continue;
    const Eigen::Vector2d along = sight / distance, across(-along.y(), along.x());
    const double sa = kAlong * distance, sc = kAcross * distance + 100;
    const Eigen::Matrix2d w = along * along.transpose() / (sa * sa) + across * across.transpose() / (sc * sc);
    information += w;
    weighted += w * readings[c];
    ++count;
  }
  if (count < 2) return false;
  *place = information.ldlt().solve(weighted);
  return place->allFinite();
}

PersonSighting LocatePerson(const std::vector<Camera>& cameras, const std::vector<cv::Mat>& masks, int min_blob_px,
                            const PersonPreference& prefer, const std::vector<cv::Mat>& hidden,
                            const std::vector<cv::Mat>& painted, std::vector<PersonSighting>* everyone,
                            const std::optional<Eigen::Vector3d>& light) {
  std::vector<PersonSighting> people = LocatePeople(cameras, masks, min_blob_px, false, hidden, painted, light);
  PersonSighting sighting = ChoosePerson(people, prefer);
  if (everyone) *everyone = std::move(people);
  sighting.boxes.resize(cameras.size());
  sighting.areas.resize(cameras.size());
  return sighting;
}

}  // namespace jgpm
