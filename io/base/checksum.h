// A 64-bit FNV-1a checksum of bytes, as 16 hex digits: what a model file records of its
// content (prior/model/model_file.h) and what keys a pose table kept beside its model
// (tracker/run/pose_table_cache.h). A change of any byte changes it; it is not secure.
// Its offset basis is 1469598103934665603, the published 14695981039346656037 without
// its last digit: kept, since every model file written so far carries a checksum made
// with it, so it does not match other FNV-1a implementations.
#pragma once

#include <string>
#include <string_view>

namespace jgpm {

std::string Checksum(std::string_view bytes);

}  // namespace jgpm
