#include "io/cli/device_commands.h"

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>

#include <opencv2/imgcodecs.hpp>

#include "io/base/error.h"
#include "io/base/output_folder.h"
#include "io/video/v4l2_camera.h"

namespace jgpm::cli {
namespace {

void ListDevices() {
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
}

struct CaptureArguments {
  std::string device, out, size;
  int count = 20;
  double every_s = 1.0;
  V4l2Options camera;
};

// Ctrl-C ends the capture early; what was saved is kept.
std::atomic<bool> stop{false};
extern "C" void OnCaptureInterrupt(int signal) {
  stop = true;
  std::signal(signal, SIG_DFL);
}

void Capture(CaptureArguments a) {
  if (!a.size.empty()) ParseSizeOption(a.size, &a.camera.width, &a.camera.height);
  const std::unique_ptr<V4l2Camera> camera = OpenV4l2Camera(a.device, a.camera);
  std::fprintf(stderr, "jgpm: %s\n", camera->negotiation().c_str());
  OutputFolder folder(a.out);
  stop = false;
  std::signal(SIGINT, OnCaptureInterrupt);
  std::signal(SIGTERM, OnCaptureInterrupt);
  Image image;
  int saved = 0;
  double next_s = -1;
  while (saved < a.count && !stop && camera->Read(&image)) {
    if (next_s >= 0 && image.time_s < next_s) continue;
    next_s = image.time_s + a.every_s;
    char name[32];
    std::snprintf(name, sizeof(name), "%06d.png", saved);
    const std::string path = (folder.partial() / name).string();
    if (!cv::imwrite(path, image.bgr)) ThrowInputError(path, "cannot write the image");
    ++saved;
    std::fprintf(stderr, "capture %d/%d  %s\n", saved, a.count, name);
  }
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  folder.Commit();
  std::string ended = stop ? " (interrupted)" : "";
  if (!stop && !camera->end_reason().empty()) ended = " (" + camera->end_reason() + ")";
  std::printf("saved %d image(s) of %dx%d from %s in %s%s\n", saved, camera->width(), camera->height(),
              a.device.c_str(), a.out.c_str(), ended.c_str());
}

}  // namespace

void ParseSizeOption(const std::string& text, int* width, int* height) {
  char x = 0, rest = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", width, &x, height, &rest) != 3 || (x != 'x' && x != 'X') || *width < 16 ||
      *height < 16 || *width > 8192 || *height > 8192) {
    ThrowInputError("--size " + text, "expected WIDTHxHEIGHT, e.g. 640x480");
  }
}

void AddDeviceCommands(CLI::App& app) {
  CLI::App* devices = app.add_subcommand("devices", "List the V4L2 cameras (/dev/video*) with their driver and formats");
  devices->callback(ListDevices);

  auto a = std::make_shared<CaptureArguments>();
  CLI::App* capture = app.add_subcommand(
      "capture", "Save a camera's frames as images: chessboard shots for jgpm calibrate, the floor board, the empty scene");
  capture->add_option("--device", a->device, "/dev/videoN (see jgpm devices), or fake:VIDEO")->required();
  capture->add_option("--out", a->out, "new (or empty) folder for NNNNNN.png")->required();
  capture->add_option("--count", a->count, "images to save")->check(CLI::Range(1, 100000))->capture_default_str();
  capture->add_option("--every", a->every_s, "seconds between saved images (move the board meanwhile)")
      ->check(CLI::Range(0.0, 3600.0))
      ->capture_default_str();
  capture->add_option("--size", a->size, "image size asked for, WxH (default 640x480)");
  capture->add_option("--device-fps", a->camera.fps, "frame rate asked for")->check(CLI::Range(1.0, 240.0));
  capture->add_option("--pixel-format", a->camera.format, "auto, yuyv or mjpg")
      ->check(CLI::IsMember({"auto", "yuyv", "mjpg"}));
  capture->callback([a] { Capture(*a); });
}

}  // namespace jgpm::cli
