// The particle filter's silhouettes, packed 64 pixels to a word: each capsule's image (the
// convex hull of its two end ellipses, as tracker/body/silhouette.h projects them) is filled row
// by row with the exact span of the hull on that row (a pixel is in when its centre is),
// so a body costs a few hundred span writes and comparing it with a mask a few hundred
// AND + popcount word operations, instead of per-pixel fills and counts.
#pragma once

#include <algorithm>
#include <cstdint>
#include <vector>

#include <Eigen/Core>
#include <opencv2/core/mat.hpp>

#include "tracker/body/silhouette.h"

namespace jgpm {

// A binary image of packed rows; remembers the box of rows and words that was touched, so
// that clearing it and counting in it cost the body's size rather than the image's.
class BitMask {
 public:
  BitMask() = default;
  BitMask(int width, int height);
  // From a CV_8U mask (nonzero = set), only the pixels inside `region` (clipped).
  static BitMask FromMat(const cv::Mat& mask, cv::Rect region);

  int width() const { return width_; }
  int height() const { return height_; }
  int words_per_row() const { return words_; }
  const uint64_t* row(int v) const { return &bits_[static_cast<size_t>(v) * words_]; }
  // Sets pixels [x0, x1] of row v (clipped to the image; nothing when x1 < x0).
  void SetSpan(int v, int x0, int x1);
  // The fast path of SetSpan for a row inside the image and 0 <= x0 <= x1 < width, which
  // leaves the touched box to a Mark call for the whole batch of spans.
  void SetSpanUnchecked(int v, int x0, int x1) {
    uint64_t* row = &bits_[static_cast<size_t>(v) * words_];
    const int w0 = x0 >> 6, w1 = x1 >> 6;
    const uint64_t first = ~uint64_t{0} << (x0 & 63);
    const uint64_t last = ~uint64_t{0} >> (63 - (x1 & 63));
    if (w0 == w1) {
      row[w0] |= first & last;
      return;
    }
    row[w0] |= first;
    for (int w = w0 + 1; w < w1; ++w) row[w] = ~uint64_t{0};
    row[w1] |= last;
  }
  // Widens the touched box to hold rows [v0, v1] and columns [x0, x1] (inside the image,
  // v0 <= v1, x0 <= x1).
  void Mark(int v0, int v1, int x0, int x1) {
    if (first_row_ == last_row_) {
      first_row_ = v0, last_row_ = v1 + 1, first_word_ = x0 >> 6, last_word_ = (x1 >> 6) + 1;
      return;
    }
    first_row_ = std::min(first_row_, v0), last_row_ = std::max(last_row_, v1 + 1);
    first_word_ = std::min(first_word_, x0 >> 6), last_word_ = std::max(last_word_, (x1 >> 6) + 1);
  }
  // Rows [first, last) and, in each, words [first, last) hold every set pixel (first_row()
  // == last_row(): none).
  int first_row() const { return first_row_; }
  int last_row() const { return last_row_; }
  int first_word() const { return first_word_; }
  int last_word() const { return last_word_; }
  void Clear();
  int Count() const;
  // Sets every pixel set in `other` (same size).
  void Or(const BitMask& other);
  // This mask grown by one pixel (3 x 3 square) into `out` (same size).
  void DilateInto(BitMask* out) const;
  // Words [w0, w1) of row v of this mask grown by one pixel, into out[w0, w1).
  void DilatedRow(int v, int w0, int w1, uint64_t* out) const;
  cv::Mat ToMat() const;  // CV_8U, 255 where set

 private:
  int width_ = 0, height_ = 0, words_ = 0;
  std::vector<uint64_t> bits_;
  int first_row_ = 0, last_row_ = 0, first_word_ = 0, last_word_ = 0;
};

class BitSilhouetteRenderer {
 public:
  explicit BitSilhouetteRenderer(const Camera& camera) : projector_(camera) {}
  const Camera& camera() const { return projector_.camera(); }
  const CapsuleProjector& projector() const { return projector_; }

  // Draws the capsules into `mask` (the camera's size; not cleared first) and appends to
  // `outline` (may be null) points along each drawn capsule's outline (its two tangent
  // segments and end arcs), at most `outline_step_px` apart.
  void Draw(const std::vector<Capsule>& capsules, BitMask* mask, std::vector<Eigen::Vector2f>* outline = nullptr,
            double outline_step_px = 3) const;

 private:
  CapsuleProjector projector_;
};

// sin and cos of |x| <= pi, to about 1e-14: Taylor polynomials at x / 4, then the double
// angle twice. The outline's arcs turn by one such step each, for every part of every
// particle and camera, where libm's sincos was 5% of a tracking run. Inline: out of line,
// this polynomial was 5% again.
inline void SinCos(double x, double* sin_x, double* cos_x) {
  const double y = 0.25 * x, y2 = y * y;
  // Horner's rule on y^2; the first terms left out are y^17 / 17! and y^16 / 16!, under
  // 2e-15 at |y| <= pi / 4.
  double s = -1.0 / 1307674368000;  // -1 / 15!
  for (const double k : {1.0 / 6227020800, -1.0 / 39916800, 1.0 / 362880, -1.0 / 5040, 1.0 / 120, -1.0 / 6, 1.0}) {
    s = s * y2 + k;
  }
  s *= y;
  double c = -1.0 / 87178291200;  // -1 / 14!
  for (const double k : {1.0 / 479001600, -1.0 / 3628800, 1.0 / 40320, -1.0 / 720, 1.0 / 24, -1.0 / 2, 1.0}) {
    c = c * y2 + k;
  }
  for (int k = 0; k < 2; ++k) {
    const double s2 = 2 * s * c;
    c = (c - s) * (c + s);
    s = s2;
  }
  *sin_x = s, *cos_x = c;
}

}  // namespace jgpm
