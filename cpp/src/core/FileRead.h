#pragma once
// Reading input files without trusting them: only regular files (not a directory, a device such
// as /dev/zero, or a pipe, which never end or never start), no larger than a stated limit that
// is checked before anything is allocated. Every loader opens its files through these.
#include <cstdint>
#include <string>
#include <vector>

namespace weft {

/// The largest input file any loader reads whole (4 GiB).
constexpr uint64_t kMaxInputFileBytes = uint64_t(4) << 30;

/// Throws IoError naming `what` and `path` unless `path` is a readable regular file of at most
/// `maxBytes`; returns its size in bytes.
uint64_t checkInputFile(const std::string& path, const std::string& what,
                        uint64_t maxBytes = kMaxInputFileBytes);

/// The bytes of the regular file `path` (checked as checkInputFile does).
std::vector<uint8_t> readInputFile(const std::string& path, const std::string& what,
                                   uint64_t maxBytes = kMaxInputFileBytes);

} // namespace weft
