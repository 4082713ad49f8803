#include "prior/eval/validation_report.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>
#include <set>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/base/json_file.h"
#include "io/base/png_file.h"

namespace jgpm {
namespace {

std::string Number(double value, const char* format = "%.4g") {
  char text[64];
  std::snprintf(text, sizeof(text), format, value);
  return text;
}

cv::Scalar ModelColour(int i) {  // BGR, distinguishable in print
  static const cv::Scalar kColours[] = {{60, 60, 60},   {200, 120, 30}, {40, 160, 40},  {40, 40, 210},
                                        {170, 60, 170}, {30, 170, 200}, {120, 80, 20},  {90, 90, 230},
                                        {150, 150, 150}};
  return kColours[i % 9];
}

// One colour per series: the palette in order, except that "X+posture" (a model with
// posture adaptation, beside X itself) takes a light tint of X's colour, so that a suite of
// 16 series still pairs each model with its adapted self.
std::vector<cv::Scalar> SeriesColours(const std::vector<std::string>& names) {
  const std::string suffix = "+posture";
  std::vector<cv::Scalar> colours(names.size());
  std::vector<int> base(names.size(), -1);
  int next = 0;
  for (size_t m = 0; m < names.size(); ++m) {
    const std::string& n = names[m];
    if (n.size() > suffix.size() && n.compare(n.size() - suffix.size(), suffix.size(), suffix) == 0) {
      const auto it = std::find(names.begin(), names.end(), n.substr(0, n.size() - suffix.size()));
      if (it != names.end()) base[m] = static_cast<int>(it - names.begin());
    }
    if (base[m] < 0) colours[m] = ModelColour(next++);
  }
  for (size_t m = 0; m < names.size(); ++m) {
    if (base[m] >= 0) colours[m] = 0.45 * colours[base[m]] + 0.55 * cv::Scalar(255, 255, 255);
  }
  return colours;
}

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.45) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, {0, 0, 0}, 1, cv::LINE_AA);
}

// One panel: error (mm) against scale, a bar per model, whiskers for the standard deviation.
struct Panel {
  std::string title;
  std::vector<double> scales;                               // groups, left to right
  std::vector<std::vector<const ValidationResult*>> bars;   // [model][scale], may hold nulls
};

void DrawPanel(cv::Mat& image, const cv::Rect& area, const Panel& panel, const std::vector<cv::Scalar>& colours,
               double top_mm, bool whiskers) {
  const int left = area.x + 50, bottom = area.y + area.height - 30, height = area.height - 60;
  const int width = area.width - 60;
  Text(image, panel.title, {area.x + 50, area.y + 18}, 0.5);
  cv::line(image, {left, bottom}, {left + width, bottom}, {0, 0, 0});
  cv::line(image, {left, bottom}, {left, bottom - height}, {0, 0, 0});
  const double step = std::pow(10, std::floor(std::log10(top_mm / 2)));
  const double tick = top_mm / step > 8 ? 2 * step : step;
  for (double mm = 0; mm <= top_mm + 1e-9; mm += tick) {
    const int y = bottom - static_cast<int>(height * mm / top_mm);
    cv::line(image, {left - 4, y}, {left + width, y}, {225, 225, 225});
    Text(image, Number(mm, "%g"), {area.x + 5, y + 4}, 0.4);
  }
  Text(image, "mm", {area.x + 10, bottom - height - 8}, 0.4);
  const int groups = static_cast<int>(panel.scales.size()), models = static_cast<int>(panel.bars.size());
  const double group_width = static_cast<double>(width) / std::max(1, groups);
  const double bar_width = group_width * 0.8 / std::max(1, models);
  for (int g = 0; g < groups; ++g) {
    const double x0 = left + g * group_width + group_width * 0.1;
    Text(image, "s=" + Number(panel.scales[g], "%g"), {static_cast<int>(x0 + group_width * 0.25), bottom + 18}, 0.4);
    for (int m = 0; m < models; ++m) {
      const ValidationResult* r = panel.bars[m][g];
      if (!r) continue;
      const int xa = static_cast<int>(x0 + m * bar_width), xb = static_cast<int>(x0 + (m + 1) * bar_width) - 1;
      const int y = bottom - static_cast<int>(height * std::min(r->mean_error_mm, top_mm) / top_mm);
      cv::rectangle(image, {xa, y}, {std::max(xa, xb), bottom}, colours[m], cv::FILLED);
      if (whiskers && r->std_error_mm > 0) {
        const int xm = (xa + xb) / 2;
        const int ya = bottom - static_cast<int>(height * std::min(r->mean_error_mm + r->std_error_mm, top_mm) / top_mm);
        const int yb = bottom - static_cast<int>(height * std::max(r->mean_error_mm - r->std_error_mm, 0.0) / top_mm);
        cv::line(image, {xm, ya}, {xm, yb}, {0, 0, 0});
      }
    }
  }
}

