// A foreground mask's blobs with the pieces of one body joined: a blob above another,
// overlapping it by half the narrower one's width, with a gap under a tenth of their joint
// height (an occluder across the body, a belt of the background's colour, a reflection in
// the floor broken where it meets the feet) is the same body. Used by the person locator
// (tracker/filter/person_locator.h) and the floor-reflection cut (floor_reflection.h).
#pragma once

#include <vector>

#include <opencv2/core/mat.hpp>

namespace jgpm {

// A standing adult's height, mm: the mean of men and women together, and about one
// standard deviation either way. Whom a blob can be (the person locator, the floor
// reflection's cut) rests on it.
constexpr double kAdultHeightMm = 1700, kAdultSpreadMm = 100;

// `labels`: CV_32S, 0 background, 1..n-1 the joined blobs; areas and boxes per label
// (index 0 unused). Returns n.
int BodyBlobs(const cv::Mat& mask, cv::Mat* labels, std::vector<int>* areas, std::vector<cv::Rect>* boxes);

}  // namespace jgpm
