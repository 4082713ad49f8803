#include "prior/model/model_file.h"

#include <cstdint>

#include "io/base/checksum.h"
#include "io/base/error.h"
#include "io/base/json_file.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace {

using nlohmann::json;

json Matrix(const Eigen::MatrixXd& m) {
  json rows = json::array();
  for (int r = 0; r < m.rows(); ++r) {
    json row = json::array();
    for (int c = 0; c < m.cols(); ++c) row.push_back(m(r, c));
    rows.push_back(std::move(row));
  }
  return rows;
}

json Vector(const Eigen::VectorXd& v) { return std::vector<double>(v.data(), v.data() + v.size()); }

const char* ShapeName(TopologyShape shape) { return shape == TopologyShape::kTorus ? "torus" : "cylinder"; }

json ModelJson(const GaitModelData& d) {
  const TrainingSet& s = d.set;
  json model;
  model["kind"] = std::string(ModelKindName(d.kind));
  model["split"] = d.split;
  model["learning"] = std::string(LearningName(d.summary.learning));  // for readers; summary.learning is read
  model["seed"] = d.seed;
  model["terms"] = {{"latent_prior", d.terms.latent_prior},
                    {"channel_scales", d.terms.channel_scales},
                    {"dynamics", d.terms.dynamics},
                    {"dynamics_weight", d.terms.dynamics_weight},
                    {"topology", d.terms.topology},
                    {"topology_sigma2", d.terms.topology_sigma2},
                    {"scale_prior_width", d.terms.scale_prior_width},
                    {"fixed_inverse_width", d.terms.fixed_inverse_width},
                    {"fixed_dynamics_noise", d.terms.fixed_dynamics_noise}};
  model["channels"] = s.channel_names;
  model["channel_joints"] = s.channel_joints;
  model["gait_ids"] = s.gait_ids;
  model["layer_scales"] = s.layer_scales;
  model["poses_per_gait"] = s.poses_per_gait;
  model["channel_mean"] = Vector(s.mean.transpose());
  model["channel_scale"] = Vector(s.scale.transpose());
  model["training_poses_deg"] = Matrix(s.y_deg);
  model["latent"] = Matrix(d.params.x);
  model["log_beta"] = Vector(d.params.log_beta);
  model["log_alpha"] = Vector(d.params.log_alpha);
  model["log_w"] = Vector(d.params.log_w);
  model["pca_basis"] = Matrix(d.pca_basis);
  if (!d.gait_order.empty()) {
    const TopologyOptions& t = d.topology_options;
    model["topology"] = {{"shape", ShapeName(t.shape)},
                         {"gait_radius", t.gait_radius},
                         {"gait_spacing", t.gait_spacing},
                         {"within_layer_neighbours", t.within_layer_neighbours},
                         {"cross_layer_neighbours", t.cross_layer_neighbours},
                         {"lle_regularization", t.lle_regularization},
                         {"gait_order", d.gait_order},
                         {"prior_coordinates", Matrix(d.prior_coordinates)}};
  }
  model["skeleton"] = {{"trial", d.skeleton_trial}, {"asf", d.skeleton_asf}};
  const TrainingSummary& r = d.summary;
  model["summary"] = {{"learning", std::string(LearningName(r.learning))},
                      {"termination", std::string(TerminationName(r.termination))},
                      {"message", r.message},
                      {"iterations", r.iterations},
                      {"evaluations", r.evaluations},
                      {"initial_objective", r.initial_objective},
                      {"final_objective", r.final_objective},
                      {"max_jitter", r.max_jitter},
                      {"wall_seconds", r.wall_seconds}};
  if (r.inducing > 0) {
    model["summary"]["inducing"] = r.inducing;
    model["summary"]["exact_objective"] = r.exact_objective;
  }
  return model;
}

