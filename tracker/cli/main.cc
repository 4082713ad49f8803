// The `jgpm` command: a table of each layer's command groups (io/cli, calibration/cli,
// prior/cli, tracker/cli); each subcommand parses its options and calls the library. The
// only file that sees every group.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "calibration/cli/calibration_commands.h"
#include "io/base/error.h"
#include "io/base/heap.h"
#include "io/cli/data_commands.h"
#include "io/cli/device_commands.h"
#include "prior/cli/prior_commands.h"
#include "prior/cli/transition_commands.h"
#include "prior/cli/validation_commands.h"
#include "prior/numerics/blas_threads.h"
#include "tracker/cli/render_commands.h"
#include "tracker/cli/track_commands.h"
#include "tracker/cli/walker_video.h"

int main(int argc, char** argv) {
  jgpm::KeepFreedMemory();  // learning's temporaries are reused, not page-faulted in again
  jgpm::UseOneLinearAlgebraThreadUnlessSet();  // commands that gain from more ask (train --threads)
  CLI::App app{"jgpm: gait priors (ML-JGPM) from motion capture and 3-D gait tracking in video"};
  app.set_version_flag("--version", "jgpm " JGPM_VERSION);
  app.require_subcommand(1);
  jgpm::cli::AddDataCommands(app);
  jgpm::cli::AddPriorCommands(app);
  jgpm::cli::AddValidationCommands(app);
  jgpm::cli::AddRenderCommands(app);
  jgpm::cli::AddTrackCommands(app);
  CLI::App* bench = app.add_subcommand("bench", "Benchmarks");
  bench->require_subcommand(1);
  jgpm::cli::AddTrackBench(bench);
  jgpm::cli::AddPriorBenches(bench);
  jgpm::cli::AddTransitionCommands(app);
  jgpm::cli::AddCalibrationCommands(app, jgpm::cli::ReadWalkersFromVideo);
  jgpm::cli::AddDeviceCommands(app);
  try {
    app.parse(argc, argv);  // subcommand callbacks run here
  } catch (const CLI::Success& e) {
    return app.exit(e);  // --help, --version
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "jgpm: error: %s (see --help)\n", e.what());
    return 2;
  } catch (const jgpm::InputError& e) {
    std::fprintf(stderr, "jgpm: error: %s\n", e.what());
    return 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "jgpm: error: %s\n", e.what());
    return 1;
  }
  return 0;
}
