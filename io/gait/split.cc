#include "io/gait/split.h"

#include <algorithm>
#include <cctype>
#include <set>

#include "io/base/error.h"
#include "io/base/text_reader.h"

namespace jgpm {
namespace fs = std::filesystem;

bool ParseTrialId(const std::string& text, TrialId* id) {
  const size_t underscore = text.find('_');
  if (underscore == 0 || underscore == std::string::npos || underscore + 1 == text.size()) {
    return false;
  }
  const auto is_digit = [](char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; };
  const auto is_alnum = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) != 0; };
  if (!std::all_of(text.begin(), text.begin() + underscore, is_digit)) return false;
  if (!std::all_of(text.begin() + underscore + 1, text.end(), is_alnum)) return false;
  id->subject = text.substr(0, underscore);
  id->name = text;
  return true;
}

fs::path ResolveSplitPath(const std::string& name_or_path, const fs::path& splits_dir) {
  std::error_code ec;
  if (fs::is_regular_file(name_or_path, ec)) return name_or_path;
  const fs::path named = splits_dir / (name_or_path + ".txt");
  if (name_or_path.find('/') == std::string::npos && fs::is_regular_file(named, ec)) return named;
  std::string known;
  for (const auto& entry : fs::directory_iterator(splits_dir, ec)) {
    if (entry.path().extension() == ".txt") known += " " + entry.path().stem().string();
  }
  ThrowInputError("--split " + name_or_path,
                  "no such split file or named split (named splits in " + splits_dir.string() +
                      ":" + (known.empty() ? " none" : known) + ")");
}

std::vector<TrialId> ParseSplit(std::string_view text, const std::string& source) {
  LineReader in(text, source);
  std::vector<TrialId> ids;
  std::set<std::string> seen;
  while (in.Next()) {
    std::string_view line = in.line();
    line = line.substr(0, line.find('#'));
    const auto tokens = SplitBlanks(line);
    if (tokens.empty()) continue;
    if (tokens.size() > 1) in.Fail("expected one trial id per line, found " + std::to_string(tokens.size()));
    TrialId id;
    if (!ParseTrialId(std::string(tokens[0]), &id)) {
      in.Fail("expected a trial id such as 35_01, found " + Quote(tokens[0]));
    }
    if (!seen.insert(id.name).second) in.Fail("trial " + id.name + " is listed twice");
    ids.push_back(id);
  }
  if (ids.empty()) ThrowInputError(source, "lists no trials");
  return ids;
}

std::vector<TrialId> ReadSplit(const fs::path& path) {
  return ParseSplit(ReadTextFile(path, "a split (one trial id such as 35_01 per line)"),
                    path.string());
}

fs::path TrialAsfPath(const fs::path& root, const TrialId& id) {
  return root / "subjects" / id.subject / (id.subject + ".asf");
}

fs::path TrialAmcPath(const fs::path& root, const TrialId& id) {
  return root / "subjects" / id.subject / (id.name + ".amc");
}

}  // namespace jgpm