// A chart of `panels` side by side with a legend of the models underneath.
cv::Mat Chart(const std::vector<Panel>& panels, const std::vector<std::string>& models, const std::string& title,
              bool whiskers) {
  double top = 1;
  for (const Panel& p : panels) {
    for (const auto& row : p.bars) {
      for (const ValidationResult* r : row) {
        if (r) top = std::max(top, r->mean_error_mm + (whiskers ? r->std_error_mm : 0));
      }
    }
  }
  top *= 1.08;
  const std::vector<cv::Scalar> colours = SeriesColours(models);
  // At least two panels wide, so the title and a legend of four columns fit.
  const int panel_width = 520, panel_height = 380;
  const int width = panel_width * std::max<int>(2, static_cast<int>(panels.size()));
  const int columns = width / 260, legend_rows = (static_cast<int>(models.size()) + columns - 1) / columns;
  cv::Mat image(panel_height + 40 + 22 * legend_rows, width, CV_8UC3, cv::Scalar(255, 255, 255));
  Text(image, title, {10, 22}, 0.6);
  for (size_t i = 0; i < panels.size(); ++i) {
    const int w = width / static_cast<int>(panels.size());
    DrawPanel(image, cv::Rect(static_cast<int>(i) * w, 30, w, panel_height), panels[i], colours, top, whiskers);
  }
  for (size_t m = 0; m < models.size(); ++m) {
    const int column = static_cast<int>(m) % columns, row = static_cast<int>(m) / columns;
    const cv::Point at(20 + column * 260, panel_height + 45 + 22 * row);
    cv::rectangle(image, {at.x, at.y - 10}, {at.x + 14, at.y + 2}, colours[m], cv::FILLED);
    Text(image, models[m], {at.x + 20, at.y}, 0.45);
  }
  return image;
}

// Per joint, each model's error averaged over every case of the suite: horizontal bars,
// a row of bars per joint, so that where the error comes from can be read off.
cv::Mat JointChart(const std::vector<ModelResults>& suite) {
  const std::vector<std::string>& joints = suite[0].results[0].joint_names;
  const int n = static_cast<int>(joints.size()), models = static_cast<int>(suite.size());
  std::vector<std::string> names;
  for (const ModelResults& r : suite) names.push_back(r.model);
  const std::vector<cv::Scalar> colours = SeriesColours(names);
  std::vector<std::vector<double>> mm(models, std::vector<double>(n, 0.0));
  double top = 1;
  for (int m = 0; m < models; ++m) {
    for (const ValidationResult& r : suite[m].results) {
      for (int j = 0; j < n && j < static_cast<int>(r.joint_errors_mm.size()); ++j) {
        mm[m][j] += r.joint_errors_mm[j] / suite[m].results.size();
      }
    }
    for (double v : mm[m]) top = std::max(top, v);
  }
  top *= 1.08;
  const int bar = 9, row = models * bar + 8, left = 110, width = 900, plot = width - left - 30;
  const int columns = width / 260, legend_rows = (models + columns - 1) / columns;
  const int axis = 60, height = axis + n * row + 20 + 22 * legend_rows;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  Text(image, "Error per joint, mean over the " + std::to_string(suite[0].results.size()) + " case(s) (mm)", {10, 22}, 0.6);
  const double step = std::pow(10, std::floor(std::log10(top / 2)));
  const double tick = top / step > 8 ? 2 * step : step;
  for (double v = 0; v <= top + 1e-9; v += tick) {
    const int x = left + static_cast<int>(plot * v / top);
    cv::line(image, {x, axis - 4}, {x, axis + n * row}, {225, 225, 225});
    Text(image, Number(v, "%g"), {x - 8, axis - 10}, 0.4);
  }
  for (int j = 0; j < n; ++j) {
    const int y0 = axis + j * row + 4;
    Text(image, joints[j], {10, y0 + models * bar / 2 + 5}, 0.45);
    for (int m = 0; m < models; ++m) {
      const int length = static_cast<int>(plot * mm[m][j] / top);
      cv::rectangle(image, {left, y0 + m * bar}, {left + std::max(0, length - 1), y0 + (m + 1) * bar - 2},
                    colours[m], cv::FILLED);
    }
  }
  for (int m = 0; m < models; ++m) {
    const cv::Point at(20 + (m % columns) * 260, axis + n * row + 30 + 22 * (m / columns));
    cv::rectangle(image, {at.x, at.y - 10}, {at.x + 14, at.y + 2}, colours[m], cv::FILLED);
    Text(image, suite[m].model, {at.x + 20, at.y}, 0.45);
  }
  return image;
}

}  // namespace

