// Live capture against a scripted fake camera (io/video/fake_v4l2_device.h): what a camera can
// answer (no capture, no streaming, another size, MJPG only, fewer buffers, busy, no USB
// bandwidth), how frames arrive (not ready yet, several at once, gaps in the sequence,
// damaged, unplugged part-way) and real time with a slow reader. The oracles: the images
// given to the fake, the sequence numbers it used, the errno it was told to give. Then
// the real kernel for what needs no camera (a missing path, a regular file, a FIFO), and
// a real camera only when JGPM_TEST_V4L2_DEVICE names one.
#include "io/video/v4l2_camera.h"

#include <sys/stat.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <thread>

#include <gtest/gtest.h>
#include <opencv2/imgproc.hpp>

#include "io/base/error.h"
#include "io/video/fake_v4l2_device.h"
#include "test_support.h"

namespace jgpm {
namespace {

const std::string kPath = "/dev/video-fake";

// Frame k: a colour that encodes k over a horizontal ramp (so chroma and luma vary).
cv::Mat FrameImage(int k, int width = 640, int height = 480) {
  cv::Mat image(height, width, CV_8UC3);
  for (int v = 0; v < height; ++v)
    for (int u = 0; u < width; ++u) image.at<cv::Vec3b>(v, u) = cv::Vec3b((k * 20) % 250, u * 200 / width, 180 - k % 10);
  return image;
}
int KOf(const cv::Mat& bgr) { return static_cast<int>(std::lround(cv::mean(bgr)[0] / 20)); }

double MeanAbsDiff(const cv::Mat& a, const cv::Mat& b) {
  cv::Mat d;
  cv::absdiff(a, b, d);
  const cv::Scalar m = cv::mean(d);
  return (m[0] + m[1] + m[2]) / 3;
}

// The error of opening a camera and starting it streaming.
std::string ErrorOf(const std::shared_ptr<V4l2Api>& api, const V4l2Options& options = {}, const std::string& path = kPath) {
  try {
    V4l2Camera camera(path, options, api);
    camera.Start();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(V4l2Camera, NegotiatesYuyvAndDecodesWhatTheCameraSaw) {
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  V4l2Camera camera(kPath, {}, fake);
  EXPECT_EQ(camera.width(), 640);
  EXPECT_EQ(camera.height(), 480);
  EXPECT_EQ(fake->pixel_format(), V4L2_PIX_FMT_YUYV);
  EXPECT_EQ(camera.buffers(), 4);
  EXPECT_FALSE(fake->streaming());  // until the first Read
  EXPECT_NE(camera.negotiation().find("gives 640x480 YUYV at 30 fps"), std::string::npos) << camera.negotiation();
  camera.Start();
  EXPECT_TRUE(fake->streaming());
  Image image;
  for (int k = 0; k < 3; ++k) {
    fake->Capture(FrameImage(k), k);
    ASSERT_TRUE(camera.Read(&image));
    EXPECT_EQ(image.index, k);
    EXPECT_LT(MeanAbsDiff(image.bgr, FrameImage(k)), 3) << "frame " << k;
  }
  EXPECT_EQ(camera.skipped(), 0);
}

TEST(V4l2Camera, MjpgWhenItIsAllTheCameraOffers) {
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  fake->formats = {V4L2_PIX_FMT_MJPEG};
  V4l2Camera camera(kPath, {}, fake);
  camera.Start();
  EXPECT_EQ(fake->pixel_format(), V4L2_PIX_FMT_MJPEG);
  fake->Capture(FrameImage(4), 0);
  Image image;
  ASSERT_TRUE(camera.Read(&image));
  EXPECT_LT(MeanAbsDiff(image.bgr, FrameImage(4)), 4);

  auto neither = std::make_shared<FakeV4l2Device>(kPath);
  neither->formats = {V4L2_PIX_FMT_RGB24};
  const std::string e = ErrorOf(neither);
  EXPECT_NE(e.find("offers RGB3"), std::string::npos) << e;
  V4l2Options yuyv;
  yuyv.format = "yuyv";
  auto mjpg_only = std::make_shared<FakeV4l2Device>(kPath);
  mjpg_only->formats = {V4L2_PIX_FMT_MJPEG};
  EXPECT_NE(ErrorOf(mjpg_only, yuyv).find("does not offer YUYV"), std::string::npos);
}

TEST(V4l2Camera, TakesTheSizeAndRateTheDeviceGives) {
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  fake->forced_width = 320;
  fake->forced_height = 240;
  fake->device_fps = 15;
  V4l2Camera camera(kPath, {}, fake);
  camera.Start();
  EXPECT_EQ(camera.width(), 320);
  EXPECT_EQ(camera.height(), 240);
  EXPECT_DOUBLE_EQ(camera.fps(), 15);
  EXPECT_NE(camera.negotiation().find("asked 640x480 YUYV at 30 fps"), std::string::npos) << camera.negotiation();
  EXPECT_NE(camera.negotiation().find("gives 320x240 YUYV at 15 fps"), std::string::npos) << camera.negotiation();
  fake->Capture(FrameImage(1, 320, 240), 0);
  Image image;
  ASSERT_TRUE(camera.Read(&image));
  EXPECT_EQ(image.bgr.cols, 320);
}

TEST(V4l2Camera, RefusesWhatIsNotAStreamingCaptureDevice) {
  auto no_capture = std::make_shared<FakeV4l2Device>(kPath);
  no_capture->capabilities = V4L2_CAP_META_CAPTURE | V4L2_CAP_STREAMING;
  EXPECT_NE(ErrorOf(no_capture).find("not a video capture device"), std::string::npos);
  auto no_streaming = std::make_shared<FakeV4l2Device>(kPath);
  no_streaming->capabilities = V4L2_CAP_VIDEO_CAPTURE | V4L2_CAP_READWRITE;
  EXPECT_NE(ErrorOf(no_streaming).find("cannot stream"), std::string::npos);
  auto not_v4l2 = std::make_shared<FakeV4l2Device>(kPath);
  not_v4l2->fail[VIDIOC_QUERYCAP] = ENOTTY;
  EXPECT_NE(ErrorOf(not_v4l2).find("not a V4L2 device"), std::string::npos);
  EXPECT_NE(ErrorOf(not_v4l2, {}, "/dev/video-none").find("no such device"), std::string::npos);
}

TEST(V4l2Camera, WorksWithFewerBuffersThanAskedButNotWithOne) {
  auto two = std::make_shared<FakeV4l2Device>(kPath);
  two->granted_buffers = 2;
  V4l2Camera camera(kPath, {}, two);
  camera.Start();
  EXPECT_EQ(camera.buffers(), 2);
  two->Capture(FrameImage(2), 0);
  Image image;
  EXPECT_TRUE(camera.Read(&image));
  auto one = std::make_shared<FakeV4l2Device>(kPath);
  one->granted_buffers = 1;
  EXPECT_NE(ErrorOf(one).find("granted 1 streaming buffer"), std::string::npos);
}

TEST(V4l2Camera, BusyAndBandwidthHaveTheirOwnMessages) {
  auto busy_open = std::make_shared<FakeV4l2Device>(kPath);
  busy_open->open_errno = EBUSY;
  EXPECT_NE(ErrorOf(busy_open).find("is busy: another program is using it"), std::string::npos);
  for (const unsigned long request : {VIDIOC_S_FMT, VIDIOC_REQBUFS, VIDIOC_STREAMON}) {
    auto busy = std::make_shared<FakeV4l2Device>(kPath);
    busy->fail[request] = EBUSY;
    EXPECT_NE(ErrorOf(busy).find("is busy"), std::string::npos) << request;
  }
  auto bandwidth = std::make_shared<FakeV4l2Device>(kPath);
  bandwidth->fail[VIDIOC_STREAMON] = ENOSPC;
  const std::string e = ErrorOf(bandwidth);
  EXPECT_NE(e.find("not enough USB bandwidth"), std::string::npos) << e;
  EXPECT_EQ(bandwidth->streaming(), false);
}

TEST(V4l2Camera, WaitsWhenNothingIsReadyYet) {
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  V4l2Camera camera(kPath, {}, fake);
  camera.Start();
  int polls = 0;
  fake->before_poll = [&polls](FakeV4l2Device& d) {
    ++polls;
    if (polls < 3) d.spurious_wakeups = 1;  // "ready", then DQBUF says EAGAIN
    if (polls == 3) d.Capture(FrameImage(5), 0);
  };
  Image image;
  ASSERT_TRUE(camera.Read(&image));
  EXPECT_EQ(polls, 3);
  EXPECT_EQ(KOf(image.bgr), KOf(FrameImage(5)));
  fake->before_poll = nullptr;
  EXPECT_THROW(camera.Read(&image), InputError);  // nothing comes: the timeout
}

TEST(V4l2Camera, CountsGapsInTheSequenceAndTakesTheNewestFrame) {
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  V4l2Camera camera(kPath, {}, fake);
  camera.Start();
  Image image;
  fake->Capture(FrameImage(0), 0);
  ASSERT_TRUE(camera.Read(&image));
  fake->Capture(FrameImage(1), 1);
  ASSERT_TRUE(camera.Read(&image));
  fake->Capture(FrameImage(5), 5);  // the driver lost 2, 3, 4
  ASSERT_TRUE(camera.Read(&image));
  EXPECT_EQ(image.index, 5);
  EXPECT_EQ(camera.dropped(), 3);
  // Three frames ready at once: the newest is taken, the two older ones are dropped and
  // their buffers given back (four more frames then fit the four buffers).
  for (int k = 6; k <= 8; ++k) fake->Capture(FrameImage(k), k);
  ASSERT_TRUE(camera.Read(&image));
  EXPECT_EQ(image.index, 8);
  EXPECT_EQ(KOf(image.bgr), KOf(FrameImage(8)));
  EXPECT_EQ(camera.dropped(), 5);
  for (int k = 9; k <= 12; ++k) fake->Capture(FrameImage(k), k);
  ASSERT_TRUE(camera.Read(&image));
  EXPECT_EQ(image.index, 12);
  EXPECT_EQ(camera.dropped(), 8);
  EXPECT_EQ(camera.skipped(), 8);
}

TEST(V4l2Camera, SkipsDamagedFrames) {
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  V4l2Camera camera(kPath, {}, fake);
  camera.Start();
  fake->Capture(FrameImage(0), 0, /*damaged=*/true);
  fake->before_poll = [](FakeV4l2Device& d) {
    if (d.captured() == 1) d.Capture(FrameImage(1), 1);
  };
  Image image;
  ASSERT_TRUE(camera.Read(&image));
  EXPECT_EQ(image.index, 1);
  EXPECT_EQ(camera.undecodable(), 1);
}

TEST(V4l2Camera, SkipsFramesThatDoNotDecode) {
  // A corrupt MJPG frame and a YUYV frame cut short are counted and passed over.
  auto mjpg = std::make_shared<FakeV4l2Device>(kPath);
  mjpg->formats = {V4L2_PIX_FMT_MJPEG};
  V4l2Camera camera(kPath, {}, mjpg);
  camera.Start();
  mjpg->CaptureBytes(std::vector<uint8_t>(5000, 0x5A), 0);
  int polls = 0;
  mjpg->before_poll = [&polls](FakeV4l2Device& d) {
    if (++polls == 2) d.Capture(FrameImage(3), 1);  // after the corrupt one was taken
  };
  Image image;
  ASSERT_TRUE(camera.Read(&image));
  EXPECT_EQ(image.index, 1);
  EXPECT_EQ(camera.undecodable(), 1);

  auto yuyv = std::make_shared<FakeV4l2Device>(kPath);
  V4l2Camera short_frames(kPath, {}, yuyv);
  short_frames.Start();
  yuyv->CaptureBytes(std::vector<uint8_t>(640 * 2 * 100, 128), 0);  // 100 of 480 rows
  polls = 0;
  yuyv->before_poll = [&polls](FakeV4l2Device& d) {
    if (++polls == 2) d.Capture(FrameImage(4), 1);
  };
  ASSERT_TRUE(short_frames.Read(&image));
  EXPECT_EQ(KOf(image.bgr), KOf(FrameImage(4)));
  EXPECT_EQ(short_frames.undecodable(), 1);
}

TEST(V4l2Camera, RefusesBadOptions) {
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  V4l2Options zero_fps;
  zero_fps.fps = 0;
  EXPECT_NE(ErrorOf(fake, zero_fps).find("frame rate"), std::string::npos);
  V4l2Options one_buffer;
  one_buffer.buffers = 1;
  EXPECT_NE(ErrorOf(fake, one_buffer).find("buffers"), std::string::npos);
}

TEST(V4l2Camera, UnpluggingEndsTheStreamCleanly) {
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  V4l2Camera camera(kPath, {}, fake);
  camera.Start();
  Image image;
  for (int k = 0; k < 2; ++k) {
    fake->Capture(FrameImage(k), k);
    ASSERT_TRUE(camera.Read(&image));
  }
  fake->Unplug();
  EXPECT_FALSE(camera.Read(&image));
  EXPECT_NE(camera.end_reason().find("went away"), std::string::npos) << camera.end_reason();
  EXPECT_NE(camera.end_reason().find("after 2 frames"), std::string::npos) << camera.end_reason();
  EXPECT_FALSE(camera.Read(&image));  // and stays ended
}

TEST(V4l2Camera, InRealTimeASlowReaderGetsTheNewestFramesAndCountsTheRest) {
  // 30 frames at 30 frames/s; the reader takes 70 ms a frame, about two frame periods.
  // However loaded the machine, each frame handed out is the newest in any buffer, and
  // every earlier frame is either handed out or counted as dropped.
  auto fake = std::make_shared<FakeV4l2Device>(kPath);
  fake->forced_width = 320;  // light, so that a sanitized build on a busy machine keeps up
  fake->forced_height = 240;
  int given = 0;
  fake->Play([&given](cv::Mat* frame) {
    if (given == 30) return false;
    *frame = FrameImage(given++, 320, 240);
    return true;
  }, 30);
  V4l2Camera camera(kPath, {}, fake);
  Image image;
  int delivered = 0, last = -1;
  while (camera.Read(&image)) {
    ++delivered;
    EXPECT_EQ(image.index, fake->last_filled()) << "not the newest frame";
    EXPECT_EQ(KOf(image.bgr), KOf(FrameImage(image.index, 320, 240))) << "frame " << image.index;
    EXPECT_GT(image.index, last);
    last = image.index;
    EXPECT_GE(image.latency_ms, 0);
    std::this_thread::sleep_for(std::chrono::milliseconds(70));
  }
  std::printf("real time: %d of 30 frames delivered, %d dropped; %s\n", delivered, camera.dropped(), camera.end_reason().c_str());
  EXPECT_GE(delivered, 3);
  EXPECT_LE(delivered, 17);  // a reader at 70 ms cannot see more than about half
  // Frames seen after the last one handed out (as the camera went away) count as dropped.
  EXPECT_GE(delivered + camera.dropped(), last + 1);
  EXPECT_LE(delivered + camera.dropped(), fake->captured());
  EXPECT_NE(camera.end_reason().find("went away"), std::string::npos);
}

TEST(V4l2Camera, OnTheRealKernelNonDevicesGiveOneClearError) {
  auto api = std::make_shared<LibV4l2Api>();
  test::TempDir dir;
  const std::string missing = ErrorOf(api, {}, (dir.path() / "video9").string());
  EXPECT_NE(missing.find("no such device"), std::string::npos) << missing;
  const std::string file = ErrorOf(api, {}, dir.Write("video0", "not a device").string());
  EXPECT_NE(file.find("is a regular file, not a video device"), std::string::npos) << file;
  const std::string fifo_path = (dir.path() / "fifo").string();
  ASSERT_EQ(mkfifo(fifo_path.c_str(), 0600), 0);
  const std::string fifo = ErrorOf(api, {}, fifo_path);  // must not block on the FIFO
  EXPECT_NE(fifo.find("is a FIFO, not a video device"), std::string::npos) << fifo;
}

TEST(V4l2Camera, ARealCameraWhenOneIsNamed) {
  const char* device = std::getenv("JGPM_TEST_V4L2_DEVICE");
  if (!device || !*device) GTEST_SKIP() << "set JGPM_TEST_V4L2_DEVICE=/dev/videoN to test a real camera";
  V4l2Camera camera(device, {}, std::make_shared<LibV4l2Api>());
  std::printf("%s\n", camera.negotiation().c_str());
  Image image;
  for (int k = 0; k < 10; ++k) {
    ASSERT_TRUE(camera.Read(&image));
    EXPECT_EQ(image.bgr.cols, camera.width());
    EXPECT_EQ(image.bgr.type(), CV_8UC3);
  }
}

TEST(ListV4l2Devices, ListsVideoNodesInNumberOrder) {
  test::TempDir dir;
  for (const char* name : {"video10", "video2", "video0", "videoX", "audio1"}) dir.Write(name, "");
  FakeV4l2Device fake((dir.path() / "video2").string());
  const std::vector<V4l2DeviceInfo> devices = ListV4l2Devices(fake, dir.path().string());
  ASSERT_EQ(devices.size(), 3u);
  EXPECT_EQ(devices[0].path, (dir.path() / "video0").string());
  EXPECT_EQ(devices[1].path, (dir.path() / "video2").string());
  EXPECT_EQ(devices[2].path, (dir.path() / "video10").string());
  EXPECT_FALSE(devices[0].error.empty());
  EXPECT_EQ(devices[1].driver, "jgpm-fake");
  EXPECT_TRUE(devices[1].capture);
  ASSERT_EQ(devices[1].formats.size(), 2u);
  EXPECT_EQ(devices[1].formats[0], "YUYV 640x480 320x240");
  test::TempDir empty;
  EXPECT_TRUE(ListV4l2Devices(fake, empty.path().string()).empty());
}

}  // namespace
}  // namespace jgpm
