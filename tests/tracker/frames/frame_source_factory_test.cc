// The frame source a command line asks for: exactly one kind of source.
#include "tracker/frames/frame_source_factory.h"

#include <gtest/gtest.h>

#include "io/base/error.h"

namespace jgpm {
namespace {

TEST(MakeFrameSource, AsksForExactlyOneSource) {
  FrameSourceSpec none;
  EXPECT_THROW(MakeFrameSource(none), InputError);
  FrameSourceSpec two;
  two.clip = "a";
  two.images = "b";
  EXPECT_THROW(MakeFrameSource(two), InputError);
}

}  // namespace
}  // namespace jgpm
