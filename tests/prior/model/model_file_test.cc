#include "prior/model/model_file.h"

#include <functional>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "prior/model/train.h"
#include "prior/prior_test_support.h"
#include "test_support.h"

namespace jgpm {
namespace {

using test::ExpectInputError;

std::unique_ptr<GaitModel> SmallModel(ModelKind kind) {
  TrainingOptions options;
  options.kind = kind;
  options.full.max_iterations = 50;
  return TrainGaitModel(test::SyntheticWalks(4, 8), test::Skeleton35(), options);
}

// Every model kind: write, read, and the predictions are bit-identical.
TEST(ModelFile, LoadsBackToIdenticalPredictions) {
  for (ModelKind kind : AllModelKinds()) {
    SCOPED_TRACE(std::string(ModelKindName(kind)));
    const auto model = SmallModel(kind);
    test::TempDir dir;
    WriteModelFile(dir.path() / "m.json", *model);
    const auto back = ReadModelFile(dir.path() / "m.json");
    EXPECT_EQ(back->kind(), kind);
    EXPECT_EQ(back->latent(), model->latent());
    EXPECT_EQ(back->data().summary.iterations, model->data().summary.iterations);
    EXPECT_EQ(back->data().set.gait_ids, model->data().set.gait_ids);
    for (const Eigen::Vector3d& x : {Eigen::Vector3d(0.1, 0.2, 0.3), Eigen::Vector3d(-1, 2, 0.5)}) {
      Eigen::VectorXd a, b;
      double va, vb;
      model->Predict(x, &a, &va);
      back->Predict(x, &b, &vb);
      EXPECT_EQ(a, b);
      EXPECT_EQ(va, vb);
      EXPECT_EQ(model->LogPrior(x, nullptr), back->LogPrior(x, nullptr));
      EXPECT_EQ(model->NextLatent(x, nullptr), back->NextLatent(x, nullptr));
    }
    const Eigen::MatrixXd xs = model->latent().topRows(5);
    EXPECT_EQ(model->MeanPoses(xs), back->MeanPoses(xs));
  }
}

// A sparse-learned model says so and keeps its inducing count and exact objective.
TEST(ModelFile, SparseLearningSummaryLoadsBack) {
  const auto model =
      TrainGaitModel(test::SyntheticWalks(4, 8), test::Skeleton35(), test::SparseTraining(ModelKind::kGpdm, 9, 20));
  const auto back = ParseModelFile(FormatModelFile(model->data()), "m.json");
  EXPECT_EQ(back->data().summary.learning, Learning::kSparse);
  EXPECT_EQ(back->data().summary.inducing, 9);
  EXPECT_EQ(back->data().summary.exact_objective, model->data().summary.exact_objective);
  EXPECT_EQ(back->latent(), model->latent());
}

class ModelFileErrors : public testing::Test {
 protected:
  static void SetUpTestSuite() { text_ = new std::string(FormatModelFile(SmallModel(ModelKind::kJgpm)->data())); }
  static void TearDownTestSuite() { delete text_; }
  static std::string* text_;
};
std::string* ModelFileErrors::text_ = nullptr;

TEST_F(ModelFileErrors, Truncated) {
  ExpectInputError([] { ParseModelFile(text_->substr(0, text_->size() * 2 / 3), "m.json"); },
                   {"m.json", "not a complete model file"});
}

TEST_F(ModelFileErrors, OtherVersion) {
  nlohmann::json j = nlohmann::json::parse(*text_);
  j["version"] = 7;
  ExpectInputError([&] { ParseModelFile(j.dump(), "m.json"); },
                   {"m.json", "version 7 is not supported", "expected 1"});
}

TEST_F(ModelFileErrors, CorruptedNumber) {
  // Change one latent coordinate: still valid JSON, but the checksum catches it.
  nlohmann::json j = nlohmann::json::parse(*text_);
  j["model"]["latent"][5][1] = 0.123;
  ExpectInputError([&] { ParseModelFile(j.dump(), "m.json"); }, {"m.json", "checksum does not match"});
}

TEST_F(ModelFileErrors, NotAModel) {
  ExpectInputError([] { ParseModelFile("{\"format\": \"jgpm-gait-dataset\"}", "d.json"); },
                   {"d.json", "not a jgpm model file"});
  ExpectInputError([] { ReadModelFile("/nonexistent/m.json"); }, {"m.json", "no such file"});
}

// The file as another tool (or version) might write it: edited, with a matching checksum.
std::string WithChecksum(nlohmann::json j) {
  const std::string model_dump = j["model"].dump();
  uint64_t hash = 1469598103934665603ull;  // FNV-1a 64, as the writer computes it
  for (unsigned char c : model_dump) hash = (hash ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(hash));
  j["checksum"] = hex;
  return j.dump();
}

TEST_F(ModelFileErrors, InconsistentContentWithAValidChecksum) {
  // Someone edits the file and recomputes nothing but the checksum: the sizes are checked.
  nlohmann::json j = nlohmann::json::parse(*text_);
  j["model"]["latent"].erase(0);
  ExpectInputError([&] { ParseModelFile(WithChecksum(j), "m.json"); }, {"m.json", "latent points must be"});
}

// Each of these aborted the process or was accepted and used as an index before.
TEST_F(ModelFileErrors, NoEditCanAbortTheProcess) {
  const nlohmann::json valid = nlohmann::json::parse(*text_);
  struct Edit {
    std::string name;
    std::function<void(nlohmann::json&)> apply;
    std::string phrase;
  };
  const std::vector<Edit> edits = {
      {"two mapping hyper-parameters", [](nlohmann::json& m) { m["log_beta"].erase(0); },
       "mapping kernel needs 3 finite log hyper-parameters"},
      {"a joint index past the 18 gait joints", [](nlohmann::json& m) { m["channel_joints"][4] = 99; },
       "channel_joints differ"},
      {"a negative joint index", [](nlohmann::json& m) { m["channel_joints"][0] = -1; }, "channel_joints differ"},
      {"a zero layer scale", [](nlohmann::json& m) { m["layer_scales"][0] = 0.0; }, "layer scales must be"},
      {"poses per gait past int", [](nlohmann::json& m) { m["poses_per_gait"] = 2147483647; }, "training points"},
      {"an odd cross-layer count", [](nlohmann::json& m) { m["topology"]["cross_layer_neighbours"] = 5; },
       "cross_layer_neighbours"},
      {"an unknown termination", [](nlohmann::json& m) { m["summary"]["termination"] = "done"; },
       "termination"},
  };
  for (const Edit& edit : edits) {
    SCOPED_TRACE(edit.name);
    nlohmann::json j = valid;
    edit.apply(j["model"]);
    ExpectInputError([&] { ParseModelFile(WithChecksum(j), "m.json"); }, {"m.json", edit.phrase});
  }
  // A number past the range of a double is not a JSON number we can read: InputError, not
  // the JSON library's own exception.
  std::string text = WithChecksum(valid);
  const size_t at = text.find("\"layer_scales\":[");
  ASSERT_NE(at, std::string::npos);
  text.insert(at + std::string("\"layer_scales\":[").size(), "1e999,");
  ExpectInputError([&] { ParseModelFile(text, "m.json"); }, {"m.json", "number overflow"});
}

}  // namespace
}  // namespace jgpm
