// `import jgpm`: the library's motions, priors and cameras for Python, NumPy arrays in and
// out. The C++ stays the implementation; these are thin bindings. A C++ InputError is a
// Python jgpm.InputError (a ValueError) with the same one-line message; arrays of the
// wrong shape or dtype are refused with a TypeError naming the argument and the shape
// expected; long calls release the GIL. Stubs: jgpm.pyi beside the module.
#include <atomic>
#include <cmath>
#include <filesystem>
#include <thread>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "calibration/camera.h"
#include "calibration/cli/calibration_commands.h"
#include "io/base/error.h"
#include "io/mocap/amc.h"
#include "io/mocap/asf.h"
#include "io/mocap/bvh.h"
#include "io/mocap/bvh_conversion.h"
#include "io/mocap/kinematics.h"
#include "io/mocap/motion_file.h"
#include "prior/model/gait_model.h"
#include "prior/model/model_file.h"
#include "io/gait/data_root.h"
#include "io/gait/gait_dataset.h"
#include "io/gait/split.h"
#include "prior/model/inference.h"
#include "prior/model/model_kind.h"
#include "prior/model/train.h"
#include "prior/numerics/blas_threads.h"
#include "tracker/filter/multi_tracker.h"
#include "tracker/filter/tracker.h"
#include "tracker/run/pose_table_cache.h"
#include "tracker/cli/walker_video.h"
#include "tracker/run/track_job.h"

namespace py = pybind11;
namespace fs = std::filesystem;

namespace jgpm {
namespace {

using RowMatrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
// A C-contiguous float64 array; other dtypes are converted (int, float32), anything that
// is not a number refused.
using Array = py::array_t<double, py::array::c_style | py::array::forcecast>;

// `a` as rows x `cols` (a single point of `cols` values is one row). TypeError naming
// `what` otherwise.
Eigen::Map<const RowMatrix> Rows(const Array& a, int cols, const char* what) {
  const bool one = a.ndim() == 1 && a.shape(0) == cols;
  if (!one && !(a.ndim() == 2 && a.shape(1) == cols)) {
    std::string shape;
    for (py::ssize_t d = 0; d < a.ndim(); ++d) shape += (d ? " x " : "") + std::to_string(a.shape(d));
    throw py::type_error(std::string(what) + ": expected an array of shape (M, " + std::to_string(cols) + ") or (" +
                         std::to_string(cols) + ",), got (" + shape + ")");
  }
  const Eigen::Index rows = one ? 1 : a.shape(0);
  for (Eigen::Index i = 0; i < rows * cols; ++i) {
    if (!std::isfinite(a.data()[i])) throw py::value_error(std::string(what) + ": holds a NaN or infinite value");
  }
  return Eigen::Map<const RowMatrix>(a.data(), rows, cols);
}

// A motion as read: an Acclaim skeleton and its frames, or a BVH file's own hierarchy.
struct PyMotion {
  std::optional<Skeleton> skeleton;  // Acclaim
  Motion motion;
  std::optional<Bvh> bvh;  // BVH read without a skeleton

