#include "tracker/run/track_output.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <numbers>

#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/mocap/asf.h"
#include "io/mocap/kinematics.h"
#include "tracker/body/bit_silhouette.h"
#include "tracker/body/cast_shadow.h"
#include "tracker/clip/contact_sheet.h"
#include "tracker/filter/shadow_light.h"

namespace jgpm {
namespace {

using nlohmann::json;

constexpr double kDegPerRad = 180.0 / std::numbers::pi;

double Round2(double v) { return std::round(v * 100) / 100; }

json Points(const Eigen::Matrix3Xd& m) {
  json points = json::array();
  for (int j = 0; j < m.cols(); ++j) points.push_back({Round2(m(0, j)), Round2(m(1, j)), Round2(m(2, j))});
  return points;
}

json ErrorsJson(const TrackErrors& e) {
  json per_joint = json::object();
  for (size_t j = 0; j < e.joints.size(); ++j) per_joint[e.joints[j]] = e.per_joint_mm[j];
  return {{"frames", e.frames},          {"absolute_mm", e.absolute_mm}, {"root_relative_mm", e.root_relative_mm},
          {"procrustes_mm", e.procrustes_mm}, {"failure_rate", e.failure_rate}, {"swap_rate", e.swap_rate},
          {"per_joint_mm", per_joint}};
}

double Median(std::vector<double> v) {
  if (v.empty()) return 1;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

// The ASF text with its `:units length` scaled so every length is `size` times longer.
std::string ScaledAsf(const std::string& asf, double length_scale, double size) {
  const size_t units = asf.find(":units");
  const size_t at = units == std::string::npos ? std::string::npos : asf.find("length", units);
  if (at == std::string::npos) ThrowInputError("the model's skeleton", "has no `:units length` to scale");
  const size_t end = asf.find('\n', at);
  char line[64];
  std::snprintf(line, sizeof(line), "length %.9g", length_scale / size);
  return asf.substr(0, at) + line + asf.substr(end);
}

// The ASF text with each limb bone's `length` times the proportion (tracker/state/proportions.h).
std::string ProportionedAsf(std::string asf, const Proportions& proportions) {
  static const char* const kLimbs[] = {"femur", "tibia", "foot", "toes",                         // legs
                                       "humerus", "radius", "wrist", "hand", "fingers", "thumb"};  // arms
  for (const char* side : {"l", "r"}) {
    for (int k = 0; k < 10; ++k) {
      const bool leg = k < 4;
      const std::string name = std::string("name ") + side + kLimbs[k];
      size_t block = asf.find(name);
      while (block != std::string::npos && block + name.size() < asf.size() && !std::isspace(asf[block + name.size()]))
        block = asf.find(name, block + 1);
      const size_t at = block == std::string::npos ? std::string::npos : asf.find("length", block);
      if (at == std::string::npos) continue;  // the placer needed every limb bone; not this one
      const size_t begin = at + 6, end = asf.find('\n', begin);
      const double length = std::strtod(asf.c_str() + begin, nullptr);
      char value[64];
      std::snprintf(value, sizeof(value), " %.9g", length * (leg ? proportions.legs : proportions.arms));
      asf.replace(begin, end - begin, value);
    }
  }
  return asf;
}

}  // namespace

RunErrors EvaluateRun(const TrackRun& run, const Skeleton& skeleton, const std::vector<Eigen::Matrix3Xd>& truth,
                      const std::vector<std::string>& truth_bones) {
  std::vector<Eigen::Matrix3Xd> estimate;
  for (const TrackedFrame& f : run.frames) estimate.push_back(f.state.size() ? f.joints_mm : Eigen::Matrix3Xd());
  const std::vector<std::string> bones = skeleton.BoneNames();
  return {CompareTracks(estimate, bones, truth, truth_bones, Gait17()),
          CompareTracks(estimate, bones, truth, truth_bones, Bodytrack14())};
}

namespace {

// The run's header: what ran on what, with which options and names.
json PosesHeader(const TrackRun& run, const Skeleton& skeleton) {
  json out;
  out["format"] = "jgpm track";
  out["version"] = 1;
  out["model"] = run.model_path;
  out["source"] = run.source;
  out["init"] = run.init;
  out["state_space"] = run.state_space;
  out["fps"] = run.fps;
  json cameras = json::array();
  for (const Camera& c : run.cameras) cameras.push_back(c.name);
  out["cameras"] = cameras;
  out["options"] = {{"particles", run.options.annealing.particles}, {"layers", run.options.annealing.layers},
                    {"seed", run.options.annealing.seed}, {"latent_prior", run.options.annealing.latent_prior},
                    {"known_size", run.options.known_size}};
  out["joint_names"] = skeleton.BoneNames();
  out["joints_note"] = "joints_mm[j] is the end of bone j (the root: its position), world y up, mm";
  out["measured_joints"] = Gait17();
  out["coordinate_names"] = run.coordinate_names;
  return out;
}

// One person's estimate in a frame (without the frame's number and time).
json EstimateJson(const TrackRun& run, const TrackedFrame& f) {
  json j;
  j["status"] = std::string(TrackStatusName(f.status));
  if (f.state.size() == 0) {
    j["joints_mm"] = nullptr;
  } else {
    const int k = static_cast<int>(f.state.size()) - 6;  // the shared placement (tracker/state/state_model.h)
    j["joints_mm"] = Points(f.joints_mm);
    j["root_mm"] = {Round2(f.joints_mm(0, 0)), Round2(f.joints_mm(1, 0)), Round2(f.joints_mm(2, 0))};
    j["heading_deg"] = f.heading_rad * kDegPerRad;
    j["rate"] = f.state[k + 3];
    j["size"] = f.size;
    j["width"] = f.width;
    json widths = json::object();
    for (int r = 0; r < kNumBodyRegions; ++r)
      widths[std::string(BodyRegionName(static_cast<BodyRegion>(r)))] = f.build.widths[r];
    j["build"] = {{"widths", widths},
                  {"legs", f.build.lengths.legs},
                  {"arms", f.build.lengths.arms},
                  {"floor_mm", f.build.floor_mm},
                  {"garment", f.build.garment}};
    json coordinates = json::object();
    for (size_t c = 0; c < run.coordinate_names.size() && static_cast<int>(c) < k; ++c) {
      coordinates[run.coordinate_names[c]] = f.state[c];
    }
    j["coordinates"] = coordinates;
  }
  j["ess"] = f.ess;
  j["evaluations"] = f.evaluations;
  json scores = json::array();
  for (size_t c = 0; c < f.cameras.size(); ++c) {
    scores.push_back({{"camera", run.cameras[c].name}, {"iou", f.cameras[c].Iou()}, {"cost", f.cameras[c].cost}});
  }
  j["cameras"] = scores;
  return j;
}

// The light of the walkers' shadows, from the first frame that has it (the frame it was
// found at): its azimuth and elevation (ShadowLight::Direction's), or null.
json ShadowLightJson(const std::vector<const TrackedFrame*>& frames) {
  for (const TrackedFrame* f : frames) {
    if (!f->shadow_light) continue;
    const Eigen::Vector2d angles = ShadowLight::AnglesOf(*f->shadow_light);
    return {{"azimuth_deg", angles.x()}, {"elevation_deg", angles.y()}, {"found_at_frame", f->index}};
  }
  return nullptr;
}

// Each camera's median share of foreground (TrackRun::foreground_share), by its name; null
// when not measured.
json ForegroundShareJson(const TrackRun& run) {
  if (run.foreground_share.size() != run.cameras.size()) return nullptr;
  json shares = json::object();
  for (size_t c = 0; c < run.cameras.size(); ++c) shares[run.cameras[c].name] = run.foreground_share[c];
  return shares;
}

}  // namespace

json PosesJson(const TrackRun& run, const Skeleton& skeleton, const std::optional<RunErrors>& errors) {
  json out = PosesHeader(run, skeleton);
  json frames = json::array();
  int tracked = 0, predicted = 0, lost = 0;
  long evaluations = 0;
  for (const TrackedFrame& f : run.frames) {
    json j = EstimateJson(run, f);
    j["frame"] = f.index;
    j["time_s"] = f.time_s;
    tracked += f.status == TrackStatus::kTracked;
    predicted += f.status == TrackStatus::kPredicted;
    lost += f.status == TrackStatus::kLost;
    evaluations += f.evaluations;
    frames.push_back(j);
  }
  out["frames"] = frames;
  const int n = static_cast<int>(run.frames.size());
  // No times here: the same seed gives the same file, whatever the threads or the machine.
  out["summary"] = {{"frames", n},
                    {"tracked", tracked},
                    {"predicted", predicted},
                    {"lost", lost},
                    {"evaluations_per_frame", n ? static_cast<double>(evaluations) / n : 0.0}};
  std::vector<const TrackedFrame*> all;
  for (const TrackedFrame& f : run.frames) all.push_back(&f);
  out["summary"]["shadow_light"] = ShadowLightJson(all);
  out["summary"]["foreground_share"] = ForegroundShareJson(run);
  if (errors) out["errors"] = {{"gait17", ErrorsJson(errors->gait17)}, {"bodytrack14", ErrorsJson(errors->bodytrack14)}};
  return out;
}

json PeoplePosesJson(const TrackRun& run, const Skeleton& skeleton, const std::vector<PeopleFrame>& frames,
                     const std::optional<MotResult>& mot) {
  json out = PosesHeader(run, skeleton);
  out["people_note"] = "each frame's people: those alive, each with the fields of a one-person frame and its id";
  json list = json::array();
  std::map<int, std::pair<int, int>> life;  // id -> first, last frame
  long evaluations = 0;
  for (const PeopleFrame& f : frames) {
    json people = json::array();
    for (const PersonFrame& p : f.people) {
      json j = EstimateJson(run, p.frame);
      j["id"] = p.id;
      people.push_back(j);
      evaluations += p.frame.evaluations;
      auto [it, fresh] = life.try_emplace(p.id, f.index, f.index);
      it->second.second = f.index;
    }
    list.push_back({{"frame", f.index}, {"time_s", f.time_s}, {"people", people}, {"born", f.born}, {"ended", f.ended}});
  }
  out["frames"] = list;
  json tracks = json::array();
  for (const auto& [id, span] : life) tracks.push_back({{"id", id}, {"first_frame", span.first}, {"last_frame", span.second}});
  const int n = static_cast<int>(frames.size());
  std::vector<const TrackedFrame*> all;
  for (const PeopleFrame& f : frames)
    for (const PersonFrame& p : f.people) all.push_back(&p.frame);
  out["summary"] = {{"frames", n}, {"people", tracks},
                    {"evaluations_per_frame", n ? static_cast<double>(evaluations) / n : 0.0},
                    {"shadow_light", ShadowLightJson(all)},
                    {"foreground_share", ForegroundShareJson(run)}};
  if (mot) {
    out["clear_mot"] = {{"mota", mot->mota}, {"motp_mm", mot->motp_mm}, {"true_person_frames", mot->truth},
                        {"pairs", mot->pairs}, {"misses", mot->misses}, {"false_positives", mot->false_positives},
                        {"id_switches", mot->id_switches}, {"fragmentations", mot->fragmentations},
                        {"true_people", mot->truth_tracks}, {"match_mm", 500}};
  }
  return out;
}

TrackedMotion MakeTrackedMotion(const TrackRun& run, const GaitModel& model) {
  std::vector<double> sizes, legs, arms;
  for (const TrackedFrame& f : run.frames) {
    if (!f.state.size()) continue;
    sizes.push_back(f.size);
    legs.push_back(f.build.lengths.legs);
    arms.push_back(f.build.lengths.arms);
  }
  const double size = Median(sizes);
  TrackedMotion t;
  t.asf = ProportionedAsf(ScaledAsf(model.data().skeleton_asf, model.skeleton().length_scale, size),
                          {Median(legs), Median(arms)});
  t.skeleton = ParseAsf(t.asf, "the tracked skeleton");
  const GaitPoseLayout layout(t.skeleton, "the tracked skeleton");
  const Kinematics kinematics(t.skeleton);
  const int n = static_cast<int>(run.frames.size());
  t.motion.frames_per_second = run.fps;
  t.motion.values = RowMatrixXd::Zero(std::max(n, 1), t.skeleton.NumChannels());
  for (size_t b = 0; b < t.skeleton.bones.size(); ++b)
    if (!t.skeleton.bones[b].dofs.empty()) t.motion.bone_order.push_back(static_cast<int>(b));
  // Each frame's pose turned by its heading, the root where the estimate put it.
  std::vector<int> source(n, -1);
  int last = -1;
  for (int i = 0; i < n; ++i) {
    if (run.frames[i].state.size()) last = i;
    source[i] = last;
  }
  for (int i = n - 1, next = -1; i >= 0; --i) {
    if (run.frames[i].state.size()) next = i;
    if (source[i] < 0) source[i] = next;
  }
  std::vector<double> frame(t.skeleton.NumChannels());
  Eigen::Matrix3Xd at_origin;
  for (int i = 0; i < n; ++i) {
    if (source[i] < 0) continue;
    const TrackedFrame& f = run.frames[source[i]];
    const double heading_deg = f.heading_rad * kDegPerRad;
    // Root translation: the estimate's root, in the scaled skeleton's units, less its rest
    // position.
    const Eigen::Vector3d root = f.joints_mm.col(0) / t.skeleton.MillimetresPerUnit() - t.skeleton.root_position;
    layout.ToFrame(f.pose_deg.data(), heading_deg, root, frame.data());
    t.motion.values.row(i) = Eigen::Map<const Eigen::RowVectorXd>(frame.data(), frame.size());
  }
  return t;
}

namespace {

// The image to draw on: a copy, or grey when there is none.
cv::Mat Canvas(const cv::Mat& image, const Camera& camera) {
  return image.empty() ? cv::Mat(camera.height, camera.width, CV_8UC3, cv::Scalar(60, 60, 60)) : image.clone();
}

// The estimate's outline; with the light of the walkers' shadows found, its shadow's
// outline on the floor too, in the colour at half strength (what the likelihood draws with
// the body: tracker/filter/shadow_light.h).
void DrawOutline(const Camera& camera, const TrackedFrame& frame, const std::vector<Capsule>& capsules,
                 const cv::Scalar& colour, cv::Mat* out) {
  const BitSilhouetteRenderer renderer(camera);
  const auto outline = [&](const BitMask& mask, const cv::Scalar& in) {
    std::vector<std::vector<cv::Point>> contours;
    cv::findContours(mask.ToMat(), contours, cv::RETR_EXTERNAL, cv::CHAIN_APPROX_NONE);
    cv::drawContours(*out, contours, -1, in, 1, cv::LINE_AA);
  };
  if (frame.shadow_light) {
    BitMask shadow(camera.width, camera.height);
    DrawCastShadow(renderer.projector(), capsules, *frame.shadow_light, frame.build.floor_mm,
                   cv::Rect(0, 0, camera.width, camera.height), &shadow);
    outline(shadow, 0.5 * colour);
  }
  BitMask body(camera.width, camera.height);
  renderer.Draw(capsules, &body);
  outline(body, colour);
}

// Text in `colour` over a black edge, readable on any image.
void Label(const std::string& text, cv::Point at, double scale, const cv::Scalar& colour, cv::Mat* out) {
  cv::putText(*out, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 0, 0), 3, cv::LINE_AA);
  cv::putText(*out, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

}  // namespace

cv::Mat OverlayFrame(const cv::Mat& image, const Camera& camera, const TrackedFrame& frame,
                     const std::vector<Capsule>& capsules, const Skeleton& skeleton) {
  cv::Mat out = Canvas(image, camera);
  if (frame.state.size()) {
    DrawOutline(camera, frame, capsules, PersonColour(0), &out);
    DrawSkeleton(skeleton, camera, frame.joints_mm, &out);
  }
  Label(std::to_string(frame.index) + " " + std::string(TrackStatusName(frame.status)), {4, 14}, 0.4,
        cv::Scalar(255, 255, 255), &out);
  return out;
}

cv::Scalar PersonColour(int id) {
  static const cv::Scalar kColours[] = {{0, 255, 255}, {255, 128, 0}, {0, 200, 0}, {255, 0, 255},
                                        {0, 128, 255}, {255, 255, 0}, {128, 0, 255}, {0, 0, 255}};
  return kColours[(id > 0 ? id - 1 : 0) % std::size(kColours)];
}

cv::Mat OverlayPeopleFrame(const cv::Mat& image, const Camera& camera, int index,
                           const std::vector<OverlayPerson>& people, const Skeleton& skeleton) {
  cv::Mat out = Canvas(image, camera);
  int tracked = 0;
  for (const OverlayPerson& p : people) {
    if (p.frame.state.size() == 0 || p.frame.status == TrackStatus::kLost) continue;
    tracked += p.frame.status == TrackStatus::kTracked;
    const cv::Scalar colour = PersonColour(p.id);
    DrawOutline(camera, p.frame, p.capsules, colour, &out);
    DrawSkeleton(skeleton, camera, p.frame.joints_mm, &out);
    // The id over the head (the highest bone end), when it is in front of the camera.
    int top = 0;
    for (int j = 1; j < p.frame.joints_mm.cols(); ++j)
      if (p.frame.joints_mm(1, j) > p.frame.joints_mm(1, top)) top = j;
    Eigen::Vector2d at;
    if (camera.Project(p.frame.joints_mm.col(top) + Eigen::Vector3d(0, 150, 0), &at)) {
      Label(std::to_string(p.id) + (p.frame.status == TrackStatus::kPredicted ? "?" : ""),
            {static_cast<int>(at.x()) - 4, static_cast<int>(at.y())}, 0.5, colour, &out);
    }
  }
  Label(std::to_string(index) + "  " + std::to_string(tracked) + " tracked", {4, 14}, 0.4, cv::Scalar(255, 255, 255),
        &out);
  return out;
}

cv::Mat ErrorPlot(const RunErrors& errors, const TrackRun& run) {
  const TrackErrors& e = errors.gait17;
  const int frames = static_cast<int>(e.distances_mm.rows());
  const struct {
    const char* name;
    cv::Scalar colour;
    std::vector<std::string> joints;
  } groups[] = {
      {"legs", {40, 40, 200}, {"lfemur", "ltibia", "lfoot", "rfemur", "rtibia", "rfoot"}},
      {"arms", {200, 90, 30}, {"lhumerus", "lradius", "lwrist", "rhumerus", "rradius", "rwrist"}},
      {"trunk and head", {30, 140, 30}, {"lowerback", "upperback", "thorax", "upperneck", "head"}},
  };
  const int width = 900, height = 360, left = 60, bottom = 40, top = 40;
  cv::Mat image(height, width, CV_8UC3, cv::Scalar(255, 255, 255));
  std::vector<std::vector<double>> series(3, std::vector<double>(frames, std::nan("")));
  double highest = 50;
  for (int g = 0; g < 3; ++g) {
    std::vector<int> columns;
    for (const std::string& joint : groups[g].joints) {
      const auto it = std::find(e.joints.begin(), e.joints.end(), joint);
      if (it != e.joints.end()) columns.push_back(static_cast<int>(it - e.joints.begin()));
    }
    for (int f = 0; f < frames; ++f) {
      double sum = 0;
      for (int c : columns) sum += e.distances_mm(f, c);
      series[g][f] = columns.empty() ? std::nan("") : sum / columns.size();
      if (std::isfinite(series[g][f])) highest = std::max(highest, series[g][f]);
    }
  }
  highest = std::ceil(highest / 50) * 50;
  const double plot_w = width - left - 20, plot_h = height - top - bottom;
  auto to_pixel = [&](int f, double mm) {
    return cv::Point(left + static_cast<int>(plot_w * f / std::max(1, frames - 1)),
                     top + static_cast<int>(plot_h * (1 - mm / highest)));
  };
  for (double mm = 0; mm <= highest; mm += 50) {
    cv::line(image, to_pixel(0, mm), to_pixel(frames - 1, mm), cv::Scalar(225, 225, 225));
    cv::putText(image, std::to_string(static_cast<int>(mm)), {8, to_pixel(0, mm).y + 4}, cv::FONT_HERSHEY_SIMPLEX, 0.4,
                cv::Scalar(80, 80, 80), 1, cv::LINE_AA);
  }
  for (int g = 0; g < 3; ++g) {
    for (int f = 1; f < frames; ++f) {
      if (std::isfinite(series[g][f - 1]) && std::isfinite(series[g][f])) {
        cv::line(image, to_pixel(f - 1, series[g][f - 1]), to_pixel(f, series[g][f]), groups[g].colour, 2, cv::LINE_AA);
      }
    }
    cv::putText(image, groups[g].name, {left + 10 + 170 * g, height - 12}, cv::FONT_HERSHEY_SIMPLEX, 0.5,
                groups[g].colour, 1, cv::LINE_AA);
  }
  char title[200];
  std::snprintf(title, sizeof(title), "mean 3-D joint error per frame (mm); mean %.1f mm over 17 joints, %d frames at %.0f fps",
                e.absolute_mm, frames, run.fps);
  cv::putText(image, title, {left, 24}, cv::FONT_HERSHEY_SIMPLEX, 0.5, cv::Scalar(0, 0, 0), 1, cv::LINE_AA);
  return image;
}

}  // namespace jgpm
