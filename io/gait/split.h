// Named train/test splits: small text files of CMU trial ids ("35_01"), one per line, '#'
// starts a comment. Named splits live in datasets_scripts/splits/<name>.txt.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace jgpm {

struct TrialId {
  std::string subject;  // "35"
  std::string name;     // "35_01"
};

// "35_01" -> {35, 35_01}; false unless it is <digits>_<letters or digits>.
bool ParseTrialId(const std::string& text, TrialId* id);

// `name_or_path` is a file path if such a file exists, else the name of a split in
// `splits_dir` (".txt" added). InputError when neither exists (listing the named splits).
std::filesystem::path ResolveSplitPath(const std::string& name_or_path,
                                       const std::filesystem::path& splits_dir);

// Trial ids of a split's text; `source` names it in errors. InputError (source:line) for
// a malformed or repeated id, or when it lists none.
std::vector<TrialId> ParseSplit(std::string_view text, const std::string& source);
// ParseSplit of a file's text.
std::vector<TrialId> ReadSplit(const std::filesystem::path& path);

// Files of a trial under a data root (CMU layout).
std::filesystem::path TrialAsfPath(const std::filesystem::path& root, const TrialId& id);
std::filesystem::path TrialAmcPath(const std::filesystem::path& root, const TrialId& id);

}  // namespace jgpm
