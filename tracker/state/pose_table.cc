#include "tracker/state/pose_table.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <thread>

#include "io/base/error.h"
#include "io/gait/gait_pose.h"
#include "prior/model/latent_density.h"

namespace jgpm {

bool PoseTableOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (phase_nodes < 8 || phase_nodes > 1024) problem = "phase_nodes must be in [8, 1024]";
  else if (nodes_per_gait < 1 || nodes_per_gait > 64) problem = "nodes_per_gait must be in [1, 64]";
  else if (scale_nodes < 2 || scale_nodes > 64) problem = "scale_nodes must be in [2, 64]";
  else if (latent_nodes < 4 || latent_nodes > 128) problem = "latent_nodes must be in [4, 128]";
  else if (!(latent_margin >= 0 && latent_margin <= 2)) problem = "latent_margin must be in [0, 2]";
  else if (density_neighbours < 1 || density_neighbours > 64) problem = "density_neighbours must be in [1, 64]";
  else if (threads < 1) problem = "threads must be >= 1";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr;
}

PoseTable::PoseTable(const GaitModel& model, const PoseTableOptions& options) : manifold_(model.HasManifold()) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("pose table options", why);
  const TrainingSet& set = model.data().set;
  if (manifold_) {
    const int gaits = set.NumGaits();
    const bool torus = model.data().topology_options.shape == TopologyShape::kTorus;
    const auto [lowest, highest] = std::minmax_element(set.layer_scales.begin(), set.layer_scales.end());
    n_ = {options.phase_nodes, torus ? gaits * options.nodes_per_gait : (gaits - 1) * options.nodes_per_gait + 1,
          *highest > *lowest ? options.scale_nodes : 1};
    lo_ = {0, 0, *lowest};
    hi_ = {1, torus ? static_cast<double>(gaits) : gaits - 1.0, *highest};
    periodic_ = {true, torus, false};
  } else {
    const Eigen::RowVector3d low = model.latent().colwise().minCoeff(), high = model.latent().colwise().maxCoeff();
    const Eigen::RowVector3d pad = options.latent_margin * (high - low);
    for (int d = 0; d < 3; ++d) {
      n_[d] = options.latent_nodes;
      lo_[d] = low[d] - pad[d];
      hi_[d] = high[d] + pad[d];
      periodic_[d] = false;
    }
  }
  for (int d = 0; d < 3; ++d) {
    step_[d] = n_[d] <= 1 ? 1.0 : (hi_[d] - lo_[d]) / (periodic_[d] ? n_[d] : n_[d] - 1);
  }

  const Skeleton& skeleton = model.skeleton();
  const GaitPoseLayout layout(skeleton, "the model's skeleton");
  bones_ = static_cast<int>(skeleton.bones.size());
  channels_ = model.NumChannels();
  fast_size_ = 3 * bones_ + 2;
  const std::vector<int> feet = skeleton.FootBones();
  if (feet.empty()) ThrowInputError("the model's skeleton", "has no lfoot, rfoot, ltoes or rtoes bone to stand on");

  const int nodes = n_[0] * n_[1] * n_[2];
  Eigen::MatrixXd xs(nodes, 3);
  for (int k = 0; k < n_[2]; ++k)
    for (int j = 0; j < n_[1]; ++j)
      for (int i = 0; i < n_[0]; ++i) {
        const Eigen::Vector3d at(lo_[0] + i * step_[0], lo_[1] + j * step_[1], lo_[2] + k * step_[2]);
        xs.row(Node(i, j, k)) = (manifold_ ? model.ManifoldToLatent({at[0], at[1], at[2]}) : at).transpose();
      }
  fast_.assign(static_cast<size_t>(nodes) * fast_size_, 0.0f);
  poses_.assign(static_cast<size_t>(nodes) * channels_, 0.0f);
  const Kinematics kinematics(skeleton);
  const LatentDensity density_model(model.latent(), std::min(options.density_neighbours, model.NumPoints() - 1));
  auto work = [&](int first, int last) {
    ModelWorkspace workspace;
    constexpr int kChunk = 256;
    Eigen::MatrixXd poses(kChunk, channels_);
    Eigen::VectorXd density(kChunk);
    std::vector<double> frame(kinematics.NumChannels());
    Eigen::Matrix3Xd joints;
    for (int begin = first; begin < last; begin += kChunk) {
      const int count = std::min(kChunk, last - begin);
      model.MeanPoses(xs.middleRows(begin, count), poses.topRows(count), &workspace);
      Eigen::VectorXd distances2(model.NumPoints());
      for (int r = 0; r < count; ++r) density[r] = density_model.LogDensity(xs.row(begin + r).transpose(), distances2);
      for (int r = 0; r < count; ++r) {
        const Eigen::VectorXd pose = poses.row(r).transpose();
        layout.ToFrame(pose.data(), frame.data());
        kinematics.Compute(frame.data(), &joints);
        const Eigen::Vector3d root = joints.col(0);
        float* out = &fast_[static_cast<size_t>(begin + r) * fast_size_];
        double foot = 1e300;
        for (int b = 0; b < bones_; ++b) {
          const Eigen::Vector3d p = joints.col(b) - root;
          for (int d = 0; d < 3; ++d) out[3 * b + d] = static_cast<float>(p[d]);
        }
        for (int b : feet) foot = std::min(foot, joints(1, b) - root.y());
        out[3 * bones_] = static_cast<float>(foot);
        out[3 * bones_ + 1] = static_cast<float>(density[r]);
        float* pose_out = &poses_[static_cast<size_t>(begin + r) * channels_];
        for (int c = 0; c < channels_; ++c) pose_out[c] = static_cast<float>(pose[c]);
      }
    }
  };
  const int threads = std::max(1, std::min(options.threads, nodes / 1024 + 1));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work, nodes * t / threads, nodes * (t + 1) / threads);
  work(0, nodes / threads);
  for (std::thread& t : pool) t.join();

  if (manifold_) {
    // Stride per (gait node, scale node): over the cycle, the lower foot's travel backwards.
    const int left = skeleton.FindBone("lfoot"), right = skeleton.FindBone("rfoot");
    if (left < 0 || right < 0) ThrowInputError("the model's skeleton", "has no lfoot and rfoot bones");
    stride_.assign(static_cast<size_t>(n_[1]) * n_[2], 0.0);
    for (int k = 0; k < n_[2]; ++k)
      for (int j = 0; j < n_[1]; ++j) {
        double travel = 0;
        for (int i = 0; i < n_[0]; ++i) {
          const float* a = &fast_[static_cast<size_t>(Node(i, j, k)) * fast_size_];
          const float* b = &fast_[static_cast<size_t>(Node((i + 1) % n_[0], j, k)) * fast_size_];
          const int stance = a[3 * left + 1] + b[3 * left + 1] < a[3 * right + 1] + b[3 * right + 1] ? left : right;
          travel += std::max(0.0f, a[3 * stance + 2] - b[3 * stance + 2]);
        }
        stride_[static_cast<size_t>(k) * n_[1] + j] = travel;
      }
  }
}