  int NumFrames() const { return bvh ? static_cast<int>(bvh->frames.rows()) : motion.NumFrames(); }
  double Fps() const { return bvh ? 1.0 / bvh->frame_time : motion.frames_per_second; }
  std::vector<std::string> JointNames() const {
    if (!bvh) return skeleton->BoneNames();
    std::vector<std::string> names;
    for (const BvhJoint& j : bvh->joints) {
      names.push_back(j.end_site ? bvh->joints[j.parent].name + "_end" : j.name);
    }
    return names;
  }
  // frames x joints x 3, mm.
  py::array_t<double> JointPositions() const {
    const int frames = NumFrames();
    const size_t joints = JointNames().size();
    py::array_t<double> out({static_cast<py::ssize_t>(frames), static_cast<py::ssize_t>(joints), py::ssize_t{3}});
    double* data = out.mutable_data();
    {
      py::gil_scoped_release release;
      Eigen::Matrix3Xd at;
      const std::optional<Kinematics> kinematics = skeleton ? std::optional<Kinematics>(*skeleton) : std::nullopt;
      for (int f = 0; f < frames; ++f) {
        if (bvh) {
          ComputeBvhPose(*bvh, f, &at);
        } else {
          kinematics->Compute(motion.Frame(f), &at);
        }
        std::copy(at.data(), at.data() + 3 * joints, data + static_cast<size_t>(f) * joints * 3);
      }
    }
    return out;
  }
};

PyMotion ReadMotion(const fs::path& path, const std::optional<fs::path>& asf, double amc_fps, double bvh_mm_per_unit) {
  MotionFileOptions options;
  options.asf = asf;
  options.amc_frames_per_second = amc_fps;
  options.bvh_mm_per_unit = bvh_mm_per_unit;
  PyMotion m;
  switch (FormatFromPath(path, "read_motion")) {
    case MotionFormat::kAsf:
      m.skeleton = ReadAsf(path);
      m.motion.values.resize(0, m.skeleton->NumChannels());
      break;
    case MotionFormat::kAmc:
      m.skeleton = ReadAsf(SkeletonForAmc(path, options));
      m.motion = ReadAmc(path, *m.skeleton);
      m.motion.frames_per_second = amc_fps;
      break;
    case MotionFormat::kBvh: {
      Bvh bvh = ReadBvh(path, bvh_mm_per_unit);
      if (asf) {
        m.skeleton = ReadAsf(*asf);
        m.motion = BvhToAcclaim(bvh, *m.skeleton, path.string());
        m.motion.frames_per_second = 1.0 / bvh.frame_time;
      } else {
        m.bvh = std::move(bvh);
      }
      break;
    }
  }
  return m;
}

// Model calls over batches of latent points (M x 3), the GIL released.
struct PyModel {
  std::shared_ptr<const GaitModel> model;
  fs::path path;  // the file it was read from (its pose table is kept beside it)

  py::array_t<double> MeanPose(const Array& latent) const {
    const Eigen::Map<const RowMatrix> xs = Rows(latent, 3, "latent");
    const Eigen::MatrixXd x = xs;  // the batch call takes T x 3 column-major
    RowMatrix poses(x.rows(), model->NumChannels());
    {
      py::gil_scoped_release release;
      Eigen::MatrixXd out(x.rows(), model->NumChannels());
      ModelWorkspace workspace;
      model->MeanPoses(x, out, &workspace);
      poses = out;
    }
    return Out(poses, latent.ndim() == 1);
  }
  py::object LogDensity(const Array& latent, bool gradient) const {
    const Eigen::Map<const RowMatrix> xs = Rows(latent, 3, "latent");
    Eigen::VectorXd values(xs.rows());
    RowMatrix gradients(xs.rows(), 3);
    {
      py::gil_scoped_release release;
      for (Eigen::Index i = 0; i < xs.rows(); ++i) {
        Eigen::Vector3d g;
        values(i) = model->LogDensity(xs.row(i).transpose(), gradient ? &g : nullptr);
        if (gradient) gradients.row(i) = g.transpose();
      }
    }
    const bool one = latent.ndim() == 1;
    py::object v = one ? py::object(py::float_(values(0))) : py::object(py::array_t<double>(values.size(), values.data()));
    if (!gradient) return v;
    return py::make_tuple(v, Out(gradients, one));
  }
  py::array_t<double> NextLatent(const Array& latent) const {
    const Eigen::Map<const RowMatrix> xs = Rows(latent, 3, "latent");
    const Eigen::MatrixXd x = xs;
    RowMatrix next(x.rows(), 3);
    {
      py::gil_scoped_release release;
      Eigen::MatrixXd out(x.rows(), 3);
      ModelWorkspace workspace;
      model->NextLatents(x, out, &workspace);
      next = out;
    }
    return Out(next, latent.ndim() == 1);
  }
  py::array_t<double> JointPositions(const Array& pose) const {
    const Eigen::Map<const RowMatrix> poses = Rows(pose, model->NumChannels(), "pose");
    std::vector<double> joints_mm;
    Eigen::Index joints = 0;
    {
      py::gil_scoped_release release;
      Eigen::Matrix3Xd at;
      for (Eigen::Index i = 0; i < poses.rows(); ++i) {
        model->JointPositions(poses.row(i).transpose(), &at);
        joints = at.cols();
        joints_mm.insert(joints_mm.end(), at.data(), at.data() + at.size());
      }
    }
    if (pose.ndim() == 1) return py::array_t<double>({joints, Eigen::Index{3}}, joints_mm.data());
    return py::array_t<double>({poses.rows(), joints, Eigen::Index{3}}, joints_mm.data());
  }
  void RequireManifold() const {
    if (!model->HasManifold()) {
      throw InputError(std::string(ModelKindName(model->kind())) + " model: no gait manifold (JGPM family only)");
    }
  }

