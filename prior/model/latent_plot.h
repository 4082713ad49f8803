// A picture of a trained model's latent space, like the paper's Fig. 8: the latent points
// in a 3-D view (coloured by layer, each gait's cycle joined in order), and three
// axis-aligned slices through the middle of the latent space with the predictive variance
// as a heat map and the points near each slice on top.
#pragma once

#include <filesystem>

#include "prior/model/gait_model.h"

namespace jgpm {

struct LatentPlotOptions {
  int width = 1400;           // pixels of the whole picture
  int slice_resolution = 120; // variance samples per slice side
};

// Writes a PNG. InputError if it cannot be written.
void PlotLatentSpace(const GaitModel& model, const std::filesystem::path& png,
                     const LatentPlotOptions& options = {});

}  // namespace jgpm
