#include "tracker/run/track_bench.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <memory>

#include <Eigen/Cholesky>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "prior/model/inference.h"
#include "prior/model/model_file.h"
#include "tracker/frames/clip_source.h"
#include "tracker/run/mot_metrics.h"
#include "tracker/run/track_job.h"

namespace jgpm {
namespace fs = std::filesystem;
namespace {

// Accumulates seed runs into one row; `in_view_at`: PersonInView of each clip frame.
void Add(TrackBenchRow* row, const TrackJobResult& r, const GaitModel& model, const ClipGroundTruth& truth,
         const std::vector<bool>& in_view_at) {
  const RunErrors& e = *r.errors;
  row->bt14_mm += e.bodytrack14.absolute_mm;
  row->bt14_root_mm += e.bodytrack14.root_relative_mm;
  row->bt14_procrustes_mm += e.bodytrack14.procrustes_mm;
  row->g17_mm += e.gait17.absolute_mm;
  row->g17_root_mm += e.gait17.root_relative_mm;
  row->g17_procrustes_mm += e.gait17.procrustes_mm;
  row->failure_rate += e.bodytrack14.failure_rate;
  row->swap_rate += e.gait17.swap_rate;
  row->joints = e.gait17.joints;
  row->per_joint_mm.resize(e.gait17.per_joint_mm.size(), 0.0);
  row->per_frame_mm.resize(e.gait17.per_frame_mm.size(), 0.0);
  for (size_t j = 0; j < e.gait17.per_joint_mm.size(); ++j) row->per_joint_mm[j] += e.gait17.per_joint_mm[j];
  for (size_t k = 0; k < e.gait17.per_frame_mm.size() && k < row->per_frame_mm.size(); ++k)
    row->per_frame_mm[k] += e.gait17.per_frame_mm[k];  // NaN stays NaN
  std::vector<Eigen::Matrix3Xd> search, target;
  std::vector<TrackStatus> status;
  std::vector<bool> in_view;
  int lost = 0;
  long evaluations = 0;
  for (const TrackedFrame& f : r.run.frames) {
    search.push_back(f.state.size() ? f.prior_joints_mm : Eigen::Matrix3Xd());
    target.push_back(truth.frames[f.index].joints_mm);
    lost += f.status == TrackStatus::kLost;
    evaluations += f.evaluations;
    status.push_back(f.status);
    in_view.push_back(in_view_at.at(f.index));
  }
  const LostInView lost_in_view = CountLostInView(status, in_view);
  const std::vector<std::string> names = model.skeleton().BoneNames();
  row->search_bt14_mm += CompareTracks(search, names, target, truth.joint_names, Bodytrack14()).absolute_mm;
  row->search_g17_root_mm += CompareTracks(search, names, target, truth.joint_names, Gait17()).root_relative_mm;
  const int n = static_cast<int>(r.run.frames.size());
  row->lost_rate += n ? static_cast<double>(lost) / n : 0;
  row->lost_in_view_rate += n ? static_cast<double>(lost_in_view.frames) / n : 0;
  row->longest_lost_in_view = std::max(row->longest_lost_in_view, lost_in_view.longest);
  row->fps += r.run.tracking_seconds > 0 ? n / r.run.tracking_seconds : 0;
  row->fps_with_input += r.loop_seconds > 0 ? n / r.loop_seconds : 0;
  row->evaluations_per_frame += n ? static_cast<double>(evaluations) / n : 0;
  row->frames = n;
  ++row->seeds;
}

// A --people all run into a crowd row.
void AddPeople(TrackBenchRow* row, const TrackJobResult& r) {
  const MotResult& m = *r.mot;
  if (row->seeds == 0) row->mota = row->motp_mm = 0;  // measured now
  row->walkers = m.truth_tracks;
  row->mota += m.mota;
  row->motp_mm += m.motp_mm;
  row->misses += m.misses;
  row->false_positives += m.false_positives;
  row->id_switches += m.id_switches;
  row->fragmentations += m.fragmentations;
  if (r.matched_bodytrack14) {
    row->bt14_mm += r.matched_bodytrack14->absolute_mm;
    row->bt14_root_mm += r.matched_bodytrack14->root_relative_mm;
    row->bt14_procrustes_mm += r.matched_bodytrack14->procrustes_mm;
  }
  long person_frames = 0, evaluations = 0;
  for (const PeopleFrame& f : r.people) {
    person_frames += static_cast<long>(f.people.size());
    for (const PersonFrame& p : f.people) evaluations += p.frame.evaluations;
  }
  const int n = static_cast<int>(r.people.size());
  row->people_per_frame += n ? static_cast<double>(person_frames) / n : 0;
  row->ms_per_person += person_frames ? 1000 * r.run.tracking_seconds / person_frames : 0;
  row->fps += r.run.tracking_seconds > 0 ? n / r.run.tracking_seconds : 0;
  row->fps_with_input += r.loop_seconds > 0 ? n / r.loop_seconds : 0;
  row->evaluations_per_frame += n ? static_cast<double>(evaluations) / n : 0;
  row->frames = n;
  ++row->seeds;
}

void Average(TrackBenchRow* row) {
  const double k = std::max(1, row->seeds);
  for (double* x : {&row->bt14_mm, &row->bt14_root_mm, &row->bt14_procrustes_mm, &row->g17_mm, &row->g17_root_mm,
                    &row->g17_procrustes_mm, &row->search_bt14_mm, &row->search_g17_root_mm, &row->failure_rate,
                    &row->swap_rate, &row->lost_rate, &row->lost_in_view_rate, &row->fps, &row->fps_with_input, &row->evaluations_per_frame}) {
    *x /= k;
  }
  for (double& x : row->per_joint_mm) x /= k;
  for (double& x : row->per_frame_mm) x /= k;
  if (row->walkers > 0) {
    for (double* x : {&row->mota, &row->motp_mm, &row->misses, &row->false_positives, &row->id_switches,
                      &row->fragmentations, &row->people_per_frame, &row->ms_per_person}) {
      *x /= k;
    }
  }
}

std::string Stem(const std::string& path) { return fs::path(path).stem().string(); }

cv::Scalar Colour(int i) {
  static const cv::Scalar colours[] = {{180, 110, 30}, {40, 40, 200}, {40, 150, 40}, {160, 60, 160},
                                       {30, 150, 220}, {120, 120, 120}, {200, 170, 60}, {90, 60, 30}};
  return colours[i % 8];
}

void Text(cv::Mat& image, const std::string& text, cv::Point at, double scale = 0.42, cv::Scalar colour = {0, 0, 0}) {
  cv::putText(image, text, at, cv::FONT_HERSHEY_SIMPLEX, scale, colour, 1, cv::LINE_AA);
}

}  // namespace

bool PersonInView(const ClipGroundTruth& truth, int frame, const fs::path& clip) {
  const Eigen::Matrix3Xd& joints = truth.frames.at(frame).joints_mm;
  const std::vector<Camera>& cameras = truth.render_cameras.empty() ? truth.cameras : truth.render_cameras;
  for (size_t c = 0; c < cameras.size(); ++c) {
    if (!JointsHalfInView({cameras[c]}, joints)) continue;
    if (clip.empty()) return true;
    const fs::path mask_path = ClipPaths{clip}.Mask(truth.cameras[c].name, frame);
    std::error_code ec;
    if (!fs::exists(mask_path, ec)) return true;
    double top = std::numeric_limits<double>::infinity(), bottom = -top;
    for (int j = 0; j < joints.cols(); ++j) {
      Eigen::Vector2d p;
      if (!cameras[c].Project(joints.col(j), &p)) continue;
      top = std::min(top, p.y());
      bottom = std::max(bottom, p.y());
    }
    const cv::Mat mask = cv::imread(mask_path.string(), cv::IMREAD_GRAYSCALE);
    if (mask.empty()) ThrowInputError(mask_path.string(), "cannot read the exact mask");
    const double height = bottom - top;
    if (cv::countNonZero(mask) >= kShowsArea * height * height) return true;
  }
  return false;
}

double TriangulatedByWrittenCameras(const ClipGroundTruth& truth, int frames) {
  const int n = static_cast<int>(truth.cameras.size());
  if (truth.render_cameras.size() != truth.cameras.size() || n < 2) return -1;
  std::vector<Eigen::Vector3d> centres;
  for (const Camera& camera : truth.cameras) centres.push_back(camera.CentreInWorld());
  std::vector<Eigen::Matrix3Xd> placed, target;
  for (int k = 0; k < frames && k < static_cast<int>(truth.frames.size()); ++k) {
    const Eigen::Matrix3Xd& joints = truth.frames[k].joints_mm;
    Eigen::Matrix3Xd seen = joints;
    for (int j = 0; j < joints.cols(); ++j) {
      // Least squares over the rays: sum_c (I - d d^T) (X - C_c) = 0.
      Eigen::Matrix3d a = Eigen::Matrix3d::Zero();
      Eigen::Vector3d b = Eigen::Vector3d::Zero();
      int rays = 0;
      for (int c = 0; c < n; ++c) {
        Eigen::Vector2d pixel;
        if (!truth.render_cameras[c].Project(joints.col(j), &pixel)) continue;
        const Eigen::Vector3d d = truth.cameras[c].PixelRaysInWorld(pixel).col(0);
        const Eigen::Matrix3d away = Eigen::Matrix3d::Identity() - d * d.transpose();
        a += away;
        b += away * centres[c];
        ++rays;
      }
      if (rays >= 2) seen.col(j) = a.ldlt().solve(b);
    }
    placed.push_back(seen);
    target.push_back(joints);
  }
  return CompareTracks(placed, truth.joint_names, target, truth.joint_names, Bodytrack14()).absolute_mm;
}

LostInView CountLostInView(const std::vector<TrackStatus>& status, const std::vector<bool>& in_view) {
  JGPM_CHECK(status.size() == in_view.size());
  LostInView counted;
  int run = 0;
  for (size_t k = 0; k < status.size(); ++k) {
    const bool lost = status[k] == TrackStatus::kLost && in_view[k];
    run = lost ? run + 1 : 0;
    counted.frames += lost;
    counted.longest = std::max(counted.longest, run);
  }
  return counted;
}

PriorFloors ModelFloors(const GaitModel& model, const ClipGroundTruth& truth, int frames) {
  std::error_code ec;
  if (!fs::exists(truth.source_asf, ec) || !fs::exists(truth.source_amc, ec)) return {};
  const Skeleton skeleton = ReadAsf(truth.source_asf);
  const Motion motion = ReadAmc(truth.source_amc, skeleton);
  const PosePlacer placer(skeleton), model_placer(model.skeleton());
  const GaitPoseLayout& layout = placer.layout();
  if (layout.channel_names() != model.data().set.channel_names) return {};
  PoseObservations observed;
  observed.poses_deg.resize(frames, layout.NumChannels());
  for (int k = 0; k < frames; ++k) {
    const double* frame = motion.Frame(std::min(truth.frames[k].source_frame, motion.NumFrames() - 1));
    Eigen::VectorXd pose(layout.NumChannels());
    layout.FromFrame(frame, HeadingOf(layout.RootRotation(frame)), pose.data());
    observed.poses_deg.row(k) = pose.transpose();
  }
  const InferenceResult best = InferLatentSequence(model, observed);
  std::vector<Eigen::Matrix3Xd> estimate(frames), on_model(frames), target(frames);
  double foot = 0;
  for (int k = 0; k < frames; ++k) {
    const Eigen::VectorXd a = best.poses_deg.row(k).transpose(), b = observed.poses_deg.row(k).transpose();
    placer.Relative(a.data(), &estimate[k], &foot);
    model_placer.Relative(a.data(), &on_model[k], &foot);
    placer.Relative(b.data(), &target[k], &foot);
  }
  const std::vector<std::string> names = skeleton.BoneNames(), model_names = model.skeleton().BoneNames();
  PriorFloors floors;
  floors.subject_bt14 = CompareTracks(estimate, names, target, names, Bodytrack14()).absolute_mm;
  floors.subject_g17 = CompareTracks(estimate, names, target, names, Gait17()).absolute_mm;
  // The best size in the tracker's range (ManifoldDynamics, tracker/state/manifold_state.h), to 0.5%.
  for (int i = 0; i <= 110; ++i) {
    const double size = (150 + i) / 200.0;  // 1 exactly among them
    std::vector<Eigen::Matrix3Xd> scaled = on_model;
    for (Eigen::Matrix3Xd& m : scaled) m *= size;
    const double g17 = CompareTracks(scaled, model_names, target, names, Gait17()).absolute_mm;
    if (floors.model_g17 < 0 || g17 < floors.model_g17) {
      floors.model_g17 = g17;
      floors.model_bt14 = CompareTracks(scaled, model_names, target, names, Bodytrack14()).absolute_mm;
    }
  }
  return floors;
}

std::vector<TrackBenchRow> RunTrackBench(const std::vector<SuiteClip>& clips, const fs::path& folder,
                                         const TrackBenchOptions& options,
                                         const std::function<void(const TrackBenchRow&, int done, int total)>& progress) {
  if (options.models.empty()) ThrowInputError("--model", "give at least one model file");
  std::vector<std::unique_ptr<GaitModel>> models;
  for (const std::string& path : options.models) models.push_back(ReadModelFile(path));
  struct Method {
    int model;
    std::string name;
    StateSpace space;
    bool latent_prior;
    bool known_skeleton = false;
    bool from_video = false;
  };
  std::vector<Method> methods;
  for (size_t m = 0; m < models.size(); ++m) methods.push_back({static_cast<int>(m), "prior", StateSpace::kModel, true});
  if (options.known_skeleton) methods.push_back({0, "known-skeleton", StateSpace::kModel, true, true});
  if (options.no_latent_prior) methods.push_back({0, "no-latent-prior", StateSpace::kModel, false});
  if (options.joint_space) methods.push_back({0, "joint-space", StateSpace::kJointSpace, true});
  if (options.from_video) methods.push_back({0, "from-video", StateSpace::kModel, true, false, true});
  std::vector<Method> crowd_methods;
  for (size_t m = 0; m < models.size(); ++m) crowd_methods.push_back({static_cast<int>(m), "people", StateSpace::kModel, true});
  if (options.from_video) crowd_methods.push_back({0, "people-from-video", StateSpace::kModel, true, false, true});
  std::vector<TrackBenchRow> rows;
  int total = 0;
  for (const SuiteClip& clip : clips) total += static_cast<int>(clip.others.empty() ? methods.size() : crowd_methods.size());
  for (const SuiteClip& clip : clips) {
    const fs::path dir = folder / clip.name;
    const ClipGroundTruth truth = ReadGroundTruth(ClipPaths{dir}.GroundTruth());
    if (!truth.people.empty()) {
      for (const Method& method : crowd_methods) {
        TrackBenchRow row;
        row.clip = clip.name;
        row.model = Stem(options.models[method.model]);
        row.method = method.name;
        row.cameras = static_cast<int>(truth.cameras.size());
        for (int seed = 1; seed <= options.seeds; ++seed) {
          TrackJobOptions job;
          job.model = options.models[method.model];
          job.source.clip = dir.string();
          job.source.max_frames = options.max_frames;
          job.source.clip_foreground = method.from_video;
          job.overlays = false;
          job.people = true;
          job.tracker = options.tracker;
          job.tracker.annealing.seed = static_cast<uint64_t>(seed);
          AddPeople(&row, RunTrackJob(job));
        }
        Average(&row);
        rows.push_back(row);
        if (progress) progress(row, static_cast<int>(rows.size()), total);
      }
      continue;
    }
    const int frames = options.max_frames > 0 ? std::min<int>(options.max_frames, truth.frames.size())
                                              : static_cast<int>(truth.frames.size());
    std::vector<PriorFloors> floors(models.size());
    for (size_t m = 0; m < models.size(); ++m) floors[m] = ModelFloors(*models[m], truth, frames);
    const double triangulated = TriangulatedByWrittenCameras(truth, frames);
    std::vector<bool> in_view;  // the same for every method and seed: each mask read once
    for (int k = 0; k < frames; ++k) in_view.push_back(PersonInView(truth, k, dir));
    for (const Method& method : methods) {
      TrackBenchRow row;
      row.clip = clip.name;
      row.model = Stem(options.models[method.model]);
      row.method = method.name;
      row.cameras = static_cast<int>(truth.cameras.size());
      row.triangulated_bt14_mm = triangulated;
      if (method.space == StateSpace::kModel) {  // the floor on the skeleton tracked on
        const PriorFloors& f = floors[method.model];
        row.floor_bt14_root_mm = method.known_skeleton ? f.subject_bt14 : f.model_bt14;
        row.floor_g17_root_mm = method.known_skeleton ? f.subject_g17 : f.model_g17;
      }
      for (int seed = 1; seed <= options.seeds; ++seed) {
        TrackJobOptions job;
        job.model = options.models[method.model];
        job.source.clip = dir.string();
        job.source.max_frames = frames;
        job.source.clip_foreground = method.from_video;
        job.overlays = false;
        job.tracker = options.tracker;
        job.tracker.space = method.space;
        job.tracker.annealing.latent_prior = method.latent_prior;
        job.tracker.annealing.seed = static_cast<uint64_t>(seed);
        if (method.known_skeleton) {
          // An unreadable ASF is refused by the job, naming it.
          if (truth.source_asf.empty())
            ThrowInputError(ClipPaths{dir}.GroundTruth().string(), "names no source ASF for the known-skeleton run");
          job.asf = truth.source_asf;
        }
        Add(&row, RunTrackJob(job), *models[method.model], truth, in_view);
      }
      Average(&row);
      rows.push_back(row);
      if (progress) progress(row, static_cast<int>(rows.size()), total);
    }
  }
  return rows;
}

std::string TrackBenchCsv(const std::vector<TrackBenchRow>& rows) {
  std::string csv =
      "clip,model,method,cameras,frames,seeds,bt14_mm,bt14_root_mm,bt14_procrustes_mm,g17_mm,g17_root_mm,"
      "g17_procrustes_mm,search_bt14_mm,search_g17_root_mm,floor_bt14_root_mm,floor_g17_root_mm,failure_rate,"
      "swap_rate,lost_rate,fps,fps_with_input,evaluations_per_frame,lost_in_view_rate,longest_lost_in_view,"
      "triangulated_bt14_mm,walkers,mota,motp_mm,misses,false_positives,id_switches,fragmentations,people_per_frame,"
      "ms_per_person\n";
  char line[800];
  for (const TrackBenchRow& r : rows) {
    std::snprintf(line, sizeof(line),
                  "%s,%s,%s,%d,%d,%d,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.2f,%.4f,%.4f,%.4f,%.2f,%.2f,%.1f,%.4f,%d,"
                  "%.2f,%d,%.4f,%.2f,%.2f,%.2f,%.2f,%.2f,%.3f,%.2f\n",
                  r.clip.c_str(), r.model.c_str(), r.method.c_str(), r.cameras, r.frames, r.seeds, r.bt14_mm,
                  r.bt14_root_mm, r.bt14_procrustes_mm, r.g17_mm, r.g17_root_mm, r.g17_procrustes_mm,
                  r.search_bt14_mm, r.search_g17_root_mm, r.floor_bt14_root_mm, r.floor_g17_root_mm, r.failure_rate,
                  r.swap_rate, r.lost_rate, r.fps, r.fps_with_input, r.evaluations_per_frame, r.lost_in_view_rate,
                  r.longest_lost_in_view, r.triangulated_bt14_mm, r.walkers, r.mota, r.motp_mm, r.misses,
                  r.false_positives, r.id_switches, r.fragmentations, r.people_per_frame, r.ms_per_person);
    csv += line;
  }
  return csv;
}

std::string TrackBenchJointsCsv(const std::vector<TrackBenchRow>& rows) {
  std::string csv = "clip,model,method,joint,mm\n";
  char line[256];
  for (const TrackBenchRow& r : rows) {
    for (size_t j = 0; j < r.per_joint_mm.size() && j < r.joints.size(); ++j) {
      std::snprintf(line, sizeof(line), "%s,%s,%s,%s,%.2f\n", r.clip.c_str(), r.model.c_str(), r.method.c_str(),
                    r.joints[j].c_str(), r.per_joint_mm[j]);
      csv += line;
    }
  }
  return csv;
}

std::string TrackBenchFramesCsv(const std::vector<TrackBenchRow>& rows) {
  std::string csv = "clip,model,method,frame,mm\n";
  char line[256];
  for (const TrackBenchRow& r : rows) {
    for (size_t k = 0; k < r.per_frame_mm.size(); ++k) {
      std::snprintf(line, sizeof(line), "%s,%s,%s,%zu,%.2f\n", r.clip.c_str(), r.model.c_str(), r.method.c_str(), k,
                    r.per_frame_mm[k]);
      csv += line;
    }
  }
  return csv;
}

cv::Mat TrackBenchPlot(const std::vector<TrackBenchRow>& rows) {
  std::vector<std::string> clips, series;
  for (const TrackBenchRow& r : rows) {
    if (std::find(clips.begin(), clips.end(), r.clip) == clips.end()) clips.push_back(r.clip);
    const std::string name = r.method == "prior" ? r.model : r.model + " " + r.method;
    if (std::find(series.begin(), series.end(), name) == series.end()) series.push_back(name);
  }
  double top = 50;
  for (const TrackBenchRow& r : rows) top = std::max(top, r.bt14_mm);
  top = std::ceil(top / 50) * 50;
  // A group per clip, wide enough for its bars and its name; the image for the title and
  // the legend.
  const int group = std::max(165, 40 + 16 * static_cast<int>(series.size())), left = 50, height = 420, base = 320;
  const int width = std::max(720, left + group * static_cast<int>(clips.size()) + 20);
  cv::Mat image(height + 20 * static_cast<int>((series.size() + 2) / 3), width, CV_8UC3, cv::Scalar(255, 255, 255));
  Text(image, "Mean 3-D error of 14 joints (mm) per clip: lower is better", {left, 20}, 0.5);
  for (double mm = 0; mm <= top; mm += 50) {
    const int y = base - static_cast<int>(250 * mm / top);
    cv::line(image, {left, y}, {image.cols - 10, y}, cv::Scalar(225, 225, 225));
    Text(image, std::to_string(static_cast<int>(mm)), {8, y + 4});
  }
  for (const TrackBenchRow& r : rows) {
    const int c = static_cast<int>(std::find(clips.begin(), clips.end(), r.clip) - clips.begin());
    const std::string name = r.method == "prior" ? r.model : r.model + " " + r.method;
    const int s = static_cast<int>(std::find(series.begin(), series.end(), name) - series.begin());
    const int x = left + c * group + 20 + 16 * s, y = base - static_cast<int>(250 * r.bt14_mm / top);
    cv::rectangle(image, {x, y}, {x + 13, base}, Colour(s), cv::FILLED);
    if (r.floor_bt14_root_mm > 0) {  // the floor as a black tick
      const int fy = base - static_cast<int>(250 * r.floor_bt14_root_mm / top);
      cv::line(image, {x - 1, fy}, {x + 14, fy}, cv::Scalar(0, 0, 0), 2);
    }
  }
  for (size_t c = 0; c < clips.size(); ++c) Text(image, clips[c], {left + static_cast<int>(c) * group + 10, base + 18}, 0.38);
  for (size_t s = 0; s < series.size(); ++s) {
    const cv::Point at(left + 230 * static_cast<int>(s % 3), base + 50 + 20 * static_cast<int>(s / 3));
    cv::rectangle(image, {at.x, at.y - 10}, {at.x + 12, at.y + 2}, Colour(static_cast<int>(s)), cv::FILLED);
    Text(image, series[s], {at.x + 18, at.y});
  }
  const int legend_rows = static_cast<int>((series.size() + 2) / 3);
  Text(image, "black tick: the model's floor (its best poses for the true ones, root-relative)",
       {left, base + 50 + 20 * legend_rows + 8}, 0.4);
  return image;
}

std::vector<BudgetPoint> RunBudgetCurve(const fs::path& clip, const std::string& model,
                                        const std::vector<std::pair<int, int>>& budgets,
                                        const TrackBenchOptions& options) {
  std::vector<BudgetPoint> points;
  for (const auto& [particles, layers] : budgets) {
    BudgetPoint p{particles, layers, 0, 0};
    for (int seed = 1; seed <= options.seeds; ++seed) {
      TrackJobOptions job;
      job.model = model;
      job.source.clip = clip.string();
      job.source.max_frames = options.max_frames;
      job.overlays = false;
      job.tracker = options.tracker;
      job.tracker.annealing.particles = particles;
      job.tracker.annealing.layers = layers;
      job.tracker.annealing.seed = static_cast<uint64_t>(seed);
      const TrackJobResult r = RunTrackJob(job);
      p.bt14_mm += r.errors->bodytrack14.absolute_mm / options.seeds;
      p.fps += r.run.frames.size() / std::max(1e-9, r.run.tracking_seconds) / options.seeds;
    }
    points.push_back(p);
  }
  return points;
}

cv::Mat BudgetPlot(const std::vector<BudgetPoint>& points, const std::string& clip) {
  // PARSEC bodytrack on the same clip (../shared/docs/TRACKER.md): frames/s, mm.
  const struct {
    const char* label;
    double fps, mm;
  } peer[] = {{"4000x5", 3.3, 41.5}, {"1000x5", 12.7, 52.8}, {"500x5", 21, 56.5}, {"250x5", 43, 71.8}, {"100x3", 95, 93.8}};
  const int width = 760, height = 440, left = 60, bottom = 60, top_margin = 40, legend = 36;
  cv::Mat image(height + legend, width, CV_8UC3, cv::Scalar(255, 255, 255));  // legend under the axis
  double max_mm = 100, max_fps = 100;
  for (const BudgetPoint& p : points) max_mm = std::max(max_mm, p.bt14_mm), max_fps = std::max(max_fps, p.fps);
  max_mm = std::ceil(max_mm / 25) * 25;
  const double log_lo = std::log10(2.0), log_hi = std::log10(max_fps * 1.3);
  auto to_pixel = [&](double fps, double mm) {
    const double fx = (std::log10(std::max(fps, 2.0)) - log_lo) / (log_hi - log_lo);
    return cv::Point(left + static_cast<int>(fx * (width - left - 30)),
                     top_margin + static_cast<int>((1 - mm / max_mm) * (height - top_margin - bottom)));
  };
  for (double mm = 0; mm <= max_mm; mm += 25) {
    cv::line(image, to_pixel(2, mm), to_pixel(max_fps * 1.3, mm), cv::Scalar(228, 228, 228));
    Text(image, std::to_string(static_cast<int>(mm)), {10, to_pixel(2, mm).y + 4});
  }
  for (double fps : {3.0, 10.0, 30.0, 100.0, 300.0, 1000.0}) {
    if (fps > max_fps * 1.3) break;
    const cv::Point at = to_pixel(fps, 0);
    cv::line(image, {at.x, top_margin}, {at.x, at.y}, cv::Scalar(228, 228, 228));
    Text(image, std::to_string(static_cast<int>(fps)), {at.x - 8, at.y + 18});
  }
  Text(image, "frames per second (2 cores)", {width / 2 - 90, height - 18});
  Text(image, "Accuracy against speed on " + clip + ": mean 3-D error of 14 joints (mm)", {left, 24}, 0.5);
  for (size_t i = 0; i + 1 < std::size(peer); ++i) {
    cv::line(image, to_pixel(peer[i].fps, peer[i].mm), to_pixel(peer[i + 1].fps, peer[i + 1].mm), cv::Scalar(60, 60, 200), 1,
             cv::LINE_AA);
  }
  for (const auto& p : peer) {
    cv::circle(image, to_pixel(p.fps, p.mm), 4, cv::Scalar(60, 60, 200), cv::FILLED, cv::LINE_AA);
    Text(image, p.label, to_pixel(p.fps, p.mm) + cv::Point(6, -6), 0.35, cv::Scalar(60, 60, 200));
  }
  for (size_t i = 0; i < points.size(); ++i) {
    if (i + 1 < points.size()) {
      cv::line(image, to_pixel(points[i].fps, points[i].bt14_mm), to_pixel(points[i + 1].fps, points[i + 1].bt14_mm),
               cv::Scalar(180, 110, 30), 2, cv::LINE_AA);
    }
    cv::circle(image, to_pixel(points[i].fps, points[i].bt14_mm), 5, cv::Scalar(180, 110, 30), cv::FILLED, cv::LINE_AA);
    Text(image, std::to_string(points[i].particles) + "x" + std::to_string(points[i].layers),
         to_pixel(points[i].fps, points[i].bt14_mm) + cv::Point(6, 14), 0.35, cv::Scalar(180, 110, 30));
  }
  Text(image, "jgpm, automatic start (blue)", {left, height + 12}, 0.45, cv::Scalar(180, 110, 30));
  Text(image, "PARSEC bodytrack, started from the truth (red, ../shared/docs/TRACKER.md)", {left, height + 30}, 0.45,
       cv::Scalar(60, 60, 200));
  return image;
}

}  // namespace jgpm
