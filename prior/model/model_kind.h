// The model kinds jgpm learns and what each one is made of (one code path for all:
// prior/learning/objective.h switches terms, prior/learning/topology.h builds the topology priors).
//
//   pca           linear baseline: the 3 leading principal components
//   gplvm         GP mapping + N(0, I) latent prior, MAP; PCA initialisation
//   gpdm          + per-channel scales W and first-order GP dynamics per sequence
//   bgpdm         GPDM with the dynamics term weighted by D / q (balanced)
//   llgpdm        GPDM + LLE topology prior on a cylinder (gaits in shortest-open-path order)
//   jgpm          GPDM + LLE topology prior on a torus (shortest closed path), one layer
//   mljgpm-torus  JGPM on three layers from diversification with scales 0.4, 1, 1.25
//   mljgpm-cyl    the same on three cylinders
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "prior/learning/objective.h"
#include "prior/learning/topology.h"

namespace jgpm {

enum class ModelKind { kPca, kGplvm, kGpdm, kBgpdm, kLlgpdm, kJgpm, kMljgpmTorus, kMljgpmCyl };

const std::vector<ModelKind>& AllModelKinds();
std::string_view ModelKindName(ModelKind kind);
bool ParseModelKind(std::string_view name, ModelKind* kind);
// "pca, gplvm, ..." for help texts and errors.
std::string ModelKindList();

struct ModelSpec {
  ModelKind kind = ModelKind::kPca;
  std::vector<double> layer_scales{1.0};
  bool gaussian_process = false;  // false: PCA
  bool topology = false;
  TopologyShape shape = TopologyShape::kTorus;
  ObjectiveTerms terms;
};

// `num_channels` is D (for B-GPDM's D / q weight).
ModelSpec SpecFor(ModelKind kind, int num_channels);

}  // namespace jgpm