Eigen::MatrixXd ReadMatrix(const JsonReader& in, const json& object, const std::string& key, int cols) {
  const auto rows = in.Get<std::vector<std::vector<double>>>(object, key, "model.");
  Eigen::MatrixXd m(static_cast<int>(rows.size()), cols);
  for (size_t r = 0; r < rows.size(); ++r) {
    if (static_cast<int>(rows[r].size()) != cols) {
      in.Fail("model." + key + "[" + std::to_string(r) + "]",
              "expected " + std::to_string(cols) + " values, found " + std::to_string(rows[r].size()));
    }
    for (int c = 0; c < cols; ++c) m(static_cast<int>(r), c) = rows[r][c];
  }
  return m;
}

Eigen::VectorXd ReadVector(const JsonReader& in, const json& object, const std::string& key) {
  const auto values = in.Get<std::vector<double>>(object, key, "model.");
  return Eigen::Map<const Eigen::VectorXd>(values.data(), static_cast<int>(values.size()));
}

}  // namespace

std::string FormatModelFile(const GaitModelData& data) {
  const json model = ModelJson(data);
  json file;
  file["format"] = "jgpm-model";
  file["version"] = kModelFileVersion;
  file["checksum"] = Checksum(model.dump());
  file["model"] = model;
  return FormatJson(file);
}

void WriteModelFile(const std::filesystem::path& path, const GaitModel& model) {
  WriteFileAtomic(path, FormatModelFile(model.data()));
}

