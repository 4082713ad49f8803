// JSON result files: readable formatting and typed reading with errors that name the file
// and the field. Shared by every file format of ours that is JSON (datasets, later models).
#pragma once

#include <cmath>
#include <cstdint>
#include <limits>
#include <filesystem>
#include <string>
#include <type_traits>
#include <vector>

#include <nlohmann/json.hpp>

#include "io/base/error.h"

namespace jgpm {

// Indented JSON, except that arrays of numbers/strings/booleans stay on one line, so a
// matrix reads as one row per line. Numbers keep full round-trip precision.
std::string FormatJson(const nlohmann::json& value);

// Parses JSON text; InputError naming `source` with the parser's line and column, or the
// number that overflows a double (1e999), otherwise.
nlohmann::json ParseJson(const std::string& text, const std::string& source);
// Reads and parses a JSON file (ReadTextFile, then ParseJson).
nlohmann::json ReadJsonFile(const std::filesystem::path& path, const std::string& what);

// Typed access to fields of a parsed file. `where` prefixes the key in messages, e.g.
// "trials[3]." gives "field 'trials[3].frames' missing".
class JsonReader {
 public:
  explicit JsonReader(std::string source) : source_(std::move(source)) {}

  const nlohmann::json& Field(const nlohmann::json& object, const std::string& key,
                              const std::string& where) const {
    if (!object.is_object() || !object.contains(key)) Fail(where + key, "missing");
    return object.at(key);
  }

  // Numbers must be finite (JSON writers turn NaN into null, which fails as a wrong type),
  // alone or in arrays and arrays of arrays. Integers must be JSON integers that fit the
  // type: nlohmann would convert 1e300 (undefined behaviour) or wrap 4294967297 to 1.
  template <typename T>
  T Get(const nlohmann::json& object, const std::string& key, const std::string& where) const {
    const nlohmann::json& value = Field(object, key, where);
    if constexpr (std::is_integral_v<T> && !std::is_same_v<T, bool>) {
      return Integer<T>(value, where + key);
    } else if constexpr (std::is_same_v<T, std::vector<int>>) {
      if (!value.is_array()) Fail(where + key, std::string("has the wrong type (") + value.type_name() + ")");
      std::vector<int> result;
      for (size_t i = 0; i < value.size(); ++i) result.push_back(Integer<int>(value[i], where + key + "[" + std::to_string(i) + "]"));
      return result;
    }
    try {
      T result = value.get<T>();
      if constexpr (std::is_floating_point_v<T>) {
        if (!std::isfinite(result)) Fail(where + key, "expected a finite number");
      } else if constexpr (std::is_same_v<T, std::vector<double>>) {
        for (double v : result)
          if (!std::isfinite(v)) Fail(where + key, "expected finite numbers");
      } else if constexpr (std::is_same_v<T, std::vector<std::vector<double>>>) {
        for (const std::vector<double>& row : result)
          for (double v : row)
            if (!std::isfinite(v)) Fail(where + key, "expected finite numbers");
      }
      return result;
    } catch (const nlohmann::json::exception&) {
      Fail(where + key, std::string("has the wrong type (") + value.type_name() + ")");
    }
  }

  [[noreturn]] void Fail(const std::string& field, const std::string& what) const {
    ThrowInputError(source_, "field '" + field + "' " + what);
  }

  // A JSON integer that fits T; InputError naming `field` otherwise.
  template <typename T>
  T Integer(const nlohmann::json& value, const std::string& field) const {
    if (value.is_number_unsigned()) {
      const uint64_t u = value.get<uint64_t>();
      if (u <= static_cast<uint64_t>(std::numeric_limits<T>::max())) return static_cast<T>(u);
    } else if (value.is_number_integer()) {
      const int64_t i = value.get<int64_t>();
      if constexpr (std::is_signed_v<T>) {
        if (i >= static_cast<int64_t>(std::numeric_limits<T>::min()) &&
            i <= static_cast<int64_t>(std::numeric_limits<T>::max())) {
          return static_cast<T>(i);
        }
      } else if (i >= 0 && static_cast<uint64_t>(i) <= static_cast<uint64_t>(std::numeric_limits<T>::max())) {
        return static_cast<T>(i);
      }
    } else if (!value.is_number()) {
      Fail(field, std::string("has the wrong type (") + value.type_name() + ")");
    }
    const char* type = std::is_signed_v<T> ? (sizeof(T) == 4 ? "an int" : "a 64-bit integer") : "an unsigned integer";
    Fail(field, std::string("expected an integer that fits ") + type + ", found " + value.dump());
  }

 private:
  std::string source_;
};

}  // namespace jgpm
