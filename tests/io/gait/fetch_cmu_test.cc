// datasets_scripts/fetch_cmu.sh, run as a new user would: offline (an address nothing
// listens on) and against a local file:// mirror of small synthetic files. Every run writes
// into a temporary folder (JGPM_DATA_OUT), never into the repository's data/.
#include <algorithm>
#include <chrono>
#include <fstream>
#include <set>
#include <sstream>

#include <arpa/inet.h>
#include <gtest/gtest.h>
#include <netinet/in.h>
#include <sys/socket.h>
#include <unistd.h>

#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

struct FetchResult {
  int status = 0;
  std::string out;
  std::string err;
  double seconds = 0;
};

// Runs the script with JGPM_CMU_URL=`url`, JGPM_DATA_OUT=`out` and `arguments`; killed
// after 60 s so that a script that hangs fails the test instead of blocking it.
FetchResult RunFetch(const std::string& url, const fs::path& out, const std::string& arguments = "") {
  const std::string command = "no_proxy='*' JGPM_CMU_URL='" + url + "' JGPM_DATA_OUT='" +
                              out.string() + "' timeout 60 '" JGPM_SOURCE_DIR
                              "/datasets_scripts/fetch_cmu.sh' " + arguments;
  FetchResult r;
  const auto start = std::chrono::steady_clock::now();
  r.status = test::RunCommand(command, &r.out, &r.err);
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// Every path under `root`, relative to it.
std::set<std::string> Tree(const fs::path& root) {
  std::set<std::string> paths;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    paths.insert(fs::relative(entry.path(), root).string());
  }
  return paths;
}

std::string Slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

void ExpectSaysWhereToPutData(const std::string& err) {
  for (const char* place : {"./data/cmu", "$JGPM_DATA", "--data", "../shared/data/cmu"}) {
    EXPECT_NE(err.find(place), std::string::npos) << "lacks " << place << " in: " << err;
  }
}

TEST(FetchCmu, OfflineFailsFastWithOneMessageAndWritesNothing) {
  const test::TempDir dir;
  const FetchResult r = RunFetch("http://127.0.0.1:9", dir.path() / "data" / "cmu");
  EXPECT_NE(r.status, 0);
  EXPECT_LT(r.seconds, 15.0);
  // One message (one line), not one curl error per file.
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("cannot reach http://127.0.0.1:9"), std::string::npos) << r.err;
  ExpectSaysWhereToPutData(r.err);
  // No data/cmu, no data/, no partial download: the folder is as empty as before.
  EXPECT_EQ(Tree(dir.path()), std::set<std::string>{});
}

// A server that accepts the connection and never answers (a stalled site or proxy): the
// connection check gives up after 10 s instead of waiting and retrying.
TEST(FetchCmu, SilentServerFailsWithinFifteenSeconds) {
  const int listener = socket(AF_INET, SOCK_STREAM, 0);
  ASSERT_GE(listener, 0);
  sockaddr_in address{};
  address.sin_family = AF_INET;
  address.sin_addr.s_addr = htonl(INADDR_LOOPBACK);
  address.sin_port = 0;  // any free port
  socklen_t length = sizeof(address);
  ASSERT_EQ(bind(listener, reinterpret_cast<sockaddr*>(&address), sizeof(address)), 0);
  ASSERT_EQ(listen(listener, 16), 0);  // the kernel completes the handshake; nobody reads
  ASSERT_EQ(getsockname(listener, reinterpret_cast<sockaddr*>(&address), &length), 0);
  const test::TempDir dir;
  const FetchResult r =
      RunFetch("http://127.0.0.1:" + std::to_string(ntohs(address.sin_port)), dir.path() / "cmu");
  close(listener);
  EXPECT_NE(r.status, 0);
  EXPECT_LT(r.seconds, 15.0);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  ExpectSaysWhereToPutData(r.err);
  EXPECT_EQ(Tree(dir.path()), std::set<std::string>{});
}

