// Video files as image sources: frames, times and content against the frames written; and
// the damage a real recording has (a cut file, no frames, a frame that does not decode,
// not a video at all) each found with the file named, before anything is tracked.
#include "io/video/video_file.h"

#include <cstdio>
#include <filesystem>
#include <fstream>

#include <gtest/gtest.h>
#include <opencv2/videoio.hpp>

#include "io/base/error.h"
#include "test_support.h"

namespace jgpm {
namespace {
namespace fs = std::filesystem;

// Frame k is one colour that encodes k.
cv::Scalar Colour(int k) { return cv::Scalar(10 * k % 250, 250 - 10 * k % 250, 128); }

fs::path WriteVideo(const test::TempDir& dir, const std::string& name, int frames, double fps = 25) {
  const fs::path path = dir.path() / name;
  cv::VideoWriter video(path.string(), cv::VideoWriter::fourcc('M', 'J', 'P', 'G'), fps, cv::Size(64, 48));
  EXPECT_TRUE(video.isOpened());
  for (int k = 0; k < frames; ++k) video.write(cv::Mat(48, 64, CV_8UC3, Colour(k)));
  return path;
}

std::string Bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void Put(const fs::path& path, const std::string& bytes) { std::ofstream(path, std::ios::binary) << bytes; }

std::string ErrorOf(const std::string& path) {
  try {
    VideoFileSource source(path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(VideoFile, ReadsEveryFrameWithItsTimeAndContent) {
  test::TempDir dir;
  VideoFileSource source(WriteVideo(dir, "walk.avi", 20).string());
  EXPECT_EQ(source.width(), 64);
  EXPECT_EQ(source.height(), 48);
  EXPECT_DOUBLE_EQ(source.fps(), 25);
  EXPECT_EQ(source.NumFrames(), 20);
  Image image;
  int k = 0;
  while (source.Read(&image)) {
    EXPECT_EQ(image.index, k);
    EXPECT_NEAR(image.time_s, k / 25.0, 1e-6);
    const cv::Scalar mean = cv::mean(image.bgr);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(mean[c], Colour(k)[c], 4) << "frame " << k;
    ++k;
  }
  EXPECT_EQ(k, 20);
  EXPECT_EQ(source.skipped(), 0);
}

TEST(VideoFile, SampleSpreadsOverTheWholeVideo) {
  test::TempDir dir;
  VideoFileSource source(WriteVideo(dir, "walk.avi", 20).string());
  const std::vector<cv::Mat> sample = source.Sample(4);
  ASSERT_EQ(sample.size(), 4u);
  const int expected[] = {2, 7, 12, 17};
  for (int i = 0; i < 4; ++i) EXPECT_NEAR(cv::mean(sample[i])[0], Colour(expected[i])[0], 4);
  Image image;
  ASSERT_TRUE(source.Read(&image));  // reading is not moved by sampling
  EXPECT_EQ(image.index, 0);
}

TEST(VideoFile, TheSampleKeptDuringTheCheckIsTheSampleDecodedAgain) {
  test::TempDir dir;
  const std::string path = WriteVideo(dir, "walk.avi", 23).string();
  VideoFileSource kept(path, 5), decoded(path);
  const std::vector<cv::Mat> a = kept.Sample(5), b = decoded.Sample(5);
  ASSERT_EQ(a.size(), 5u);
  ASSERT_EQ(b.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(cv::norm(a[i], b[i], cv::NORM_INF), 0) << i;
  // Asked again, or for another count: decoded.
  const std::vector<cv::Mat> again = kept.Sample(5), three = kept.Sample(3);
  ASSERT_EQ(again.size(), 5u);
  for (int i = 0; i < 5; ++i) EXPECT_EQ(cv::norm(again[i], b[i], cv::NORM_INF), 0) << i;
  EXPECT_EQ(three.size(), 3u);
}

TEST(VideoFile, AFrameThatDoesNotDecodeIsSkippedAndCounted) {
  test::TempDir dir;
  const fs::path path = WriteVideo(dir, "walk.avi", 20);
  std::string bytes = Bytes(path);
  // Frame 10's JPEG data: the 11th "00dc" chunk of the "movi" list; all of it zeros.
  size_t at = bytes.find("movi");
  for (int k = 0; k <= 10 && at != std::string::npos; ++k) at = bytes.find("00dc", at + 1);
  ASSERT_NE(at, std::string::npos);
  ASSERT_EQ(static_cast<unsigned char>(bytes[at + 8]), 0xFF);
  const uint32_t size = static_cast<unsigned char>(bytes[at + 4]) | static_cast<unsigned char>(bytes[at + 5]) << 8 |
                        static_cast<unsigned char>(bytes[at + 6]) << 16 | static_cast<uint32_t>(static_cast<unsigned char>(bytes[at + 7])) << 24;
  for (uint32_t i = 0; i < size; ++i) bytes[at + 8 + i] = 0;
  Put(path, bytes);
  VideoFileSource source(path.string());
  Image image;
  std::vector<int> read;
  while (source.Read(&image)) {
    read.push_back(image.index);
    EXPECT_NEAR(cv::mean(image.bgr)[0], Colour(image.index)[0], 4) << "frame " << image.index;
  }
  EXPECT_EQ(read.size(), 19u);
  EXPECT_EQ(source.skipped(), 1);
  EXPECT_EQ(std::count(read.begin(), read.end(), 10), 0);
}

TEST(VideoFile, DamagedFilesAreRefusedWithTheirName) {
  test::TempDir dir;
  const fs::path cut = WriteVideo(dir, "cut.avi", 60);
  const std::string bytes = Bytes(cut);
  Put(cut, bytes.substr(0, bytes.size() / 2));
  const std::string cut_error = ErrorOf(cut.string());
  EXPECT_NE(cut_error.find("cut.avi"), std::string::npos) << cut_error;
  EXPECT_NE(cut_error.find("truncated"), std::string::npos) << cut_error;

  const fs::path empty = WriteVideo(dir, "empty.avi", 0);
  const std::string empty_error = ErrorOf(empty.string());
  EXPECT_NE(empty_error.find("empty.avi"), std::string::npos) << empty_error;

  const fs::path text = dir.Write("notes.avi", "not a video\n");
  const std::string text_error = ErrorOf(text.string());
  EXPECT_NE(text_error.find("notes.avi"), std::string::npos) << text_error;

  const std::string missing = ErrorOf((dir.path() / "missing.mp4").string());
  EXPECT_NE(missing.find("no such video file"), std::string::npos) << missing;
  EXPECT_NE(ErrorOf(dir.path().string()).find("no such video file"), std::string::npos);
}

// Checked as it goes (one decoding): the same frames, times and content as after a first
// pass; a cut file is read up to its cut and then refused with its name; a file with no
// frame is refused at once.
TEST(VideoFile, CheckedAsItGoesReadsTheSameAndRefusesACutFileAtItsEnd) {
  test::TempDir dir;
  const std::string path = WriteVideo(dir, "walk.avi", 20).string();
  VideoFileSource first(path), going(path, 0, VideoCheck::kAsItGoes);
  EXPECT_EQ(going.NumFrames(), 20);
  Image a, b;
  int k = 0;
  while (first.Read(&a)) {
    ASSERT_TRUE(going.Read(&b)) << k;
    EXPECT_EQ(a.index, b.index);
    EXPECT_EQ(a.time_s, b.time_s);
    EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_INF), 0) << k;
    ++k;
  }
  EXPECT_FALSE(going.Read(&b));
  EXPECT_EQ(k, 20);

  const fs::path cut = WriteVideo(dir, "cut.avi", 60);
  const std::string bytes = Bytes(cut);
  Put(cut, bytes.substr(0, bytes.size() / 2));
  VideoFileSource cut_going(cut.string(), 0, VideoCheck::kAsItGoes);
  int read = 0;
  try {
    while (cut_going.Read(&b)) ++read;
    ADD_FAILURE() << "the cut file ended without complaint after " << read << " frames";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("cut.avi"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
  }
  EXPECT_GT(read, 10);  // what was there was read first

  const fs::path empty = WriteVideo(dir, "empty.avi", 0);
  EXPECT_THROW(VideoFileSource(empty.string(), 0, VideoCheck::kAsItGoes), InputError);
}

}  // namespace
}  // namespace jgpm
