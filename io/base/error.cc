#include "io/base/error.h"

#include <cstdio>
#include <cstdlib>

namespace jgpm {

void ThrowInputError(const std::string& where, const std::string& what) {
  throw InputError(where.empty() ? what : where + ": " + what);
}

void CheckFailed(const char* condition, const char* file, int line) {
  std::fprintf(stderr, "jgpm internal error: check '%s' failed at %s:%d\n", condition, file, line);
  std::abort();
}

}  // namespace jgpm