TEST(FetchCmu, OfflineLeavesAnExistingDataRootAsItWas) {
  const test::TempDir dir;
  fs::create_directories(dir.path() / "cmu" / "subjects" / "02");
  dir.Write("cmu/subjects/02/02.asf", "kept\n");
  const FetchResult r = RunFetch("http://127.0.0.1:9", dir.path() / "cmu");
  EXPECT_NE(r.status, 0);
  ExpectSaysWhereToPutData(r.err);
  EXPECT_EQ(Tree(dir.path()), (std::set<std::string>{"cmu", "cmu/subjects", "cmu/subjects/02",
                                                     "cmu/subjects/02/02.asf"}));
  EXPECT_EQ(Slurp(dir.path() / "cmu/subjects/02/02.asf"), "kept\n");
}

// A file:// mirror holding subject 35's skeleton and trials 35_01, 35_02, and a split.
class FetchCmuMirror : public testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_.path() / "mirror/subjects/35");
    dir_.Write("mirror/subjects/35/35.asf", "skeleton 35\n");
    dir_.Write("mirror/subjects/35/35_01.amc", "motion 35_01\n");
    dir_.Write("mirror/subjects/35/35_02.amc", "motion 35_02\n");
    split_ = dir_.Write("split.txt", "# two trials\n35_01\n35_02  # the second\n");
  }
  std::string MirrorUrl() const { return "file://" + (dir_.path() / "mirror").string(); }
  fs::path Out() const { return dir_.path() / "out" / "cmu"; }

  test::TempDir dir_;
  fs::path split_;
};

TEST_F(FetchCmuMirror, DownloadsEveryFileIntoPlace) {
  const FetchResult r = RunFetch(MirrorUrl(), Out(), split_.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(Tree(Out()), (std::set<std::string>{"subjects", "subjects/35", "subjects/35/35.asf",
                                                "subjects/35/35_01.amc", "subjects/35/35_02.amc"}));
  EXPECT_EQ(Slurp(Out() / "subjects/35/35_02.amc"), "motion 35_02\n");
  EXPECT_EQ(Tree(dir_.path() / "out"), (std::set<std::string>{"cmu", "cmu/subjects", "cmu/subjects/35",
                                                              "cmu/subjects/35/35.asf",
                                                              "cmu/subjects/35/35_01.amc",
                                                              "cmu/subjects/35/35_02.amc"}));
}

TEST_F(FetchCmuMirror, MergesIntoAnExistingDataRootKeepingItsFiles) {
  fs::create_directories(Out() / "subjects/35");
  dir_.Write("out/cmu/subjects/35/35.asf", "already here\n");
  const FetchResult r = RunFetch(MirrorUrl(), Out(), split_.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(Slurp(Out() / "subjects/35/35.asf"), "already here\n");
  EXPECT_EQ(Slurp(Out() / "subjects/35/35_01.amc"), "motion 35_01\n");
  EXPECT_EQ(Tree(dir_.path() / "out"), (std::set<std::string>{"cmu", "cmu/subjects", "cmu/subjects/35",
                                                              "cmu/subjects/35/35.asf",
                                                              "cmu/subjects/35/35_01.amc",
                                                              "cmu/subjects/35/35_02.amc"}));
}

TEST_F(FetchCmuMirror, AFileMissingOnTheSiteLeavesNoPartialDataRoot) {
  const fs::path split = dir_.Write("split3.txt", "35_01\n35_02\n35_03\n");  // no 35_03 on the mirror
  const FetchResult r = RunFetch(MirrorUrl(), Out(), split.string());
  EXPECT_NE(r.status, 0);
  EXPECT_NE(r.err.find("35_03.amc"), std::string::npos) << r.err;
  ExpectSaysWhereToPutData(r.err);
  EXPECT_FALSE(fs::exists(dir_.path() / "out")) << "left behind: " << testing::PrintToString(Tree(dir_.path()));
}

}  // namespace
}  // namespace jgpm
