// Error tiers (see README "Errors"):
//  - InputError: bad input from outside (files, options, devices). The message says where
//    (file:line or option) and what was expected; the `jgpm` command prints it on one line
//    and exits non-zero.
//  - JGPM_CHECK: an internal invariant. A failure is a bug; it aborts with file:line.
#pragma once

#include <stdexcept>
#include <string>

namespace jgpm {

class InputError : public std::runtime_error {
 public:
  explicit InputError(const std::string& message) : std::runtime_error(message) {}
};

// Throws InputError("<where>: <what>").
[[noreturn]] void ThrowInputError(const std::string& where, const std::string& what);

[[noreturn]] void CheckFailed(const char* condition, const char* file, int line);

}  // namespace jgpm

#define JGPM_CHECK(condition) \
  ((condition) ? static_cast<void>(0) : ::jgpm::CheckFailed(#condition, __FILE__, __LINE__))
