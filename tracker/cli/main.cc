// The `jgpm` command: each subcommand parses its options and calls the library.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>

#include "io/error.h"
#include "io/heap.h"
#include "tracker/cli/calibration_commands.h"
#include "tracker/cli/data_commands.h"
#include "tracker/cli/device_commands.h"
#include "tracker/cli/prior_commands.h"
#include "tracker/cli/render_commands.h"
#include "tracker/cli/track_commands.h"
#include "tracker/cli/transition_commands.h"
#include "tracker/cli/validation_commands.h"

int main(int argc, char** argv) {
  jgpm::KeepFreedMemory();  // learning's temporaries are reused, not page-faulted in again
  CLI::App app{"jgpm: gait priors (ML-JGPM) from motion capture and 3-D gait tracking in video"};
  app.set_version_flag("--version", "jgpm " JGPM_VERSION);
  app.require_subcommand(1);
  jgpm::cli::AddDataCommands(app);
  jgpm::cli::AddPriorCommands(app);
  jgpm::cli::AddValidationCommands(app);
  jgpm::cli::AddRenderCommands(app);
  jgpm::cli::AddTrackCommands(app);
  jgpm::cli::AddTransitionCommands(app);
  jgpm::cli::AddCalibrationCommands(app);
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
