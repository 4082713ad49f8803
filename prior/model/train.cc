#include "prior/model/train.h"

#include <chrono>

#include <Eigen/Eigenvalues>

#include "io/base/error.h"
#include "io/base/text_reader.h"
#include "prior/learning/topology.h"
#include "prior/numerics/blas_threads.h"

namespace jgpm {
namespace {

// Leading three right singular vectors of the normalised poses: the eigenvectors of the
// D x D matrix Y^T Y with the largest eigenvalues (ascending order from the solver).
Eigen::MatrixXd PrincipalBasis(const Eigen::MatrixXd& y) {
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(y.transpose() * y);
  Eigen::MatrixXd basis = eigen.eigenvectors().rightCols(3).rowwise().reverse();
  // Sign convention: the largest entry of each component positive, so results repeat.
  for (int c = 0; c < 3; ++c) {
    Eigen::Index largest;
    basis.col(c).cwiseAbs().maxCoeff(&largest);
    if (basis(largest, c) < 0) basis.col(c) *= -1;
  }
  return basis;
}

}  // namespace

std::vector<Sequence> TrainingSequences(const TrainingSet& set) {
  std::vector<Sequence> sequences;
  for (int s = 0; s < set.NumLayers() * set.NumGaits(); ++s) {
    sequences.push_back({s * set.poses_per_gait, set.poses_per_gait});
  }
  return sequences;
}

ReferenceSkeleton ChooseReferenceSkeleton(const GaitDataset& dataset, const std::filesystem::path& data_root) {
  for (const GaitTrial& trial : dataset.trials) {
    if (trial.cycle.clean) return {trial.id.name, ReadTextFile(data_root / trial.asf, "an ASF skeleton")};
  }
  ThrowInputError("dataset " + dataset.split, "has no clean gait cycle");
}

bool TrainingOptions::Check(std::string* why) const {
  const char* problem = nullptr;
  if (!(topology_sigma2 > 0)) problem = "topology sigma^2 must be > 0";
  else if (threads < 0) problem = "threads must be >= 0";
  else if (learning == Learning::kClosedForm) problem = "closed form is PCA's learning, not a GP model's";
  else if (learning == Learning::kSparse && inducing < 3) problem = "sparse learning needs at least 3 inducing inputs";
  if (problem && why) *why = problem;  // `why` may be null
  return problem == nullptr && local.Check(why);
}

std::unique_ptr<GaitModel> TrainGaitModel(const GaitDataset& dataset,
                                          const ReferenceSkeleton& skeleton,
                                          const TrainingOptions& options) {
  const ModelSpec spec = SpecFor(options.kind, static_cast<int>(dataset.channel_names.size()));
  return TrainGaitModel(MakeTrainingSet(dataset, spec.layer_scales), dataset.split, skeleton, options);
}

std::unique_ptr<GaitModel> TrainGaitModel(TrainingSet training_set, const std::string& split,
                                          const ReferenceSkeleton& skeleton, const TrainingOptions& options) {
  std::string why;
  if (!options.Check(&why)) ThrowInputError("training options", why);
  const LinearAlgebraThreadScope threads(options.threads);  // the caller's setting comes back
  const ModelSpec spec = SpecFor(options.kind, training_set.NumChannels());
  if (training_set.NumLayers() != static_cast<int>(spec.layer_scales.size())) {
    ThrowInputError("training set", std::to_string(training_set.NumLayers()) + " layer(s); a " +
                                        std::string(ModelKindName(options.kind)) + " model needs " +
                                        std::to_string(spec.layer_scales.size()));
  }
  GaitModelData data;
  data.kind = options.kind;
  data.split = split;
  data.seed = options.seed;
  data.terms = spec.terms;
  data.terms.topology_sigma2 = options.topology_sigma2;
  data.set = std::move(training_set);
  data.skeleton_trial = skeleton.trial;
  data.skeleton_asf = skeleton.asf;
  const TrainingSet& set = data.set;

  const Eigen::MatrixXd basis = PrincipalBasis(set.y);
  Eigen::MatrixXd scores = set.y * basis;
  if (!spec.gaussian_process) {
    const auto start = std::chrono::steady_clock::now();
    data.pca_basis = basis;
    data.params.x = scores;
    data.summary.learning = Learning::kClosedForm;
    data.summary.termination = Termination::kConverged;
    data.summary.message = "principal components of the training poses";
    data.summary.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return GaitModel::Create(std::move(data), "training");
  }

  Topology topology;
  if (spec.topology) {
    data.topology_options.shape = spec.shape;
    topology = MakeTopology(set, data.topology_options);
    data.gait_order = topology.gait_order;
    data.prior_coordinates = topology.coordinates;
    data.params.x = topology.coordinates;
  } else {
    data.params.x = scores / std::sqrt(scores.squaredNorm() / (3.0 * scores.rows()));
  }
  data.params.log_beta = Eigen::Vector3d(0, 0, std::log(100.0));
  if (spec.terms.dynamics) data.params.log_alpha = Eigen::Vector4d(0, 0, std::log(0.1), std::log(1e4));
  if (spec.terms.channel_scales) data.params.log_w = Eigen::VectorXd::Zero(set.NumChannels());
  if (options.start) {
    const GpParameters& start = *options.start;
    if (start.x.rows() != data.params.x.rows() || start.x.cols() != 3 ||
        start.log_beta.size() != data.params.log_beta.size() ||
        start.log_alpha.size() != data.params.log_alpha.size() || start.log_w.size() != data.params.log_w.size()) {
      ThrowInputError("training options", "the starting parameters' sizes are not the model's (" +
                                              std::to_string(data.params.x.rows()) + " latent points)");
    }
    if (!start.x.allFinite()) ThrowInputError("training options", "the starting latent points are not finite");
    data.params = start;
  }

  const GpObjective objective(set.y, TrainingSequences(set), spec.topology ? &topology : nullptr, data.terms);
  const bool budget_set = options.budget.max_seconds > 0 || options.budget.interrupted;
  if (options.learning == Learning::kSparse) {
    if (options.inducing > set.NumPoints()) {
      ThrowInputError("training options", std::to_string(options.inducing) + " inducing inputs for " +
                                              std::to_string(set.NumPoints()) + " training points; at most N");
    }
    // Inducing inputs start on the initial latent points (the topology prior's grid for the
    // JGPM family), evenly spread over the rows, which run over layers, gaits and poses.
    auto spread = [&](const std::vector<int>& rows) {
      const int m = std::min<int>(options.inducing, static_cast<int>(rows.size()));
      Eigen::MatrixXd u(m, 3);
      for (int k = 0; k < m; ++k) u.row(k) = data.params.x.row(rows[static_cast<size_t>(k) * rows.size() / m]);
      return u;
    };
    std::vector<int> all(set.NumPoints()), inputs;
    for (int i = 0; i < set.NumPoints(); ++i) {
      all[i] = i;
      if ((i + 1) % set.poses_per_gait != 0) inputs.push_back(i);  // has a next pose in its cycle
    }
    data.params.u = spread(all);
    if (spec.terms.dynamics) data.params.u_dynamics = spread(inputs);
  }
  if (options.learning != Learning::kLocal) {
    FullTrainingOptions full = options.full;
    if (options.progress) full.progress = options.progress;
    if (budget_set) full.budget = options.budget;
    data.summary = TrainFull(objective, &data.params, full);
    if (options.learning == Learning::kSparse) {
      // The model keeps the latent points and hyper-parameters (its predictions are exact),
      // and the summary their exact objective, comparable with the other learnings'.
      data.params.u.resize(0, 3);
      data.params.u_dynamics.resize(0, 3);
      const ObjectiveValue exact = objective.Evaluate(data.params, nullptr);
      if (exact.ok) {
        data.summary.exact_objective = exact.total;
      } else {
        data.summary.inducing = 0;  // no exact objective to report
        data.summary.message += "; the exact objective could not be evaluated (" + exact.why + ")";
      }
    }
  } else {
    LocalTrainingOptions local = options.local;
    local.seed = options.seed;
    if (options.progress) local.progress = options.progress;
    if (budget_set) local.budget = options.budget;
    // Neighbourhoods over the prior's coordinates where there is a topology, else over
    // the initial latent points.
    const Eigen::MatrixXd& where = spec.topology ? topology.coordinates : data.params.x;
    const auto neighbourhoods = LocalNeighbourhoods(set, where, LocalNeighbourhoodSize(set.NumPoints(), local));
    data.summary = TrainLocal(objective, neighbourhoods, &data.params, local);
  }
  // A numerical failure keeps the best parameters found before it (the trainers return
  // those); the summary says how training ended. Only when even those cannot be factorised
  // (the data themselves are degenerate) is there no model.
  return GaitModel::Create(std::move(data), "training");
}

}  // namespace jgpm
