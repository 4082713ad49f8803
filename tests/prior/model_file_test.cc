#include "prior/model_file.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "prior/train.h"
#include "prior_test_support.h"
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

TEST_F(ModelFileErrors, InconsistentContentWithAValidChecksum) {
  // Someone edits the file and recomputes nothing but the checksum: the sizes are checked.
  nlohmann::json j = nlohmann::json::parse(*text_);
  j["model"]["latent"].erase(0);
  const std::string model_dump = j["model"].dump();
  uint64_t hash = 1469598103934665603ull;  // FNV-1a 64, as the writer computes it
  for (unsigned char c : model_dump) hash = (hash ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof(hex), "%016llx", static_cast<unsigned long long>(hash));
  j["checksum"] = hex;
  ExpectInputError([&] { ParseModelFile(j.dump(), "m.json"); }, {"m.json", "latent points must be"});
}

}  // namespace
}  // namespace jgpm