namespace {

constexpr char kMagic[8] = {'J', 'G', 'P', 'M', 'T', 'A', 'B', '1'};

template <typename T>
void Put(std::string* out, const T& value) {
  out->append(reinterpret_cast<const char*>(&value), sizeof(T));
}
template <typename T>
void PutVector(std::string* out, const std::vector<T>& values) {
  Put(out, static_cast<uint64_t>(values.size()));
  if (!values.empty()) out->append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(T));
}

// Reads what Put wrote, refusing to run past the end.
class Reader {
 public:
  Reader(std::string_view bytes, const std::string& source) : bytes_(bytes), source_(source) {}
  template <typename T>
  T Get() {
    T value;
    Take(&value, sizeof(T));
    return value;
  }
  template <typename T>
  std::vector<T> GetVector(uint64_t expected) {
    const uint64_t n = Get<uint64_t>();
    if (n != expected) Fail("an array of " + std::to_string(n) + " values where " + std::to_string(expected) + " belong");
    if (n > (bytes_.size() - at_) / sizeof(T)) Fail("truncated");
    std::vector<T> values(n);
    Take(values.data(), n * sizeof(T));
    return values;
  }
  std::string GetString() {
    const uint64_t n = Get<uint64_t>();
    if (n > bytes_.size() - at_) Fail("truncated");
    std::string text(bytes_.substr(at_, n));
    at_ += n;
    return text;
  }
  bool GetBool() {
    const uint8_t b = Get<uint8_t>();
    if (b > 1) Fail("a flag of " + std::to_string(b));
    return b == 1;
  }
  bool AtEnd() const { return at_ == bytes_.size(); }
  [[noreturn]] void Fail(const std::string& what) const { ThrowInputError(source_, "not a pose table: " + what); }