nlohmann::json ValidationResultJson(const ValidationResult& r) {
  const ValidationCase& c = r.validation_case;
  nlohmann::json j;
  j["case"] = c.Label();
  j["task"] = std::string(ValidationTaskName(c.task));
  j["scale"] = c.scale;
  if (c.task == ValidationTask::kReconstruction) j["missing"] = std::string(MissingPartName(c.missing));
  if (c.task == ValidationTask::kFiltering) {
    j["noise"] = c.noise;
    j["draws"] = c.draws;
    j["draw_errors_mm"] = r.draw_errors_mm;
  }
  j["mean_error_mm"] = r.mean_error_mm;
  j["std_error_mm"] = r.std_error_mm;
  j["inference_failures"] = r.inference_failures;
  nlohmann::json trials = nlohmann::json::array();
  for (size_t i = 0; i < r.trials.size(); ++i) trials.push_back({{"trial", r.trials[i]}, {"error_mm", r.trial_errors_mm[i]}});
  j["trials"] = trials;
  nlohmann::json joints = nlohmann::json::array(), channels = nlohmann::json::array();
  for (size_t k = 0; k < r.joint_names.size(); ++k) joints.push_back({{"joint", r.joint_names[k]}, {"mm", r.joint_errors_mm[k]}});
  for (size_t k = 0; k < r.channel_names.size(); ++k) {
    nlohmann::json channel = {{"channel", r.channel_names[k]}, {"deg", r.channel_errors_deg[k]}};
    if (k < r.channel_posture_deg.size()) channel["posture_offset_deg"] = r.channel_posture_deg[k];
    if (k < r.channel_gain.size()) channel["gain"] = r.channel_gain[k];
    channels.push_back(channel);
  }
  j["per_joint_mm"] = joints;
  j["per_channel_deg"] = channels;
  j["seconds"] = r.seconds;
  return j;
}

std::string SuiteCsv(const std::vector<ModelResults>& suite) {
  std::string csv = "model,task,missing,noise,scale,mean_error_mm,std_error_mm,trials,seconds\n";
  for (const ModelResults& m : suite) {
    for (const ValidationResult& r : m.results) {
      const ValidationCase& c = r.validation_case;
      csv += m.model + "," + std::string(ValidationTaskName(c.task)) + "," + std::string(MissingPartName(c.missing)) + "," +
             Number(c.noise, "%g") + "," + Number(c.scale, "%g") + "," + Number(r.mean_error_mm, "%.3f") + "," +
             Number(r.std_error_mm, "%.3f") + "," + std::to_string(r.trials.size()) + "," +
             Number(r.seconds, "%.2f") + "\n";
    }
  }
  return csv;
}

std::string SuiteDetailCsv(const std::vector<ModelResults>& suite) {
  std::string csv = "model,task,missing,noise,scale,kind,name,error\n";
  for (const ModelResults& m : suite) {
    for (const ValidationResult& r : m.results) {
      const ValidationCase& c = r.validation_case;
      const std::string key = m.model + "," + std::string(ValidationTaskName(c.task)) + "," +
                              std::string(MissingPartName(c.missing)) + "," + Number(c.noise, "%g") + "," +
                              Number(c.scale, "%g") + ",";
      for (size_t k = 0; k < r.joint_names.size(); ++k) {
        csv += key + "joint_mm," + r.joint_names[k] + "," + Number(r.joint_errors_mm[k], "%.3f") + "\n";
      }
      for (size_t k = 0; k < r.channel_names.size(); ++k) {
        csv += key + "channel_deg," + r.channel_names[k] + "," + Number(r.channel_errors_deg[k], "%.3f") + "\n";
      }
      for (size_t k = 0; k < r.channel_posture_deg.size(); ++k) {
        csv += key + "posture_offset_deg," + r.channel_names[k] + "," + Number(r.channel_posture_deg[k], "%.3f") + "\n";
      }
      for (size_t k = 0; k < r.channel_gain.size(); ++k) {
        csv += key + "gain," + r.channel_names[k] + "," + Number(r.channel_gain[k], "%.4f") + "\n";
      }
    }
  }
  return csv;
}

