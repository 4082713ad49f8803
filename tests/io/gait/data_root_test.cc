#include "io/gait/data_root.h"

#include <cstdlib>

#include <gtest/gtest.h>
#include <unistd.h>

#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;
using test::ExpectInputError;

// Runs in a scratch working directory with $JGPM_DATA unset; restores both.
class DataRootTest : public testing::Test {
 protected:
  void SetUp() override {
    previous_cwd_ = fs::current_path();
    if (const char* env = std::getenv("JGPM_DATA")) previous_env_ = env;
    unsetenv("JGPM_DATA");
    fs::create_directories(dir_.path() / "work");
    fs::current_path(dir_.path() / "work");
  }
  void TearDown() override {
    fs::current_path(previous_cwd_);
    if (previous_env_) setenv("JGPM_DATA", previous_env_->c_str(), 1);
  }
  // A data root holding one subject's skeleton (the search does not read it).
  fs::path MakeRoot(const fs::path& relative) {
    fs::create_directories(dir_.path() / relative / "subjects" / "02");
    dir_.Write((relative / "subjects" / "02" / "02.asf").string(), ":version 1.10\n");
    return dir_.path() / relative;
  }
  // The CMU layout without data: an empty subjects/, as an interrupted download left it.
  fs::path MakeEmptyRoot(const fs::path& relative) {
    fs::create_directories(dir_.path() / relative / "subjects");
    return dir_.path() / relative;
  }

  test::TempDir dir_;
  fs::path previous_cwd_;
  std::optional<std::string> previous_env_;
};

TEST_F(DataRootTest, NothingFoundListsEveryPlaceTried) {
  ExpectInputError([] { ResolveDataRoot(std::nullopt); },
                   {"--data (not given)", "$JGPM_DATA (not set)", "./data/cmu", "../shared/data/cmu",
                    "fetch_cmu.sh"});
}

TEST_F(DataRootTest, FallsBackInOrder) {
  MakeRoot("shared/data/cmu");  // ../shared/data/cmu from work/
  EXPECT_EQ(ResolveDataRoot(std::nullopt), fs::path("../shared/data/cmu"));
  MakeRoot("work/data/cmu");
  EXPECT_EQ(ResolveDataRoot(std::nullopt), fs::path("data/cmu"));
  const fs::path env = MakeRoot("env");
  setenv("JGPM_DATA", env.c_str(), 1);
  EXPECT_EQ(ResolveDataRoot(std::nullopt), env);
  const fs::path flag = MakeRoot("flag");
  EXPECT_EQ(ResolveDataRoot(flag.string()), flag);
}

TEST_F(DataRootTest, ExplicitChoicesMustHoldData) {
  MakeRoot("work/data/cmu");
  ExpectInputError([&] { ResolveDataRoot((dir_.path() / "empty").string()); }, {"--data", "empty", "no subjects/"});
  setenv("JGPM_DATA", "/nonexistent/x", 1);
  ExpectInputError([] { ResolveDataRoot(std::nullopt); }, {"$JGPM_DATA=/nonexistent/x", "no subjects/"});
}

TEST_F(DataRootTest, EmptyLayoutDoesNotShadowTheNextPlace) {
  MakeRoot("shared/data/cmu");
  MakeEmptyRoot("work/data/cmu");
  EXPECT_EQ(ResolveDataRoot(std::nullopt), fs::path("../shared/data/cmu"));
  // Subject folders without a skeleton (half a download) are no data either.
  fs::create_directories(dir_.path() / "work/data/cmu/subjects/35");
  dir_.Write("work/data/cmu/subjects/35/35_01.amc", "1\n");
  dir_.Write("work/data/cmu/subjects/35/35.asf.part", "");
  fs::create_directories(dir_.path() / "work/data/cmu/subjects/39/39.asf");  // a folder, not a file
  EXPECT_EQ(ResolveDataRoot(std::nullopt), fs::path("../shared/data/cmu"));
  dir_.Write("work/data/cmu/subjects/35/35.asf", ":version 1.10\n");
  EXPECT_EQ(ResolveDataRoot(std::nullopt), fs::path("data/cmu"));
}

TEST_F(DataRootTest, OnlyEmptyLayoutsListEveryPlaceTried) {
  MakeEmptyRoot("work/data/cmu");
  MakeEmptyRoot("shared/data/cmu");
  ExpectInputError([] { ResolveDataRoot(std::nullopt); },
                   {"--data (not given)", "$JGPM_DATA (not set)", "./data/cmu (exists, no subjects/NN/NN.asf)",
                    "../shared/data/cmu (exists, no subjects/NN/NN.asf)", "fetch_cmu.sh"});
}

TEST_F(DataRootTest, ExplicitEmptyLayoutIsRefusedNamingIt) {
  MakeRoot("work/data/cmu");  // a usable default must not be taken instead
  const fs::path empty = MakeEmptyRoot("empty_layout");
  fs::create_directories(empty / "subjects" / "02");
  ExpectInputError([&] { ResolveDataRoot(empty.string()); },
                   {"--data " + empty.string(), "no subjects/NN/ folder with an .asf skeleton"});
  setenv("JGPM_DATA", empty.c_str(), 1);
  ExpectInputError([] { ResolveDataRoot(std::nullopt); },
                   {"$JGPM_DATA=" + empty.string(), "no subjects/NN/ folder with an .asf skeleton"});
}

}  // namespace
}  // namespace jgpm
