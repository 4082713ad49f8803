#include "tracker/body/bit_silhouette.h"

#include <algorithm>
#include <bit>
#include <cmath>
#include <numbers>

#include "io/base/error.h"

namespace jgpm {

BitMask::BitMask(int width, int height)
    : width_(width), height_(height), words_((width + 63) / 64), bits_(static_cast<size_t>(words_) * height, 0) {}

BitMask BitMask::FromMat(const cv::Mat& mask, cv::Rect region) {
  BitMask bits(mask.cols, mask.rows);
  region &= cv::Rect(0, 0, mask.cols, mask.rows);
  if (region.empty()) return bits;
  for (int v = region.y; v < region.y + region.height; ++v) {
    const uint8_t* m = mask.ptr<uint8_t>(v);
    uint64_t* out = &bits.bits_[static_cast<size_t>(v) * bits.words_];
    for (int u = region.x; u < region.x + region.width; ++u) {
      if (m[u]) out[u >> 6] |= uint64_t{1} << (u & 63);
    }
  }
  bits.Mark(region.y, region.y + region.height - 1, region.x, region.x + region.width - 1);
  return bits;
}

void BitMask::SetSpan(int v, int x0, int x1) {
  if (v < 0 || v >= height_) return;
  x0 = std::max(x0, 0);
  x1 = std::min(x1, width_ - 1);
  if (x1 < x0) return;
  Mark(v, v, x0, x1);
  SetSpanUnchecked(v, x0, x1);
}

void BitMask::Clear() {
  for (int v = first_row_; v < last_row_; ++v) {
    uint64_t* r = &bits_[static_cast<size_t>(v) * words_];
    std::fill(r + first_word_, r + last_word_, 0);
  }
  first_row_ = last_row_ = first_word_ = last_word_ = 0;
}

int BitMask::Count() const {
  int n = 0;
  for (int v = first_row_; v < last_row_; ++v) {
    const uint64_t* r = row(v);
    for (int k = first_word_; k < last_word_; ++k) n += std::popcount(r[k]);
  }
  return n;
}

void BitMask::DilatedRow(int v, int w0, int w1, uint64_t* out) const {
  if (w1 <= w0) return;
  const uint64_t* r = row(v);
  // Each word of the row with the rows above and below; the sideways spread needs the
  // words either side of [w0, w1) too.
  auto vertical = [&](int k) {
    if (k < 0 || k >= words_) return uint64_t{0};
    uint64_t x = r[k];
    if (v > 0) x |= r[k - words_];
    if (v + 1 < height_) x |= r[k + words_];
    return x;
  };
  // Sideways: each bit also sets its neighbours, carried across words (bit u is pixel u).
  uint64_t previous = vertical(w0 - 1), x = vertical(w0);
  for (int k = w0; k < w1; ++k) {
    const uint64_t next = vertical(k + 1);
    out[k] = x | (x << 1) | (previous >> 63) | (x >> 1) | (next << 63);
    previous = x, x = next;
  }
  if (w1 == words_ && width_ % 64) out[words_ - 1] &= ~uint64_t{0} >> (64 - width_ % 64);
}

void BitMask::Or(const BitMask& other) {
  if (other.first_row_ == other.last_row_) return;
  for (int v = other.first_row_; v < other.last_row_; ++v) {
    uint64_t* out = &bits_[static_cast<size_t>(v) * words_];
    const uint64_t* in = other.row(v);
    for (int w = other.first_word_; w < other.last_word_; ++w) out[w] |= in[w];
  }
  Mark(other.first_row_, other.last_row_ - 1, other.first_word_ * 64, std::min(width_, other.last_word_ * 64) - 1);
}

void BitMask::DilateInto(BitMask* out) const {
  *out = BitMask(width_, height_);
  if (first_row_ == last_row_) return;
  const int v0 = std::max(0, first_row_ - 1), v1 = std::min(height_, last_row_ + 1);
  const int w0 = std::max(0, first_word_ - 1), w1 = std::min(words_, last_word_ + 1);
  for (int v = v0; v < v1; ++v) DilatedRow(v, w0, w1, &out->bits_[static_cast<size_t>(v) * words_]);
  out->Mark(v0, v1 - 1, w0 * 64, std::min(width_, w1 * 64) - 1);
}

cv::Mat BitMask::ToMat() const {
  cv::Mat mask = cv::Mat::zeros(height_, width_, CV_8UC1);
  for (int v = first_row_; v < last_row_; ++v) {
    uint8_t* out = mask.ptr<uint8_t>(v);
    const uint64_t* r = row(v);
    for (int u = 0; u < width_; ++u) out[u] = (r[u >> 6] >> (u & 63)) & 1 ? 255 : 0;
  }
  return mask;
}

namespace {

// ceil and floor to int for |x| well inside the int range (the projector culls what is
// far outside the image): a truncation and a compare, where std::ceil/floor are library
// calls on jgpm's baseline x86-64 (no SSE4.1 rounding instruction).
inline int CeilInt(double x) {
  x = std::clamp(x, -1e9, 1e9);
  const int i = static_cast<int>(x);
  return i + (x > i);
}
inline int FloorInt(double x) {
  x = std::clamp(x, -1e9, 1e9);
  const int i = static_cast<int>(x);
  return i - (x < i);
}

}  // namespace

void BitSilhouetteRenderer::Draw(const std::vector<Capsule>& capsules, BitMask* mask,
                                 std::vector<Eigen::Vector2f>* outline, double outline_step_px) const {
  JGPM_CHECK(mask->width() == camera().width && mask->height() == camera().height);
  ImageCapsule c;
  for (const Capsule& capsule : capsules) {
    if (!projector_.Project(capsule, &c)) continue;
    // In the capsule's round frame (silhouette.h), where its ends are discs.
    const Eigen::Vector2d ra_centre = c.Round(c.a), rb_centre = c.Round(c.b);
    const Eigen::Vector2d d = rb_centre - ra_centre;
    const double length = d.norm();
    // The hull: both ends, and, unless one holds the other, the quadrilateral between the
    // outer tangents' touching points (round frame: u along the axis, n its normal,
    // sin(phi) = (ra - rb) / |d|, the tangents touch in directions +-n cos(phi) + u sin(phi)),
    // mapped to the image.
    const bool quad = length > std::abs(c.ra - c.rb) + 1e-9;
    Eigen::Vector2d q[4];
    Eigen::Vector2d ta = Eigen::Vector2d::Zero(), tb = Eigen::Vector2d::Zero();  // used only with quad
    if (quad) {
      const Eigen::Vector2d u = d / length, n(-u.y(), u.x());
      const double sin_phi = (c.ra - c.rb) / length, cos_phi = std::sqrt(std::max(0.0, 1 - sin_phi * sin_phi));
      ta = n * cos_phi + u * sin_phi;
      tb = -n * cos_phi + u * sin_phi;
      q[0] = c.Image(ra_centre + c.ra * ta);
      q[1] = c.Image(rb_centre + c.rb * ta);
      q[2] = c.Image(rb_centre + c.rb * tb);
      q[3] = c.Image(ra_centre + c.ra * tb);
    }
    // Each end's ellipse: p in it when (p - centre)' M (p - centre) <= r^2, M = I - lean
    // lean' / k^2 (Round's map squared, as k^2 = 1 + |lean|^2, and 1 / k = shrink (k + 1));
    // it spans at most r k above and below its centre. (Few divisions and roots: this
    // runs for every part of every particle and camera.)
    const double inverse_k = c.shrink * (c.stretch + 1), inverse_k2 = inverse_k * inverse_k;
    const double m00 = 1 - inverse_k2 * c.lean.x() * c.lean.x(), m01 = -inverse_k2 * c.lean.x() * c.lean.y(),
                 m11 = 1 - inverse_k2 * c.lean.y() * c.lean.y();
    const double half_height = c.stretch;
    const double inverse_m00 = 1 / m00;
    // Rows v0..v1 (clamped to the image; coordinates are bounded by the projector's culling,
    // so the int conversions are defined). The quad's two side edges, q0-q1 and q2-q3, as
    // x = x0 + (v - y0) * slope over [y0, y1], set up once per capsule; its other two are
    // chords of the end ellipses, inside them, so they add nothing to a row's span (nor
    // does a horizontal side edge, whose ends are on the ellipses).
    const double top = std::min(c.a.y() - c.ra * half_height, c.b.y() - c.rb * half_height);
    const double bottom = std::max(c.a.y() + c.ra * half_height, c.b.y() + c.rb * half_height);
    const int v0 = std::max(0, CeilInt(top)), v1 = std::min(mask->height() - 1, FloorInt(bottom));
    if (v1 < v0) continue;
    struct Edge {
      double y0 = 1, y1 = 0, x0 = 0, slope = 0;  // y1 < y0: no row
    } edges[2];
    if (quad) {
      for (int e = 0; e < 2; ++e) {
        const Eigen::Vector2d& p = q[2 * e];
        const Eigen::Vector2d& s = q[2 * e + 1];
        if (p.y() == s.y()) continue;
        const Eigen::Vector2d& lo = p.y() < s.y() ? p : s;
        const Eigen::Vector2d& hi = p.y() < s.y() ? s : p;
        edges[e] = {lo.y(), hi.y(), lo.x(), (hi.x() - lo.x()) / (hi.y() - lo.y())};
      }
    }
    const double ra2 = c.ra * c.ra, rb2 = c.rb * c.rb;
    const int last_column = mask->width() - 1;
    int drawn_first = mask->height(), drawn_last = -1, drawn_left = mask->width(), drawn_right = -1;
    // Row v's span of each end's ellipse: m00 x^2 + 2 m01 x dy + m11 dy^2 <= r^2 in x
    // (relative to its centre, dy = v - its row), i.e. x = -slope dy +- sqrt(curve dy^2 +
    // r^2 / m00): as short a chain of dependent operations per row as a circle's.
    const double slope = m01 * inverse_m00, curve = slope * slope - m11 * inverse_m00;
    const double ax = c.a.x(), ay = c.a.y(), bx = c.b.x(), by = c.b.y();
    const double ca = ra2 * inverse_m00, cb = rb2 * inverse_m00;
    for (int v = v0; v <= v1; ++v) {
      double left = 1e300, right = -1e300;
      const double da = v - ay, ha2 = curve * da * da + ca;
      if (ha2 >= 0) {
        const double h = std::sqrt(ha2), x = ax - slope * da;
        left = x - h, right = x + h;
      }
      const double db = v - by, hb2 = curve * db * db + cb;
      if (hb2 >= 0) {
        const double h = std::sqrt(hb2), x = bx - slope * db;
        left = std::min(left, x - h), right = std::max(right, x + h);
      }
      for (const Edge& edge : edges) {
        if (v < edge.y0 || v > edge.y1) continue;
        const double x = edge.x0 + (v - edge.y0) * edge.slope;
        left = std::min(left, x), right = std::max(right, x);
      }
      if (right < left) continue;
      const int x0 = std::max(0, CeilInt(left)), x1 = std::min(last_column, FloorInt(right));
      if (x1 < x0) continue;
      mask->SetSpanUnchecked(v, x0, x1);
      drawn_first = std::min(drawn_first, v), drawn_last = v;
      drawn_left = std::min(drawn_left, x0), drawn_right = std::max(drawn_right, x1);
    }
    if (drawn_last >= 0) mask->Mark(drawn_first, drawn_last, drawn_left, drawn_right);
    if (outline) {
      auto segment = [&](const Eigen::Vector2d& from, const Eigen::Vector2d& to) {
        const int steps = std::max(1, static_cast<int>(std::ceil((to - from).norm() / outline_step_px)));
        const Eigen::Vector2d delta = (to - from) / steps;
        for (int k = 0; k < steps; ++k) outline->push_back((from + k * delta).cast<float>());
      };
      // Points on the arc of (centre, radius) of the round frame from unit direction
      // `start`, turning by `span` radians, in the image: each offset from the ellipse's
      // centre is the last one turned by the step's rotation seen through Image's map
      // (S R S^-1), so one sine and cosine per arc.
      const Eigen::Matrix2d stretch_map = Eigen::Matrix2d::Identity() + c.grow * c.lean * c.lean.transpose();
      const Eigen::Matrix2d squeeze_map = Eigen::Matrix2d::Identity() - c.shrink * c.lean * c.lean.transpose();
      auto arc = [&](const Eigen::Vector2d& centre, double radius, const Eigen::Vector2d& start, double span) {
        const int steps =
            std::max(2, static_cast<int>(std::ceil(std::abs(span) * radius * c.stretch / outline_step_px)));
        double cs, sn;
        SinCos(span / steps, &sn, &cs);
        const Eigen::Matrix2d turn = stretch_map * (Eigen::Matrix2d() << cs, -sn, sn, cs).finished() * squeeze_map;
        const Eigen::Vector2d base = c.Image(centre);
        Eigen::Vector2d offset = stretch_map * (radius * start);
        for (int k = 0; k <= steps; ++k) {
          outline->push_back((base + offset).cast<float>());
          offset = turn * offset;
        }
      };
      if (quad) {
        // As tracker/body/silhouette.cc walks it: the far side of b from ta to tb, the back of a
        // from tb to ta.
        const double half = std::numbers::pi / 2 - std::asin(std::clamp((c.ra - c.rb) / length, -1.0, 1.0));
        segment(q[0], q[1]);
        segment(q[2], q[3]);
        arc(rb_centre, c.rb, ta, -2 * half);
        arc(ra_centre, c.ra, tb, -(2 * std::numbers::pi - 2 * half));
      } else {
        arc(c.ra >= c.rb ? ra_centre : rb_centre, std::max(c.ra, c.rb), Eigen::Vector2d(1, 0), 2 * std::numbers::pi);
      }
    }
  }
}

}  // namespace jgpm
