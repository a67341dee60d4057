#pragma once
// Reading and writing Cem Yuksel's .hair files (shared/formats/hair.md).
#include <cstdint>
#include <string>
#include <vector>

#include <weft/HairStrands.h>

namespace weft {

/// Parses the bytes of a .hair file. Every count is checked against the size (64-bit
/// arithmetic, no overflow); inconsistent segment sums, a missing points array, non-finite or
/// out-of-range values and truncation throw IoError naming `name`. Unknown flag bits and
/// trailing bytes are tolerated and reported in `warnings`. `zUp`: the file is Z-up (as the
/// public models are); points are rotated to weft's Y-up, (x, y, z) -> (x, z, -y).
HairStrands parseHair(const uint8_t* data, size_t size, bool zUp = false,
                      const std::string& name = "<memory>");
/// Reads and parses a file; IoError if it cannot be read.
HairStrands loadHair(const std::string& path, bool zUp = false);

/// The .hair bytes of `strands` (validated first): only the arrays the strands hold are
/// written, segments only when per-strand counts are present. `zUp` writes Z-up points,
/// (x, y, z) -> (x, -z, y), the inverse of the loader's rotation.
std::vector<uint8_t> serializeHair(const HairStrands& strands, bool zUp = false);
/// Writes serializeHair() to `path`; IoError if the file cannot be written.
void saveHair(const std::string& path, const HairStrands& strands, bool zUp = false);

} // namespace weft