  static py::array_t<double> Out(const RowMatrix& m, bool one) {
    if (one) return py::array_t<double>(m.cols(), m.data());
    return py::array_t<double>({m.rows(), m.cols()}, m.data());
  }
};

py::array_t<double> Project(const Camera& camera, const Array& points) {
  const Eigen::Map<const RowMatrix> p = Rows(points, 3, "points");
  RowMatrix pixels(p.rows(), 2);
  for (Eigen::Index i = 0; i < p.rows(); ++i) {
    Eigen::Vector2d q;
    if (camera.Project(p.row(i).transpose(), &q)) {
      pixels(i, 0) = q.x();  // not row(i) = q: GCC 12 warns on the vectorised copy
      pixels(i, 1) = q.y();
    } else {
      pixels.row(i).setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }
  return PyModel::Out(pixels, points.ndim() == 1);
}

// A tracked frame as Python sees it (poses.json's fields).
py::dict EstimateDict(const TrackedFrame& f) {
  py::dict d;
  d["frame"] = f.index;
  d["time_s"] = f.time_s;
  d["status"] = std::string(TrackStatusName(f.status));
  d["ess"] = f.ess;
  d["seconds"] = f.seconds;
  if (f.state.size() == 0) {
    d["joints_mm"] = py::none();
    return d;
  }
  const RowMatrix joints = f.joints_mm.transpose();
  d["joints_mm"] = py::array_t<double>({joints.rows(), joints.cols()}, joints.data());
  d["root_mm"] = py::array_t<double>(3, Eigen::Vector3d(f.joints_mm.col(0)).data());
  d["heading_deg"] = f.heading_rad * 180 / std::numbers::pi;
  d["size"] = f.size;
  d["pose_deg"] = py::array_t<double>(f.pose_deg.size(), f.pose_deg.data());
  return d;
}

// A frame of several people as Python sees it (poses.json's with --people all): each
// person an estimate with its id.
py::dict PeopleDict(const PeopleFrame& f) {
  py::list everyone;
  for (const PersonFrame& p : f.people) {
    py::dict d = EstimateDict(p.frame);
    d["id"] = p.id;
    everyone.append(d);
  }
  py::list earlier;  // estimates of frames already returned, new or in place of the person's there
  for (const auto& [index, p] : f.earlier) {
    py::dict d = EstimateDict(p.frame);
    d["id"] = p.id;
    earlier.append(d);
  }
  return py::dict(py::arg("frame") = f.index, py::arg("time_s") = f.time_s, py::arg("people") = everyone,
                  py::arg("born") = f.born, py::arg("ended") = f.ended, py::arg("earlier") = earlier);
}

// The tracker fed one frame of masks at a time (from any segmenter). Its start looks at the
// first start_frames frames together (the person's place, height and heading, or everyone
// in view), so those are returned together once they are all in; after that each step
// returns its frame. people='all': a MultiTracker, each frame as PeopleDict.
struct PyTracker {
  std::shared_ptr<const GaitModel> model;
  std::vector<Camera> cameras;
  std::unique_ptr<Tracker> tracker;      // people='one'
  std::unique_ptr<MultiTracker> multi;   // people='all'
  double fps = 30;
  int start_frames = 0;
  std::vector<Frame> first;  // held for the start
  std::optional<StartBackOver> hold;  // people='one': a start's frames until gone back over
  bool started = false;
  int next = 0;

  PyTracker(const PyModel& m, std::vector<Camera> cams, uint64_t seed, int particles, int layers, int threads,
            double frames_per_second, const std::string& people, int max_people)
      : model(m.model), cameras(std::move(cams)), fps(frames_per_second) {
    if (cameras.empty()) throw InputError("Tracker: give at least one camera");
    if (!(fps > 0)) throw InputError("Tracker: fps must be positive");
    if (people != "one" && people != "all") ThrowInputError("people='" + people + "'", "expected 'one' or 'all'");
    TrackerOptions options;
    options.annealing.seed = seed;
    options.annealing.particles = particles;
    options.annealing.layers = layers;
    options.threads = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
    py::gil_scoped_release release;
    PoseTableOptions table_options = options.table;
    table_options.threads = options.threads;
    const std::shared_ptr<const PoseTable> table =
        CachedPoseTable(*model, m.path.string(), "", table_options, nullptr);
    start_frames = options.start_frames;
    if (people == "all") {
      MultiTrackerOptions everyone;
      everyone.max_people = max_people;
      multi = std::make_unique<MultiTracker>(*model, cameras, options, everyone, table);
    } else {
      tracker = std::make_unique<Tracker>(*model, cameras, options, table);
      hold.emplace(tracker.get());
    }
  }

  // One frame: a mask per camera (H x W, any number type or bool; nonzero is the person),
  // or None when the frame was not seen (predicted).
  py::list Step(const std::optional<std::vector<py::array>>& masks) {
    Frame frame;
    frame.index = next++;
    frame.time_s = frame.index / fps;
    if (!masks) {
      frame.dropped = true;
    } else {
      if (masks->size() != cameras.size()) {
        throw py::type_error("masks: expected one per camera (" + std::to_string(cameras.size()) + "), got " +
                             std::to_string(masks->size()));
      }
      for (size_t c = 0; c < cameras.size(); ++c) {
        const py::array_t<uint8_t, py::array::c_style | py::array::forcecast> mask((*masks)[c].attr("astype")("bool"));
        if (mask.ndim() != 2 || mask.shape(0) != cameras[c].height || mask.shape(1) != cameras[c].width) {
          throw py::type_error("masks[" + std::to_string(c) + "]: expected " + std::to_string(cameras[c].height) + " x " +
                               std::to_string(cameras[c].width) + " (camera " + cameras[c].name + "'s image)");
        }
        cv::Mat m(cameras[c].height, cameras[c].width, CV_8UC1);
        for (py::ssize_t i = 0; i < mask.size(); ++i) m.data[i] = mask.data()[i] ? 255 : 0;
        frame.masks.push_back(m);
      }
    }
    py::list out;
    if (!started) {
      first.push_back(std::move(frame));
      if (static_cast<int>(first.size()) < start_frames) return out;
      return Start();
    }
    if (multi) {
      PeopleFrame f;
      {
        py::gil_scoped_release release;
        f = multi->Step(frame);
      }
      out.append(PeopleDict(f));
    } else {
      std::vector<StartBackOver::Estimate> ready;
      {
        py::gil_scoped_release release;
        hold->Add(frame, tracker->Step(frame), &ready);
      }
      for (const StartBackOver::Estimate& e : ready) out.append(EstimateDict(e.estimate));
    }
    return out;
  }
  // The frames still held: for the start (a sequence shorter than start_frames), tracked;
  // a start's not gone back over yet (shorter than start_backwards_s after it), as they are.
  py::list Finish() {
    py::list out = started || first.empty() ? py::list() : Start();
    if (hold) {
      std::vector<StartBackOver::Estimate> ready;
      hold->Flush(&ready);
      for (const StartBackOver::Estimate& e : ready) out.append(EstimateDict(e.estimate));
    }
    return out;
  }

  py::list Start() {
    started = true;
    std::vector<StartBackOver::Estimate> tracked;
    std::vector<PeopleFrame> everyone;
    {
      py::gil_scoped_release release;
      if (multi) {
        multi->Start(first);
        for (const Frame& f : first) {
          everyone.push_back(multi->Step(f));
          PlaceEarlier(&everyone);  // these frames are returned together
          everyone.back().earlier.clear();
        }
      } else {
        tracker->StartFromFrames(first);
        for (const Frame& f : first) hold->Add(f, tracker->Step(f), &tracked);
      }
    }
    first.clear();
    py::list out;
    for (const StartBackOver::Estimate& e : tracked) out.append(EstimateDict(e.estimate));
    for (const PeopleFrame& f : everyone) out.append(PeopleDict(f));
    return out;
  }
};

// `jgpm train` as a call: the gait cycles of a prepared dataset (jgpm data cycles' JSON) or
// of a split of the data root. `progress` (optional) is called with each progress report
// as a dict; an exception it raises stops training and is raised here.
PyModel Train(const std::string& kind, const std::optional<fs::path>& cycles, const std::optional<std::string>& data,
              const std::string& split, const std::string& learning, int max_iterations, uint64_t seed,
              const py::object& progress) {
  TrainingOptions options;
  if (!ParseModelKind(kind, &options.kind)) throw InputError("train: kind '" + kind + "', expected one of " + ModelKindList());
  if (!ParseLearning(learning, &options.learning)) {
    throw InputError("train: learning '" + learning + "', expected full, local or sparse");
  }
  options.seed = seed;
  // As `jgpm train` (its --threads 0): the same model to the last bit, whatever this
  // process's OpenBLAS count is.
  options.threads = ThreadsOrAllCores(0);
  if (max_iterations > 0) {
    options.full.max_iterations = max_iterations;
    options.local.max_steps = max_iterations;
  }
  std::atomic<bool> stop{false};
  std::optional<py::error_already_set> raised;
  if (!progress.is_none()) {
    options.budget.interrupted = &stop;
    options.progress = [&](const TrainingProgress& p) {
      py::gil_scoped_acquire acquire;
      if (raised) return;
      try {
        progress(py::dict(py::arg("stage") = p.stage, py::arg("iteration") = p.iteration,
                          py::arg("objective") = p.objective, py::arg("jitter") = p.jitter,
                          py::arg("elapsed_seconds") = p.elapsed_seconds, py::arg("rate") = p.rate));
      } catch (py::error_already_set& e) {
        raised = std::move(e);
        stop = true;
      }
    };
  }
  std::unique_ptr<GaitModel> model;
  {
    py::gil_scoped_release release;
    GaitDataset dataset;
    fs::path root;
    if (cycles) {
      dataset = ReadGaitDataset(*cycles);
      root = data ? ResolveDataRoot(data) : fs::path(dataset.data_root);
    } else {
      root = ResolveDataRoot(data);
      dataset = PrepareGaitDataset(root, split, ReadSplit(ResolveSplitPath(split, JGPM_SPLITS_DIR)), GaitCycleOptions{});
    }
    model = TrainGaitModel(dataset, ChooseReferenceSkeleton(dataset, root), options);
  }
  if (raised) throw std::move(*raised);
  return PyModel{std::move(model), {}};
}

// `jgpm track --video ...` as a call: the command's whole job (background learnt unless
// given, working resolution, overlays when `out` is given).
py::dict TrackVideo(const fs::path& model, const std::vector<std::string>& videos, const std::vector<std::string>& cameras,
                    const std::optional<std::string>& out, const std::vector<std::string>& backgrounds, uint64_t seed,
                    int threads, const std::string& people, const std::vector<std::string>& occluders) {
  if (people != "one" && people != "all") ThrowInputError("people='" + people + "'", "expected 'one' or 'all'");
  TrackJobOptions o;
  o.people = people == "all";
  o.model = model.string();
  o.source.videos = videos;
  o.source.camera_yamls = cameras;
  o.source.backgrounds = backgrounds;
  o.source.occluders = occluders;
  if (out) o.out = *out;
  o.tracker.annealing.seed = seed;
  o.tracker.threads = threads > 0 ? threads : std::max(1u, std::thread::hardware_concurrency());
  TrackJobResult result;
  {
    py::gil_scoped_release release;
    result = RunTrackJob(o);
  }
  py::list frames;
  for (const TrackedFrame& f : result.run.frames) frames.append(EstimateDict(f));
  for (const PeopleFrame& f : result.people) frames.append(PeopleDict(f));  // people='all
  py::list written;
  for (const fs::path& p : result.written) written.append(p.string());
  py::object light = py::none();  // poses.json's summary's shadow_light
  if (result.shadow_light_deg)
    light = py::dict(py::arg("azimuth_deg") = result.shadow_light_deg->x(),
                     py::arg("elevation_deg") = result.shadow_light_deg->y(),
                     py::arg("found_at_frame") = result.shadow_light_frame);
  py::dict shares;  // poses.json's summary's foreground_share
  for (size_t c = 0; c < result.run.foreground_share.size(); ++c)
    shares[py::str(result.run.cameras[c].name)] = result.run.foreground_share[c];
  return py::dict(py::arg("frames") = frames, py::arg("tracking_seconds") = result.run.tracking_seconds,
                  py::arg("wall_seconds") = result.wall_seconds, py::arg("written") = written,
                  py::arg("shadow_light") = light, py::arg("foreground_share") = shares);
}

}  // namespace
}  // namespace jgpm

PYBIND11_MODULE(jgpm, m) {
  using namespace jgpm;
  m.doc() = "jgpm: gait priors (ML-JGPM and the models it is compared with), cameras and motion files; "
            "arrays are NumPy, lengths millimetres, angles degrees.";
  m.attr("__version__") = JGPM_VERSION;
  py::register_exception<InputError>(m, "InputError", PyExc_ValueError);

  py::class_<PyMotion>(m, "Motion", "A motion read from ASF/AMC or BVH.")
      .def_property_readonly("num_frames", &PyMotion::NumFrames)
      .def_property_readonly("frames_per_second", &PyMotion::Fps)
      .def_property_readonly("joint_names", &PyMotion::JointNames,
                             "Names of joint_positions()' joints: the Acclaim bones' ends (root first), or the BVH "
                             "joints (End Sites as PARENT_end).")
      .def_property_readonly(
          "values",
          [](py::object owner) {
            const PyMotion& self = owner.cast<const PyMotion&>();
            const RowMatrixXd& v = self.bvh ? self.bvh->frames : self.motion.values;
            py::array_t<double> view({v.rows(), v.cols()}, v.data(), owner);  // no copy; keeps the motion alive
            view.attr("setflags")(py::arg("write") = false);
            return view;
          },
          "frames x channels, read-only view: rotations in degrees, the root's translation in the file's units.")
      .def("joint_positions", &PyMotion::JointPositions, "frames x joints x 3, millimetres (world, y up).")
      .def(
          "write_bvh",
          [](const PyMotion& self, const fs::path& path) {
            WriteBvh(path, self.bvh ? *self.bvh : AcclaimToBvh(*self.skeleton, self.motion));
          },
          py::arg("path"), "Writes BVH (centimetres).")
      .def(
          "write_amc",
          [](const PyMotion& self, const fs::path& path) {
            if (!self.skeleton) {
              throw InputError(path.string() + ": a BVH motion read without asf= has no Acclaim skeleton to write AMC for");
            }
            WriteAmc(path, self.motion, *self.skeleton);
          },
          py::arg("path"), "Writes AMC for the motion's Acclaim skeleton.");

  m.def("read_motion", &ReadMotion, py::arg("path"), py::arg("asf") = std::nullopt, py::arg("amc_fps") = 120.0,
        py::arg("bvh_mm_per_unit") = 10.0,
        "Reads an ASF (no frames), AMC (its skeleton: asf=, else NN.asf beside it) or BVH file (with asf=, "
        "converted to that Acclaim skeleton). jgpm.InputError naming the file and line on a malformed one.");

  py::class_<PyModel>(m, "Model", "A trained gait prior (jgpm train's JSON).")
      .def_property_readonly("kind", [](const PyModel& self) { return std::string(ModelKindName(self.model->kind())); })
      .def_property_readonly("num_channels", [](const PyModel& self) { return self.model->NumChannels(); })
      .def_property_readonly("channel_names", [](const PyModel& self) { return self.model->data().set.channel_names; })
      .def_property_readonly("latent", [](const PyModel& self) { return RowMatrix(self.model->latent()); },
                             "The training poses' latent points, N x 3.")
      .def(
          "save", [](const PyModel& self, const fs::path& path) { WriteModelFile(path, *self.model); }, py::arg("path"),
          "Writes the model file (as jgpm train does).")
      .def_property_readonly("has_dynamics", [](const PyModel& self) { return self.model->HasDynamics(); })
      .def_property_readonly("has_manifold", [](const PyModel& self) { return self.model->HasManifold(); })
      .def("mean_pose", &PyModel::MeanPose, py::arg("latent"),
           "Mean poses (degrees, num_channels each) at latent points: (M, 3) -> (M, D), (3,) -> (D,).")
      .def("log_density", &PyModel::LogDensity, py::arg("latent"), py::arg("gradient") = false,
           "ln of the latent density up to a constant at latent points ((M, 3) -> (M,)); with gradient=True, also "
           "its gradient ((M, 3)).")
      .def("next_latent", &PyModel::NextLatent, py::arg("latent"),
           "The mean next latent point along the dynamics (GPDM family; others: the point itself).")
      .def("joint_positions", &PyModel::JointPositions, py::arg("pose"),
           "Joint positions (mm) of poses on the model's skeleton: (M, D) -> (M, joints, 3), (D,) -> (joints, 3).")
      .def(
          "manifold_to_latent",
          [](const PyModel& self, double phase, double gait, double scale) {
            self.RequireManifold();
            return Eigen::Vector3d(self.model->ManifoldToLatent({phase, gait, scale}));
          },
          py::arg("phase"), py::arg("gait"), py::arg("scale"),
          "JGPM family: the latent point of a manifold point (phase in [0, 1), gait, stride scale).")
      .def(
          "latent_to_manifold",
          [](const PyModel& self, const Array& latent) {
            self.RequireManifold();
            const Eigen::Map<const RowMatrix> x = Rows(latent, 3, "latent");
            if (x.rows() != 1) throw py::type_error("latent: expected one point, shape (3,)");
            const ManifoldPoint p = self.model->LatentToManifold(x.row(0).transpose());
            return py::make_tuple(p.phase, p.gait, p.scale);
          },
          py::arg("latent"), "JGPM family: (phase, gait, scale) of the manifold point nearest a latent point.");

  m.def("train", &Train, py::arg("kind"), py::arg("cycles") = std::nullopt, py::arg("data") = std::nullopt,
        py::arg("split") = "train", py::arg("learning") = "full", py::arg("max_iterations") = 0, py::arg("seed") = 1,
        py::arg("progress") = py::none(),
        "Trains a prior as `jgpm train` does: kind (pca, gplvm, gpdm, bgpdm, llgpdm, jgpm, mljgpm-torus, "
        "mljgpm-cyl) on the gait cycles of cycles= (jgpm data cycles' JSON) or of split= of the data root (data=, "
        "else $JGPM_DATA or ../shared/data/cmu); progress(dict) is called as it goes (stage, iteration, objective, "
        "jitter, elapsed_seconds, rate) and may raise to stop it.");
  m.def(
      "infer",
      [](const PyModel& self, const Array& poses, std::optional<std::vector<bool>> observed, bool adapt) {
        PoseObservations o;
        o.poses_deg = Rows(poses, self.model->NumChannels(), "poses");
        if (observed) {
          if (observed->size() != static_cast<size_t>(self.model->NumChannels())) {
            throw py::type_error("observed: expected " + std::to_string(self.model->NumChannels()) + " flags, got " +
                                 std::to_string(observed->size()));
          }
          o.observed = *observed;
        }
        InferenceOptions options;
        options.adapt_posture = adapt;
        InferenceResult r;
        {
          py::gil_scoped_release release;
          r = InferLatentSequence(*self.model, o, options);
        }
        return py::dict(py::arg("latent") = RowMatrix(r.latent), py::arg("poses_deg") = RowMatrix(r.poses_deg),
                        py::arg("initial_latent") = RowMatrix(r.initial_latent),
                        py::arg("posture_deg") = r.posture_deg, py::arg("gain") = r.gain,
                        py::arg("initial_objective") = r.initial_objective,
                        py::arg("final_objective") = r.final_objective, py::arg("iterations") = r.iterations,
                        py::arg("message") = r.message);
      },
      py::arg("model"), py::arg("poses"), py::arg("observed") = std::nullopt, py::arg("adapt") = false,
      "The latent sequence of observed poses (T x D degrees; observed: D flags, False for a missing channel), as "
      "`jgpm eval` infers it: a dict of latent (T x 3), poses_deg (the reconstruction, missing channels filled), "
      "posture_deg and gain (adapt=True: the person's style), objectives and iterations.");
  m.def(
      "calibrate_from_walkers",
      [](const std::vector<std::vector<std::string>>& takes, double person_height_m,
         const std::vector<std::string>& backgrounds, const std::vector<std::string>& intrinsics,
         double max_clock_offset_s) {
        cli::WalkerRequest request;
        request.takes = takes;
        request.person_height_m = person_height_m;
        request.backgrounds = backgrounds;
        request.intrinsics = intrinsics;
        request.max_clock_offset_s = max_clock_offset_s;
        if (takes.empty() || takes.front().empty()) throw InputError("calibrate_from_walkers: give at least one video");
        py::gil_scoped_release release;
        return cli::CalibrateFromWalkerVideos(request, cli::ReadWalkersFromVideo);
      },
      py::arg("takes"), py::arg("person_height_m") = 1.70, py::arg("backgrounds") = std::vector<std::string>(),
      py::arg("intrinsics") = std::vector<std::string>(), py::arg("max_clock_offset_s") = 2.0,
      "`jgpm calibrate --walkers` as a call: takes is a list of takes, each a list of one video (or frames folder, "
      "or clip folder) per camera; returns the cameras (one: above the world origin looking along +z; several: "
      "placed in cam0's world from the walkers they share, with their clock offsets). Prints what it found; "
      "jgpm.InputError with the command's one-line refusal when the walkers do not determine a camera.");
  m.def("track_video", &TrackVideo, py::arg("model"), py::arg("videos"), py::arg("cameras"),
        py::arg("out") = std::nullopt, py::arg("backgrounds") = std::vector<std::string>(), py::arg("seed") = 1,
        py::arg("threads") = 0, py::arg("people") = "one", py::arg("occluders") = std::vector<std::string>(),
        "`jgpm track --video ... --camera ...` as a call (one video and one camera YAML per camera; background "
        "learnt unless backgrounds= are given; occluders=: a painting of the static objects in front of the walk "
        "per camera; outputs written to out= when given): a dict of frames (as "
        "Tracker.step gives them), tracking_seconds, wall_seconds and written files. people='all' (--people all): "
        "each frame is {frame, time_s, people, born, ended}, each person an estimate with its id.");
  m.def(
      "load_model",
      [](const fs::path& path) {
        std::unique_ptr<GaitModel> model;
        {
          py::gil_scoped_release release;
          model = ReadModelFile(path);
        }
        return PyModel{std::move(model), path};
      },
      py::arg("path"), "Reads a model file (jgpm train's JSON); jgpm.InputError naming the file when it is not one.");

  py::class_<Camera>(m, "Camera", "A calibrated camera (OpenCV's pinhole model, world in millimetres).")
      .def_static(
          "from_yaml", [](const std::string& path) { return ReadCameraYaml(path).camera; }, py::arg("path"),
          "Reads a camera YAML (OpenCV's calibration sample's keys plus our extrinsics).")
      .def_readonly("name", &Camera::name)
      .def_readonly("width", &Camera::width)
      .def_readonly("height", &Camera::height)
      .def_readonly("fx", &Camera::fx)
      .def_readonly("fy", &Camera::fy)
      .def_readonly("cx", &Camera::cx)
      .def_readonly("cy", &Camera::cy)
      .def_readonly("clock_offset_s", &Camera::clock_offset_s)
      .def_property_readonly("camera_matrix", &Camera::CameraMatrix)
      .def_property_readonly("distortion", [](const Camera& c) { return c.distortion; })
      .def_property_readonly("rotation", [](const Camera& c) { return Eigen::Matrix3d(c.cam_from_world_rotation); },
                             "cam_from_world rotation (3 x 3).")
      .def_property_readonly("translation_mm",
                             [](const Camera& c) { return Eigen::Vector3d(c.cam_from_world_translation_mm); },
                             "cam_from_world translation, mm.")
      .def_property_readonly("centre_mm", &Camera::CentreInWorld)
      .def("project", &Project, py::arg("points"),
           "Pixels of world points (mm): (M, 3) -> (M, 2), through the lens distortion; NaN for a point not in "
           "front of the camera.");

  py::class_<PyTracker>(m, "Tracker",
                        "The annealed particle filter in a prior's latent space, fed one frame of binary masks "
                        "(one per camera) at a time from any segmenter.")
      .def(py::init<const PyModel&, std::vector<Camera>, uint64_t, int, int, int, double, const std::string&, int>(),
           py::arg("model"), py::arg("cameras"), py::arg("seed") = 1, py::arg("particles") = 200,
           py::arg("layers") = 4, py::arg("threads") = 0, py::arg("fps") = 30.0, py::arg("people") = "one",
           py::arg("max_people") = 8,
           "As `jgpm track` with its defaults (threads 0: all cores; the same seed gives the same poses for any "
           "thread count). The model's pose table is read from beside its file, or built and kept there. "
           "people='all' (--people all, at most max_people at once): each frame is {frame, time_s, people, born, "
           "ended, earlier}, each person an estimate with its id; earlier: estimates of frames returned before (each "
           "with its frame), new or in place of the person's estimate there, which jgpm track puts in those "
           "frames: the people born (confirmed) now, from the first frame they were followed in, and a birth's "
           "first second gone back over.")
      .def("step", &PyTracker::Step, py::arg("masks"),
           "One frame: a list of masks, one per camera (height x width, nonzero: the person), or None for a frame "
           "not seen. Returns the frames tracked by this call, as dicts (frame, time_s, status, joints_mm: joints "
           "x 3 or None, root_mm, heading_deg, size, pose_deg, ess, seconds): none while the first 15 frames are "
           "gathered (the start looks at them together), then, people='one', none until a second more has been "
           "tracked, the start's leg order settled (about 1.33 s) and the start gone over again backwards, then "
           "every frame so far, then one per call.")
      .def("finish", &PyTracker::Finish,
           "The frames still held when the sequence ended (for the start, or for going back over it).")
      .def_property_readonly("joint_names",
                             [](const PyTracker& self) { return self.model->skeleton().BoneNames(); });
}
