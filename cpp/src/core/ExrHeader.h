#pragma once
// A check of an OpenEXR file's header before the OpenEXR library reads it.
#include <cstdint>
#include <string>

namespace weft {

/// Walks the header attributes of the EXR file `path` (`fileSize` bytes; every part of a
/// multi-part file) the way OpenEXR 3.1's reader steps through them and throws IoError naming
/// the file when an attribute declares a negative size or more bytes than the file has left.
/// OpenEXR allocates an attribute of unknown type at its declared size before reading it: a
/// 400-byte file could make it reserve 2 GiB. Files that are not EXR, or whose header ends or
/// goes wrong in another way, are left to OpenEXR, which refuses them.
void checkExrHeaderSizes(const std::string& path, uint64_t fileSize);

} // namespace weft
