// The `jgpm` command as a whole (tracker/cli/main.cc): every group's subcommands answer
// --help, and bad options give exit 2 with one line.
#include <gtest/gtest.h>

#include "test_support.h"

namespace jgpm {
namespace {

using Result = test::CommandResult;
Result Jgpm(const std::string& arguments) { return test::RunJgpm(arguments); }

TEST(JgpmCli, HelpOnEverySubcommand) {
  for (const char* command : {"", "data", "data info", "data convert", "data cycles", "devices", "capture", "calibrate",
                              "train", "model", "model info", "plot", "plot latent", "eval", "synth", "transition",
                              "render", "track", "bench", "bench track", "bench learning", "bench inducing"}) {
    const Result r = Jgpm(std::string(command) + " --help");
    EXPECT_EQ(r.status, 0) << command << r.err;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << command;
  }
}

TEST(JgpmCli, BadOptionsGiveOneLineAndExit2) {
  for (const char* arguments : {"", "bogus", "data info", "data info x.amc --fps -3",
                                "data convert a.amc", "data cycles --out x.json --poses 1",
                                "data info x.bvh --bvh-unit furlong"}) {
    const Result r = Jgpm(arguments);
    EXPECT_EQ(r.status, 2) << arguments << "\n" << r.err;
    EXPECT_EQ(test::CountLines(r.err), 1) << arguments << "\n" << r.err;
    EXPECT_NE(r.err.find("jgpm: error:"), std::string::npos) << r.err;
  }
}

}  // namespace
}  // namespace jgpm