 private:
  void Take(void* to, uint64_t n) {
    if (n > bytes_.size() - at_) Fail("truncated");
    if (n == 0) return;  // `to` may be null (an empty array)
    std::memcpy(to, bytes_.data() + at_, n);
    at_ += n;
  }
  std::string_view bytes_;
  const std::string& source_;
  size_t at_ = 0;
};

}  // namespace

std::string PoseTable::Serialize(const std::string& key) const {
  std::string out(kMagic, sizeof(kMagic));
  Put(&out, static_cast<uint64_t>(key.size()));
  out += key;
  Put(&out, static_cast<uint8_t>(manifold_));
  Put(&out, bones_);
  Put(&out, channels_);
  for (int d = 0; d < 3; ++d) {
    Put(&out, n_[d]);
    Put(&out, lo_[d]);
    Put(&out, hi_[d]);
    Put(&out, step_[d]);
    Put(&out, static_cast<uint8_t>(periodic_[d]));
  }
  PutVector(&out, fast_);
  PutVector(&out, poses_);
  PutVector(&out, stride_);
  return out;
}

std::unique_ptr<PoseTable> PoseTable::Parse(std::string_view bytes, const std::string& key,
                                            const std::string& source) {
  Reader in(bytes, source);
  char magic[sizeof(kMagic)];
  for (char& c : magic) c = in.Get<char>();
  if (!std::equal(magic, magic + sizeof(kMagic), kMagic)) in.Fail("it does not begin with JGPMTAB1");
  if (in.GetString() != key) return nullptr;
  std::unique_ptr<PoseTable> table(new PoseTable());
  table->manifold_ = in.GetBool();
  table->bones_ = in.Get<int>();
  table->channels_ = in.Get<int>();
  if (table->bones_ < 1 || table->bones_ > 1000 || table->channels_ < 1 || table->channels_ > 10000)
    in.Fail("bones or channels out of range");
  uint64_t nodes = 1;
  for (int d = 0; d < 3; ++d) {
    table->n_[d] = in.Get<int>();
    table->lo_[d] = in.Get<double>();
    table->hi_[d] = in.Get<double>();
    table->step_[d] = in.Get<double>();
    table->periodic_[d] = in.GetBool();
    const int n = table->n_[d];
    if (n < 1 || n > 4096 || (table->periodic_[d] && n < 2))
      in.Fail("grid size out of range");
    if (!(std::isfinite(table->lo_[d]) && std::isfinite(table->hi_[d]) && table->step_[d] > 0 &&
          std::isfinite(table->step_[d])))
      in.Fail("grid range not finite");
    nodes *= static_cast<uint64_t>(n);
  }
  if (nodes > (uint64_t{1} << 24)) in.Fail("too many nodes");
  table->fast_size_ = 3 * table->bones_ + 2;
  table->fast_ = in.GetVector<float>(nodes * table->fast_size_);
  table->poses_ = in.GetVector<float>(nodes * table->channels_);
  table->stride_ = in.GetVector<double>(table->manifold_ ? static_cast<uint64_t>(table->n_[1]) * table->n_[2] : 0);
  if (!in.AtEnd()) in.Fail("bytes after the end");
  const auto finite = [](const auto& v) { return std::all_of(v.begin(), v.end(), [](double x) { return std::isfinite(x); }); };
  if (!finite(table->fast_) || !finite(table->poses_) || !finite(table->stride_)) in.Fail("values not finite");
  return table;
}

