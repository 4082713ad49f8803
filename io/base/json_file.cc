#include "io/base/json_file.h"

#include "io/base/text_reader.h"

namespace jgpm {
namespace {

bool IsFlat(const nlohmann::json& array) {
  for (const auto& element : array) {
    if (element.is_structured()) return false;
  }
  return true;
}

void Format(const nlohmann::json& value, int depth, std::string* out) {
  const std::string indent(static_cast<size_t>(depth + 1), ' ');
  const std::string closing(static_cast<size_t>(depth), ' ');
  if (value.is_object() && !value.empty()) {
    *out += "{\n";
    size_t i = 0;
    for (const auto& [key, element] : value.items()) {
      *out += indent + nlohmann::json(key).dump() + ": ";
      Format(element, depth + 1, out);
      *out += ++i < value.size() ? ",\n" : "\n";
    }
    *out += closing + "}";
  } else if (value.is_array() && !value.empty() && !IsFlat(value)) {
    *out += "[\n";
    for (size_t i = 0; i < value.size(); ++i) {
      *out += indent;
      Format(value[i], depth + 1, out);
      *out += i + 1 < value.size() ? ",\n" : "\n";
    }
    *out += closing + "]";
  } else {
    *out += value.dump();
  }
}

}  // namespace

std::string FormatJson(const nlohmann::json& value) {
  std::string out;
  Format(value, 0, &out);
  return out + "\n";
}

nlohmann::json ParseJson(const std::string& text, const std::string& source) {
  try {
    return nlohmann::json::parse(text);
  } catch (const nlohmann::json::exception& e) {  // parse_error, and out_of_range for 1e999
    ThrowInputError(source, std::string("invalid JSON: ") + e.what());
  }
}

nlohmann::json ReadJsonFile(const std::filesystem::path& path, const std::string& what) {
  return ParseJson(ReadTextFile(path, what), path.string());
}

}  // namespace jgpm
