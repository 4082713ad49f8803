// The checksum against values computed by hand (Python, the same recurrence): FNV-1a's
// prime and xor-multiply, from the offset basis the project has always used.
#include "io/base/checksum.h"

#include <gtest/gtest.h>

namespace jgpm {
namespace {

TEST(Checksum, IsTheRecordedFnv1aVariant) {
  EXPECT_EQ(Checksum(""), "14650fb0739d0383");
  EXPECT_EQ(Checksum("a"), "44bd8ad473cd9906");
  EXPECT_EQ(Checksum("foobar"), "88fad7c0a8ff07f2");
  EXPECT_EQ(Checksum(std::string("\0", 1)), "44bd2bd473ccf799");  // NUL counts
}

}  // namespace
}  // namespace jgpm
