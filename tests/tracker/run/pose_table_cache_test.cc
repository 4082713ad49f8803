// The pose table kept beside its model file: the first call builds and keeps it, the
// second reads it (the file untouched, the table bit for bit the one built); a model file
// that changed, or other options, build it again and replace the file; a damaged file is
// said and rebuilt; a folder that cannot hold the file still gives the table.
#include "tracker/run/pose_table_cache.h"

#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "prior/model/model_file.h"
#include "prior/prior_test_support.h"
#include "test_support.h"

namespace jgpm {
namespace {

namespace fs = std::filesystem;

std::string ReadBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(PoseTableCache, KeepsTheTableAndRebuildsWhenTheModelOrOptionsChange) {
  test::TempDir dir;
  const auto model = test::TrainOnSyntheticWalks(ModelKind::kMljgpmTorus);
  const fs::path path = dir.path() / "model.json";
  WriteModelFile(path, *model);
  PoseTableOptions options;
  options.phase_nodes = 16;
  options.nodes_per_gait = 3;
  std::vector<std::string> notes;
  const auto note = [&notes](const std::string& text) { notes.push_back(text); };

  const fs::path kept = PoseTableCachePath(path.string());
  EXPECT_EQ(kept, dir.path() / "model.json.table");
  EXPECT_EQ(ReadKeptPoseTable(path.string(), "", options, note), nullptr);  // none kept yet
  const auto built = CachedPoseTable(*model, path.string(), "", options, note);
  ASSERT_TRUE(fs::exists(kept));
  // Read without the model (while it is parsed), then fitted to it.
  std::unique_ptr<PoseTable> alone = ReadKeptPoseTable(path.string(), "", options, note);
  ASSERT_TRUE(alone);
  EXPECT_EQ(alone->Serialize("k"), built->Serialize("k"));
  EXPECT_EQ(CachedPoseTable(*model, path.string(), "", options, note, std::move(alone))->Serialize("k"),
            built->Serialize("k"));
  const std::string bytes = ReadBytes(kept);
  const auto time = fs::last_write_time(kept);
  const auto read = CachedPoseTable(*model, path.string(), "", options, note);
  EXPECT_EQ(fs::last_write_time(kept), time);  // read, not rebuilt
  EXPECT_EQ(read->Serialize("k"), built->Serialize("k"));
  EXPECT_TRUE(notes.empty());

  // Other options: another table, and the file replaced.
  options.phase_nodes = 20;
  EXPECT_EQ(ReadKeptPoseTable(path.string(), "", options, note), nullptr);  // another key
  const auto other = CachedPoseTable(*model, path.string(), "", options, note);
  EXPECT_NE(other->Serialize("k"), built->Serialize("k"));
  EXPECT_NE(ReadBytes(kept), bytes);
  options.phase_nodes = 16;
  CachedPoseTable(*model, path.string(), "", options, note);
  EXPECT_EQ(ReadBytes(kept), bytes);  // back as it was

  // The model file changed (retrained: here one more byte): not the kept table's model.
  {
    std::ofstream more(path, std::ios::app);
    more << ' ';
  }
  CachedPoseTable(*model, path.string(), "", options, note);
  EXPECT_NE(ReadBytes(kept), bytes);
  EXPECT_TRUE(notes.empty());

  // Damaged: said, and rebuilt.
  fs::resize_file(kept, fs::file_size(kept) / 2);
  const auto again = CachedPoseTable(*model, path.string(), "", options, note);
  EXPECT_EQ(again->Serialize("k"), built->Serialize("k"));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("model.json.table"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("truncated"), std::string::npos) << notes[0];

  // Cannot be kept (a folder of that name): said, and the table given all the same.
  notes.clear();
  fs::remove(kept);
  fs::create_directories(kept);
  const auto unkept = CachedPoseTable(*model, path.string(), "", options, note);
  EXPECT_EQ(unkept->Serialize("k"), built->Serialize("k"));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("not kept"), std::string::npos) << notes[0];
}

}  // namespace
}  // namespace jgpm
