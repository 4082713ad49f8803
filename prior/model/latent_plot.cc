#include "prior/model/latent_plot.h"

#include <cmath>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/base/png_file.h"

namespace jgpm {
namespace {

// Layer colours (BGR) from the smallest stride scale to the largest.
cv::Scalar LayerColour(int rank, int layers) {
  static const cv::Scalar kColours[] = {{220, 120, 30}, {40, 170, 40}, {40, 40, 220}, {160, 60, 160}};
  if (layers == 1) return {40, 40, 40};
  return kColours[std::min(rank, 3)];
}

void Title(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.55) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, {0, 0, 0}, 1, cv::LINE_AA);
}

}  // namespace

void PlotLatentSpace(const GaitModel& model, const std::filesystem::path& png,
                     const LatentPlotOptions& options) {
  const TrainingSet& set = model.data().set;
  const Eigen::MatrixXd& x = model.latent();
  const int n = model.NumPoints();
  const int width = options.width;
  const int view = width / 2;           // the 3-D view is a square on the left
  const int slice = width / 4;          // slices: a 2 x 2 grid on the right (3 used + legend)
  cv::Mat image(view + 40, width, CV_8UC3, cv::Scalar(255, 255, 255));
  std::vector<int> rank(set.NumLayers());
  {
    std::vector<int> order(set.NumLayers());
    for (int l = 0; l < set.NumLayers(); ++l) order[l] = l;
    std::sort(order.begin(), order.end(), [&](int a, int b) { return set.layer_scales[a] < set.layer_scales[b]; });
    for (int k = 0; k < set.NumLayers(); ++k) rank[order[k]] = k;
  }
  const Eigen::RowVector3d low = x.colwise().minCoeff(), high = x.colwise().maxCoeff();
  const Eigen::RowVector3d centre = (low + high) / 2;
  const double extent = std::max(1e-9, (high - low).maxCoeff()) * 0.55;

  // 3-D view: azimuth 35 degrees, elevation 30 degrees, orthographic.
  const double az = 35 * std::numbers::pi / 180, el = 30 * std::numbers::pi / 180;
  Eigen::Matrix<double, 2, 3> projection;
  projection << std::cos(az), std::sin(az), 0, -std::sin(az) * std::sin(el), std::cos(az) * std::sin(el), std::cos(el);
  const double view_scale = view * 0.42 / extent;
  auto to_view = [&](const Eigen::RowVector3d& p) {
    const Eigen::Vector2d q = projection * (p - centre).transpose();
    return cv::Point2d(view / 2.0 + view_scale * q.x(), 20 + view / 2.0 - view_scale * q.y());
  };
  for (int layer = 0; layer < set.NumLayers(); ++layer) {
    const cv::Scalar colour = LayerColour(rank[layer], set.NumLayers());
    for (int g = 0; g < set.NumGaits(); ++g) {
      for (int p = 0; p < set.poses_per_gait; ++p) {
        const int i = set.Row(layer, g, p);
        if (p + 1 < set.poses_per_gait) {
          cv::line(image, to_view(x.row(i)), to_view(x.row(i + 1)), colour * 0.5 + cv::Scalar(127, 127, 127), 1, cv::LINE_AA);
        }
        cv::circle(image, to_view(x.row(i)), 2, colour, cv::FILLED, cv::LINE_AA);
      }
    }
  }
  Title(image, std::string(ModelKindName(model.kind())) + ": " + std::to_string(n) +
                   " latent points, " + std::to_string(set.NumGaits()) + " gaits x " +
                   std::to_string(set.NumLayers()) + " layer(s)", {10, 18});

  // Slices through the centre, perpendicular to z, y and x.
  const int res = options.slice_resolution;
  const int axes[3][3] = {{0, 1, 2}, {0, 2, 1}, {1, 2, 0}};  // (horizontal, vertical, normal)
  const char* names[3] = {"slice z = centre (x right, y up)", "slice y = centre (x right, z up)",
                          "slice x = centre (y right, z up)"};
  for (int s = 0; s < 3; ++s) {
    const int h = axes[s][0], v = axes[s][1], normal = axes[s][2];
    Eigen::MatrixXd grid(res * res, 3);
    for (int r = 0; r < res; ++r) {
      for (int c = 0; c < res; ++c) {
        Eigen::RowVector3d p = centre;
        p[h] = centre[h] + extent * (2.0 * (c + 0.5) / res - 1);
        p[v] = centre[v] - extent * (2.0 * (r + 0.5) / res - 1);
        grid.row(r * res + c) = p;
      }
    }
    const Eigen::VectorXd variance = model.Variances(grid);
    cv::Mat values(res, res, CV_64F);
    for (int k = 0; k < res * res; ++k) values.at<double>(k / res, k % res) = std::log10(std::max(variance[k], 1e-12));
    double lo, hi;
    cv::minMaxLoc(values, &lo, &hi);
    cv::Mat gray, heat;
    values.convertTo(gray, CV_8U, 255.0 / std::max(1e-9, hi - lo), -lo * 255.0 / std::max(1e-9, hi - lo));
    cv::applyColorMap(gray, heat, cv::COLORMAP_VIRIDIS);
    cv::resize(heat, heat, cv::Size(slice - 20, slice - 40), 0, 0, cv::INTER_NEAREST);
    const cv::Point origin(view + (s % 2) * slice + 10, 30 + (s / 2) * slice);
    heat.copyTo(image(cv::Rect(origin.x, origin.y, heat.cols, heat.rows)));
    const double to_pixels = heat.cols / (2 * extent);
    for (int i = 0; i < n; ++i) {
      if (std::abs(x(i, normal) - centre[normal]) > 0.15 * extent) continue;
      const cv::Point2d q(origin.x + heat.cols / 2.0 + to_pixels * (x(i, h) - centre[h]),
                          origin.y + heat.rows / 2.0 - heat.rows / (2 * extent) * (x(i, v) - centre[v]));
      cv::circle(image, q, 2, cv::Scalar(255, 255, 255), cv::FILLED, cv::LINE_AA);
      cv::circle(image, q, 2, LayerColour(rank[set.points[i].layer], set.NumLayers()), 1, cv::LINE_AA);
    }
    char range[96];
    std::snprintf(range, sizeof(range), "log10 variance %.1f (dark) .. %.1f (bright)", lo, hi);
    Title(image, names[s], {origin.x, origin.y - 8}, 0.45);
    Title(image, range, {origin.x, origin.y + heat.rows + 14}, 0.4);
  }
  // Legend in the fourth cell.
  const cv::Point legend(view + slice + 10, 50 + slice);
  for (int layer = 0; layer < set.NumLayers(); ++layer) {
    const cv::Point at(legend.x, legend.y + 22 * rank[layer]);
    cv::circle(image, at, 5, LayerColour(rank[layer], set.NumLayers()), cv::FILLED, cv::LINE_AA);
    char label[64];
    std::snprintf(label, sizeof(label), "layer scale %.2f", set.layer_scales[layer]);
    Title(image, label, {at.x + 12, at.y + 5}, 0.5);
  }
  Title(image, "lines join each gait's poses in cycle order", {legend.x, legend.y + 22 * set.NumLayers() + 10}, 0.45);
  Title(image, "slices: points within 15% of the slice", {legend.x, legend.y + 22 * set.NumLayers() + 32}, 0.45);

  WritePngFile(png, image);
}

}  // namespace jgpm