PoseTable::Corner PoseTable::Corners(const Eigen::Vector3d& at) const {
  std::array<int, 3> i0{}, i1{};
  std::array<double, 3> f{};
  for (int d = 0; d < 3; ++d) {
    if (n_[d] <= 1) continue;
    double t = (at[d] - lo_[d]) / step_[d];
    if (!std::isfinite(t)) t = 0;
    if (periodic_[d]) {
      t -= n_[d] * std::floor(t / n_[d]);
      i0[d] = std::min(static_cast<int>(t), n_[d] - 1);
      f[d] = t - i0[d];
      i1[d] = (i0[d] + 1) % n_[d];
    } else {
      t = std::clamp(t, 0.0, n_[d] - 1.0);
      i0[d] = std::min(static_cast<int>(t), n_[d] - 2);
      f[d] = t - i0[d];
      i1[d] = i0[d] + 1;
    }
  }
  Corner c;
  for (int corner = 0; corner < 8; ++corner) {
    const int a = corner & 1, b = (corner >> 1) & 1, e = (corner >> 2) & 1;
    c.node[corner] = Node(a ? i1[0] : i0[0], b ? i1[1] : i0[1], e ? i1[2] : i0[2]);
    c.weight[corner] = (a ? f[0] : 1 - f[0]) * (b ? f[1] : 1 - f[1]) * (e ? f[2] : 1 - f[2]);
  }
  return c;
}

void PoseTable::Lookup(const Eigen::Vector3d& at, Eigen::Matrix3Xd* joints, double* foot_height_mm,
                       double* log_density) const {
  const Corner c = Corners(at);
  if (joints->cols() != bones_) joints->resize(3, bones_);
  double* out = joints->data();
  std::fill(out, out + 3 * bones_, 0.0);
  double foot = 0, density = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const double w = c.weight[corner];
    if (w == 0) continue;
    const float* node = &fast_[static_cast<size_t>(c.node[corner]) * fast_size_];
    for (int k = 0; k < 3 * bones_; ++k) out[k] += w * node[k];
    foot += w * node[3 * bones_];
    density += w * node[3 * bones_ + 1];
  }
  if (foot_height_mm) *foot_height_mm = foot;
  if (log_density) *log_density = density;
}

Eigen::VectorXd PoseTable::Pose(const Eigen::Vector3d& at) const {
  const Corner c = Corners(at);
  Eigen::VectorXd pose = Eigen::VectorXd::Zero(channels_);
  for (int corner = 0; corner < 8; ++corner) {
    const float* node = &poses_[static_cast<size_t>(c.node[corner]) * channels_];
    for (int k = 0; k < channels_; ++k) pose[k] += c.weight[corner] * node[k];
  }
  return pose;
}

double PoseTable::StrideMm(double gait, double scale) const {
  JGPM_CHECK(manifold_);
  const Corner c = Corners(Eigen::Vector3d(0, gait, scale));
  double stride = 0;
  for (int corner = 0; corner < 8; ++corner) {
    const int node = c.node[corner];
    const int j = (node / n_[0]) % n_[1], k = node / (n_[0] * n_[1]);
    stride += c.weight[corner] * stride_[static_cast<size_t>(k) * n_[1] + j];
  }
  return stride;
}

}  // namespace jgpm