std::unique_ptr<GaitModel> ParseModelFile(const std::string& text, const std::string& source) {
  json file;
  try {
    file = json::parse(text);
  } catch (const json::exception& e) {  // parse_error, and out_of_range for 1e999
    ThrowInputError(source, std::string("not a complete model file (invalid JSON: ") + e.what() + ")");
  }
  const JsonReader in(source);
  if (!file.is_object() || !file.contains("format") || file["format"] != "jgpm-model") {
    ThrowInputError(source, "not a jgpm model file (expected \"format\": \"jgpm-model\")");
  }
  const int version = in.Get<int>(file, "version", "");
  if (version != kModelFileVersion) {
    ThrowInputError(source, "model file version " + std::to_string(version) +
                                " is not supported by this jgpm (expected " +
                                std::to_string(kModelFileVersion) + "); retrain the model");
  }
  const json& model = in.Field(file, "model", "");
  if (in.Get<std::string>(file, "checksum", "") != Checksum(model.dump())) {
    ThrowInputError(source, "checksum does not match the content: the file was edited or corrupted");
  }
  GaitModelData d;
  if (!ParseModelKind(in.Get<std::string>(model, "kind", "model."), &d.kind)) {
    in.Fail("model.kind", "is not one of " + ModelKindList());
  }
  d.split = in.Get<std::string>(model, "split", "model.");
  d.seed = in.Get<uint64_t>(model, "seed", "model.");
  const json& t = in.Field(model, "terms", "model.");
  d.terms.latent_prior = in.Get<bool>(t, "latent_prior", "model.terms.");
  d.terms.channel_scales = in.Get<bool>(t, "channel_scales", "model.terms.");
  d.terms.dynamics = in.Get<bool>(t, "dynamics", "model.terms.");
  d.terms.dynamics_weight = in.Get<double>(t, "dynamics_weight", "model.terms.");
  d.terms.topology = in.Get<bool>(t, "topology", "model.terms.");
  d.terms.topology_sigma2 = in.Get<double>(t, "topology_sigma2", "model.terms.");
  d.terms.scale_prior_width = in.Get<double>(t, "scale_prior_width", "model.terms.");
  d.terms.fixed_inverse_width = in.Get<bool>(t, "fixed_inverse_width", "model.terms.");
  d.terms.fixed_dynamics_noise = in.Get<bool>(t, "fixed_dynamics_noise", "model.terms.");
  TrainingSet& s = d.set;
  s.channel_names = in.Get<std::vector<std::string>>(model, "channels", "model.");
  s.channel_joints = in.Get<std::vector<int>>(model, "channel_joints", "model.");
  s.gait_ids = in.Get<std::vector<std::string>>(model, "gait_ids", "model.");
  s.layer_scales = in.Get<std::vector<double>>(model, "layer_scales", "model.");
  s.poses_per_gait = in.Get<int>(model, "poses_per_gait", "model.");
  const int channels = static_cast<int>(s.channel_names.size());
  s.mean = ReadVector(in, model, "channel_mean").transpose();
  s.scale = ReadVector(in, model, "channel_scale").transpose();
  s.y_deg = ReadMatrix(in, model, "training_poses_deg", channels);
  d.params.x = ReadMatrix(in, model, "latent", 3);
  d.params.log_beta = ReadVector(in, model, "log_beta");
  d.params.log_alpha = ReadVector(in, model, "log_alpha");
  d.params.log_w = ReadVector(in, model, "log_w");
  d.pca_basis = ReadMatrix(in, model, "pca_basis", d.kind == ModelKind::kPca ? 3 : 0);
  if (model.contains("topology")) {
    const json& topology = model["topology"];
    const std::string where = "model.topology.";
    const std::string shape = in.Get<std::string>(topology, "shape", where);
    if (shape != "torus" && shape != "cylinder") in.Fail(where + "shape", "must be torus or cylinder");
    TopologyOptions& o = d.topology_options;
    o.shape = shape == "torus" ? TopologyShape::kTorus : TopologyShape::kCylinder;
    o.gait_radius = in.Get<double>(topology, "gait_radius", where);
    o.gait_spacing = in.Get<double>(topology, "gait_spacing", where);
    o.within_layer_neighbours = in.Get<int>(topology, "within_layer_neighbours", where);
    o.cross_layer_neighbours = in.Get<int>(topology, "cross_layer_neighbours", where);
    o.lle_regularization = in.Get<double>(topology, "lle_regularization", where);
    d.gait_order = in.Get<std::vector<int>>(topology, "gait_order", where);
    d.prior_coordinates = ReadMatrix(in, topology, "prior_coordinates", 3);
  }
  const json& skeleton = in.Field(model, "skeleton", "model.");
  d.skeleton_trial = in.Get<std::string>(skeleton, "trial", "model.skeleton.");
  d.skeleton_asf = in.Get<std::string>(skeleton, "asf", "model.skeleton.");
  const json& r = in.Field(model, "summary", "model.");
  const std::string w = "model.summary.";
  if (!ParseLearning(in.Get<std::string>(r, "learning", w), &d.summary.learning)) {
    in.Fail(w + "learning", "is not one of closed form, full, local, sparse");
  }
  if (!ParseTermination(in.Get<std::string>(r, "termination", w), &d.summary.termination)) {
    in.Fail(w + "termination", "is not one of converged, no convergence, stopped, numerical failure");
  }
  d.summary.message = in.Get<std::string>(r, "message", w);
  d.summary.iterations = in.Get<int>(r, "iterations", w);
  d.summary.evaluations = in.Get<int>(r, "evaluations", w);
  d.summary.initial_objective = in.Get<double>(r, "initial_objective", w);
  d.summary.final_objective = in.Get<double>(r, "final_objective", w);
  d.summary.max_jitter = in.Get<double>(r, "max_jitter", w);
  d.summary.wall_seconds = in.Get<double>(r, "wall_seconds", w);
  if (r.contains("inducing")) {  // sparse learning
    d.summary.inducing = in.Get<int>(r, "inducing", w);
    d.summary.exact_objective = in.Get<double>(r, "exact_objective", w);
  }
  return GaitModel::Create(std::move(d), source);
}

std::unique_ptr<GaitModel> ReadModelFile(const std::filesystem::path& path) {
  return ParseModelFile(ReadTextFile(path, "a jgpm model (JSON from `jgpm train`)"), path.string());
}

}  // namespace jgpm
