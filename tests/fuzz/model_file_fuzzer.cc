// libFuzzer target: ParseModelFile must either return a model or throw InputError, never
// abort, whatever the file holds (its checksum stops only accidental edits, so the
// checksum is recomputed here for every input: the fuzzer reaches the model's checks).
// What loads must predict finite poses and write and read back to identical predictions.
#include <cstddef>
#include <cstdint>
#include <string>

#include <nlohmann/json.hpp>

#include "io/base/checksum.h"
#include "io/base/error.h"
#include "prior/model/model_file.h"

namespace {

// The input with a correct checksum (FNV-1a 64 of the "model" member's dump), when it is
// JSON with a "model" member; otherwise as it is.
std::string WithChecksum(const std::string& text) {
  nlohmann::json file;
  try {
    file = nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception&) {
    return text;
  }
  if (!file.is_object() || !file.contains("model")) return text;
  file["checksum"] = jgpm::Checksum(file["model"].dump());
  return file.dump();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 200000) return 0;  // a model of a few training points is all the checks need
  const std::string text = WithChecksum(std::string(reinterpret_cast<const char*>(data), size));
  try {
    const auto model = jgpm::ParseModelFile(text, "fuzz.json");
    Eigen::VectorXd pose;
    double variance = 0;
    const Eigen::Vector3d x = model->latent().row(0).transpose();
    model->Predict(x, &pose, &variance);
    JGPM_CHECK(pose.allFinite() && std::isfinite(variance));
    const auto again = jgpm::ParseModelFile(jgpm::FormatModelFile(model->data()), "again.json");
    Eigen::VectorXd pose2;
    again->Predict(x, &pose2, nullptr);
    JGPM_CHECK(pose2 == pose);
  } catch (const jgpm::InputError&) {
  }
  return 0;
}
