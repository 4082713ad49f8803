#include "tracker/cli/device_commands.h"

#include <cstdio>

#include "io/v4l2_camera.h"

namespace jgpm::cli {

void AddDeviceCommands(CLI::App& app) {
  CLI::App* devices = app.add_subcommand("devices", "List the V4L2 cameras (/dev/video*) with their driver and formats");
  devices->callback([] {
    LibV4l2Api api;
    const std::vector<V4l2DeviceInfo> found = ListV4l2Devices(api);
    if (found.empty()) {
      std::printf("no V4L2 video devices (/dev/video* not found)\n");
      return;
    }
    for (const V4l2DeviceInfo& d : found) {
      if (!d.error.empty()) {
        std::printf("%s: %s\n", d.path.c_str(), d.error.c_str());
        continue;
      }
      std::printf("%s: %s (%s, %s)%s\n", d.path.c_str(), d.card.c_str(), d.driver.c_str(), d.bus.c_str(),
                  d.capture ? "" : " - not a capture node");
      for (const std::string& f : d.formats) std::printf("  %s\n", f.c_str());
    }
  });
}

}  // namespace jgpm::cli
