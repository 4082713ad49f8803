// Reading an enum value back from the name its naming function gives it, e.g.
//   ParseByName(text, {Task::kA, Task::kB}, ValidationTaskName, &task)
// so every named enum parses with the same loop.
#pragma once

#include <string_view>
#include <vector>

namespace jgpm {

// Sets *value to the element of `values` that `name_of` calls `name`; false (value
// untouched) when none is.
template <typename Enum, typename NameOf>
bool ParseByName(std::string_view name, const std::vector<Enum>& values, NameOf name_of, Enum* value) {
  for (Enum v : values) {
    if (name_of(v) == name) {
      *value = v;
      return true;
    }
  }
  return false;
}

}  // namespace jgpm
