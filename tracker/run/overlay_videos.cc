#include "tracker/run/overlay_videos.h"

#include <algorithm>

#include "io/base/error.h"
#include "tracker/run/track_output.h"

namespace jgpm {

OverlayVideos::OverlayVideos(const std::filesystem::path& dir, const std::vector<Camera>& cameras, double fps,
                             const BodyModel& body, const Skeleton& skeleton, int depth)
    : cameras_(cameras), body_(body), skeleton_(skeleton), depth_(static_cast<size_t>(std::max(1, depth))),
      last_(cameras.size()) {
  for (const Camera& camera : cameras_) {
    const std::filesystem::path path = dir / ("overlay_" + camera.name + ".avi");
    videos_.emplace_back(path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps,
                         cv::Size(camera.width, camera.height));
    if (!videos_.back().isOpened()) ThrowInputError(path.string(), "OpenCV cannot write an MJPG video here");
  }
  thread_ = std::thread([this] { Run(); });
}

OverlayVideos::~OverlayVideos() {
  try {
    Close();
  } catch (...) {
  }
}

OverlayVideos::Job OverlayVideos::MakeJob(const Frame& frame, const TrackedFrame& estimate) {
  Job job;
  job.estimate = estimate;
  if (estimate.state.size()) body_.Place(estimate.joints_mm, estimate.size * estimate.width, estimate.build.widths, estimate.build.garment, &job.capsules);
  job.dimmed = frame.dropped;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    if (!frame.dropped && c < frame.images.size()) last_[c] = frame.images[c];
    job.images.push_back(last_[c]);
  }
  return job;
}

void OverlayVideos::Draw(Job* job) const {
  if (job->drawn) return;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    const cv::Mat image = job->dimmed && !job->images[c].empty() ? cv::Mat(job->images[c] * 0.5) : job->images[c];
    job->images[c] = job->several ? OverlayPeopleFrame(image, cameras_[c], job->estimate.index, job->people, skeleton_)
                                  : OverlayFrame(image, cameras_[c], job->estimate, job->capsules, skeleton_);
  }
  job->drawn = true;
}

void OverlayVideos::Push(Job job) {
  std::unique_lock<std::mutex> lock(mutex_);
  changed_.wait(lock, [this] { return jobs_.size() < depth_ || error_; });
  if (error_) std::rethrow_exception(error_);
  jobs_.push_back(std::move(job));
  lock.unlock();
  changed_.notify_all();
}

void OverlayVideos::Add(const Frame& frame, const TrackedFrame& estimate) { Push(MakeJob(frame, estimate)); }

std::vector<cv::Mat> OverlayVideos::AddAndDraw(const Frame& frame, const TrackedFrame& estimate) {
  Job job = MakeJob(frame, estimate);
  Draw(&job);
  std::vector<cv::Mat> shown = job.images;
  Push(std::move(job));
  return shown;
}

std::vector<cv::Mat> OverlayVideos::AddPeople(const Frame& frame,
                                              const std::vector<std::pair<int, TrackedFrame>>& people,
                                              const std::function<const BodyModel&(int)>& body_of, bool draw_now) {
  TrackedFrame index;
  index.index = frame.index;
  Job job = MakeJob(frame, index);
  job.several = true;
  for (const auto& [id, estimate] : people) {
    OverlayPerson p{id, estimate, {}};
    if (estimate.state.size())
      body_of(id).Place(estimate.joints_mm, estimate.size * estimate.width, estimate.build.widths, estimate.build.garment, &p.capsules);
    job.people.push_back(std::move(p));
  }
  std::vector<cv::Mat> shown;
  if (draw_now) {
    Draw(&job);
    shown = job.images;
  }
  Push(std::move(job));
  return shown;
}

void OverlayVideos::Run() {
  for (;;) {
    Job job;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [this] { return !jobs_.empty() || closing_; });
      if (jobs_.empty()) return;
      job = std::move(jobs_.front());
    }
    try {
      Draw(&job);
      for (size_t c = 0; c < cameras_.size(); ++c) videos_[c].write(job.images[c]);
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      jobs_.clear();
      changed_.notify_all();
      return;
    }
    {
      std::lock_guard<std::mutex> lock(mutex_);
      jobs_.pop_front();
    }
    changed_.notify_all();
  }
}

void OverlayVideos::Close() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    closing_ = true;
  }
  changed_.notify_all();
  if (thread_.joinable()) thread_.join();
  for (cv::VideoWriter& video : videos_) video.release();
  if (error_) std::rethrow_exception(error_);
}

}  // namespace jgpm
