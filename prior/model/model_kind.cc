#include "prior/model/model_kind.h"

#include "io/base/enum_name.h"

namespace jgpm {

const std::vector<ModelKind>& AllModelKinds() {
  static const std::vector<ModelKind> kinds = {
      ModelKind::kPca,    ModelKind::kGplvm, ModelKind::kGpdm,        ModelKind::kBgpdm,
      ModelKind::kLlgpdm, ModelKind::kJgpm,  ModelKind::kMljgpmTorus, ModelKind::kMljgpmCyl};
  return kinds;
}

std::string_view ModelKindName(ModelKind kind) {
  switch (kind) {
    case ModelKind::kPca: return "pca";
    case ModelKind::kGplvm: return "gplvm";
    case ModelKind::kGpdm: return "gpdm";
    case ModelKind::kBgpdm: return "bgpdm";
    case ModelKind::kLlgpdm: return "llgpdm";
    case ModelKind::kJgpm: return "jgpm";
    case ModelKind::kMljgpmTorus: return "mljgpm-torus";
    case ModelKind::kMljgpmCyl: return "mljgpm-cyl";
  }
  return "?";
}

bool ParseModelKind(std::string_view name, ModelKind* kind) {
  return ParseByName(name, AllModelKinds(), ModelKindName, kind);
}

std::string ModelKindList() {
  std::string list;
  for (ModelKind k : AllModelKinds()) list += (list.empty() ? "" : ", ") + std::string(ModelKindName(k));
  return list;
}

ModelSpec SpecFor(ModelKind kind, int num_channels) {
  ModelSpec spec;
  spec.kind = kind;
  if (kind == ModelKind::kPca) return spec;
  spec.gaussian_process = true;
  if (kind == ModelKind::kGplvm) {
    spec.terms.latent_prior = true;
    return spec;
  }
  spec.terms.channel_scales = true;
  spec.terms.dynamics = true;
  if (kind == ModelKind::kBgpdm) spec.terms.dynamics_weight = num_channels / 3.0;
  if (kind == ModelKind::kGpdm || kind == ModelKind::kBgpdm) return spec;
  spec.topology = true;
  spec.terms.topology = true;
  spec.shape = (kind == ModelKind::kLlgpdm || kind == ModelKind::kMljgpmCyl) ? TopologyShape::kCylinder
                                                                             : TopologyShape::kTorus;
  if (kind == ModelKind::kMljgpmTorus || kind == ModelKind::kMljgpmCyl) spec.layer_scales = {0.4, 1.0, 1.25};
  return spec;
}

}  // namespace jgpm
