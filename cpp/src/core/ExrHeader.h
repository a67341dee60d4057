#pragma once
// A check of an OpenEXR file's header before the OpenEXR library reads it.
#include <cstdint>
#include <string>

namespace weft {

/// What checkExrHeaderSizes saw of the first part's header.
struct ExrHeaderFacts {
    bool haveDataWindow = false;   ///< a box2i "dataWindow" attribute was read
    int64_t width = 0, height = 0; ///< of the data window (max - min + 1; may be <= 0)
};

/// Walks the header attributes of the EXR file `path` (`fileSize` bytes; every part of a
/// multi-part file) the way OpenEXR 3.1's reader steps through them and throws IoError naming
/// the file when an attribute declares a negative size or more bytes than the file has left.
/// OpenEXR allocates an attribute of unknown type at its declared size before reading it: a
/// 400-byte file could make it reserve 2 GiB. Files that are not EXR, or whose header ends or
/// goes wrong in another way, are left to OpenEXR, which refuses them. Returns the data window
/// (OpenEXR sizes its line buffers by it when it opens the file, so the caller can check it
/// first).
ExrHeaderFacts checkExrHeaderSizes(const std::string& path, uint64_t fileSize);

} // namespace weft