void PlotSuite(const std::vector<ModelResults>& suite, const std::filesystem::path& folder, OutputBatch* batch) {
  if (!suite.empty() && !suite[0].results.empty() && !suite[0].results[0].joint_names.empty()) {
    const std::filesystem::path path = folder / "joints.png";
    batch->Add(path, EncodePng(JointChart(suite), path.string()));
  }
  std::vector<std::string> models;
  for (const ModelResults& m : suite) models.push_back(m.model);
  // Panels keyed by (task, condition), groups by scale in descending order as in the paper.
  struct Key {
    ValidationTask task;
    MissingPart missing;
    double noise;
    bool operator<(const Key& o) const {
      return std::tie(task, missing, noise) < std::tie(o.task, o.missing, o.noise);
    }
  };
  std::map<Key, Panel> panels;
  std::map<Key, std::set<double, std::greater<double>>> scales;
  for (const ModelResults& m : suite) {
    for (const ValidationResult& r : m.results) {
      const ValidationCase& c = r.validation_case;
      scales[{c.task, c.missing, c.noise}].insert(c.scale);
    }
  }
  for (const auto& [key, scale_set] : scales) {
    Panel& p = panels[key];
    p.scales.assign(scale_set.begin(), scale_set.end());
    p.bars.assign(suite.size(), std::vector<const ValidationResult*>(p.scales.size(), nullptr));
    p.title = key.task == ValidationTask::kReconstruction ? std::string(MissingPartName(key.missing)) + " missing"
              : key.task == ValidationTask::kFiltering    ? Number(100 * key.noise, "%g") + "% noise (mean, std over draws)"
                                                          : "interpolation";
  }
  for (size_t m = 0; m < suite.size(); ++m) {
    for (const ValidationResult& r : suite[m].results) {
      const ValidationCase& c = r.validation_case;
      Panel& p = panels[{c.task, c.missing, c.noise}];
      const auto g = std::find(p.scales.begin(), p.scales.end(), c.scale) - p.scales.begin();
      p.bars[m][g] = &r;
    }
  }
  const struct {
    ValidationTask task;
    const char* file;
    const char* title;
  } charts[] = {
      {ValidationTask::kInterpolation, "interpolation.png", "Interpolation: mean 3-D joint error of unseen cycles scaled by s (Fig. 9)"},
      {ValidationTask::kReconstruction, "reconstruction.png", "Reconstruction of missing joints, error over all 17 joints (Fig. 12)"},
      {ValidationTask::kFiltering, "filtering.png", "Filtering white noise of a fraction of each channel's std (Fig. 13)"},
  };
  for (const auto& chart : charts) {
    std::vector<Panel> selected;
    for (const auto& [key, panel] : panels) {
      if (key.task == chart.task) selected.push_back(panel);
    }
    if (selected.empty()) continue;
    const std::filesystem::path path = folder / chart.file;
    batch->Add(path, EncodePng(Chart(selected, models, chart.title, chart.task == ValidationTask::kFiltering),
                               path.string()));
  }
}

std::vector<std::filesystem::path> WriteValidationOutputs(const std::vector<ModelResults>& suite,
                                                          const std::vector<std::string>& model_paths,
                                                          const std::string& split,
                                                          const std::filesystem::path& json,
                                                          const std::filesystem::path& folder,
                                                          const std::string& csv_name) {
  JGPM_CHECK(suite.size() == model_paths.size());
  OutputBatch batch;
  if (!json.empty()) {
    nlohmann::json j;
    if (suite.size() == 1 && suite[0].results.size() == 1) {
      j = ValidationResultJson(suite[0].results[0]);  // one case: its fields at the top
      j["model"] = model_paths[0];
    } else {
      j["models"] = nlohmann::json::array();
      for (size_t m = 0; m < suite.size(); ++m) {
        nlohmann::json results = nlohmann::json::array();
        for (const ValidationResult& r : suite[m].results) results.push_back(ValidationResultJson(r));
        j["models"].push_back({{"model", model_paths[m]}, {"name", suite[m].model}, {"results", results}});
      }
    }
    j["split"] = split;
    batch.Add(json, FormatJson(j));
  }
  if (!folder.empty()) {
    batch.Add(folder / csv_name, SuiteCsv(suite));
    batch.Add(folder / (std::filesystem::path(csv_name).stem().string() + "_detail.csv"), SuiteDetailCsv(suite));
    PlotSuite(suite, folder, &batch);
  }
  return batch.Commit();
}

}  // namespace jgpm
