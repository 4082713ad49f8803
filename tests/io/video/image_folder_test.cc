// An image folder as an image source: name order, times from the frame rate given, and a
// clear error naming the file for a frame that is not an image or has another size.
#include "io/video/image_folder.h"

#include <gtest/gtest.h>
#include <opencv2/imgcodecs.hpp>

#include "io/base/error.h"
#include "test_support.h"

namespace jgpm {
namespace {
namespace fs = std::filesystem;

void WriteFrame(const test::TempDir& dir, const std::string& name, int value, cv::Size size = {40, 30}) {
  ASSERT_TRUE(cv::imwrite((dir.path() / name).string(), cv::Mat(size, CV_8UC3, cv::Scalar::all(value))));
}

std::string ErrorOf(const fs::path& folder, double fps = 10) {
  try {
    ImageFolderSource source(folder, fps);
    Image image;
    while (source.Read(&image)) {
    }
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(ImageFolder, ReadsTheImagesInNameOrderAtTheGivenRate) {
  test::TempDir dir;
  WriteFrame(dir, "frame_002.png", 30);
  WriteFrame(dir, "frame_000.png", 10);
  WriteFrame(dir, "frame_001.jpg", 20);
  dir.Write("notes.txt", "not a frame, ignored\n");
  ImageFolderSource source(dir.path(), 12.5);
  EXPECT_EQ(source.NumFrames(), 3);
  EXPECT_EQ(source.width(), 40);
  Image image;
  for (int k = 0; k < 3; ++k) {
    ASSERT_TRUE(source.Read(&image));
    EXPECT_EQ(image.index, k);
    EXPECT_DOUBLE_EQ(image.time_s, k / 12.5);
    EXPECT_NEAR(cv::mean(image.bgr)[0], 10 * (k + 1), 2);
  }
  EXPECT_FALSE(source.Read(&image));
  const std::vector<cv::Mat> sample = source.Sample(1);
  ASSERT_EQ(sample.size(), 1u);
  EXPECT_NEAR(cv::mean(sample[0])[0], 20, 2);  // the middle one
}

TEST(ImageFolder, BadFoldersAndFramesAreNamed) {
  test::TempDir dir;
  EXPECT_NE(ErrorOf(dir.path()).find("holds no images"), std::string::npos);
  EXPECT_NE(ErrorOf(dir.path() / "missing").find("no such folder"), std::string::npos);
  WriteFrame(dir, "a.png", 10);
  EXPECT_NE(ErrorOf(dir.path(), 0).find("--fps"), std::string::npos);
  EXPECT_NE(ErrorOf(dir.path(), -1).find("--fps"), std::string::npos);

  WriteFrame(dir, "b.png", 10, {41, 30});
  const std::string mixed = ErrorOf(dir.path());
  EXPECT_NE(mixed.find("b.png"), std::string::npos) << mixed;
  EXPECT_NE(mixed.find("41x30"), std::string::npos) << mixed;
  fs::remove(dir.path() / "b.png");

  dir.Write("c.png", "a text file with an image's name\n");
  const std::string text = ErrorOf(dir.path());
  EXPECT_NE(text.find("c.png"), std::string::npos) << text;
  EXPECT_NE(text.find("not an image"), std::string::npos) << text;
}

}  // namespace
}  // namespace jgpm
