// Each camera's overlay video (the estimate drawn over the image, track_output.h's
// OverlayFrame), drawn and encoded on a thread of its own as the frames are tracked: on
// a 4-camera 320x240 clip the drawing and MJPG encoding were an eighth of the tracking
// loop's wall time, done while the tracker's threads waited. At most `depth` frames wait
// to be written; a tracker faster than the encoder waits for it rather than hold the whole
// video in memory.
#pragma once

#include <condition_variable>
#include <deque>
#include <exception>
#include <functional>
#include <utility>
#include <filesystem>
#include <mutex>
#include <thread>
#include <vector>

#include <opencv2/videoio.hpp>

#include "calibration/camera.h"
#include "io/mocap/skeleton.h"
#include "tracker/body/body_model.h"
#include "tracker/filter/tracker.h"
#include "tracker/frames/frame_source.h"
#include "tracker/run/track_output.h"

namespace jgpm {

class OverlayVideos {
 public:
  // DIR/overlay_<camera>.avi for each camera, at `fps`. InputError naming the file when
  // OpenCV cannot write one. `body` and `skeleton` must outlive this.
  OverlayVideos(const std::filesystem::path& dir, const std::vector<Camera>& cameras, double fps,
                const BodyModel& body, const Skeleton& skeleton, int depth = 4);
  // Finishes the videos (Close), swallowing a writing error: call Close to see it.
  ~OverlayVideos();
  OverlayVideos(const OverlayVideos&) = delete;
  OverlayVideos& operator=(const OverlayVideos&) = delete;

  // The frame's images with the estimate over them (a dropped frame: the last image,
  // dimmed), written in the background.
  void Add(const Frame& frame, const TrackedFrame& estimate);
  // The same, drawn now and returned (to show them), written in the background.
  std::vector<cv::Mat> AddAndDraw(const Frame& frame, const TrackedFrame& estimate);
  // Several people, each drawn with its own body (`body_of(id)`; track_output.h's
  // OverlayPeopleFrame). Drawn now and returned when `draw_now`.
  std::vector<cv::Mat> AddPeople(const Frame& frame, const std::vector<std::pair<int, TrackedFrame>>& people,
                                 const std::function<const BodyModel&(int)>& body_of, bool draw_now = false);
  // Writes what waits and closes the videos; rethrows a writing error.
  void Close();

 private:
  struct Job {
    std::vector<cv::Mat> images;  // per camera, what to draw on; drawn already when `drawn`
    bool dimmed = false;
    bool drawn = false;
    TrackedFrame estimate;
    std::vector<Capsule> capsules;
    bool several = false;               // people (AddPeople), else the one estimate
    std::vector<OverlayPerson> people;
  };
  Job MakeJob(const Frame& frame, const TrackedFrame& estimate);
  void Draw(Job* job) const;
  void Push(Job job);
  void Run();

  const std::vector<Camera> cameras_;
  const BodyModel& body_;
  const Skeleton& skeleton_;
  const size_t depth_;
  std::vector<cv::VideoWriter> videos_;
  std::vector<cv::Mat> last_;  // per camera, the last image (for dropped frames)

  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Job> jobs_;
  bool closing_ = false;
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace jgpm
