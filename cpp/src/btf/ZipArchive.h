#pragma once
// Minimal zip access through libzip: list and read entries, or build an archive from buffers.
#include <cstdint>
#include <string>
#include <vector>

struct zip;

namespace weft {

/// Most entries a zip may list (a full Bonn BTF has 6561 images): more is refused on opening,
/// before any name is read.
constexpr uint64_t kMaxZipEntries = 100000;

class ZipReader {
public:
    /// Throws IoError when the file is missing or not a zip archive.
    explicit ZipReader(const std::string& path);
    ~ZipReader();
    ZipReader(const ZipReader&) = delete;
    ZipReader& operator=(const ZipReader&) = delete;

    /// Entry names (directories excluded), by index.
    const std::vector<std::string>& names() const { return mNames; }
    /// Uncompressed size the archive declares for an entry, checked before anything is inflated:
    /// throws IoError when it exceeds `limit`, or when the declared sizes are impossible for the
    /// archive (compressed data larger than the file, more than deflate's ~1032:1 ratio, a stored
    /// entry whose two sizes differ).
    uint64_t checkedSize(size_t index, uint64_t limit) const;
    /// Whole entry (at most `limit` bytes, see checkedSize), inflated into a buffer of the
    /// declared size; throws IoError when it cannot be inflated (corrupt, truncated) or when it
    /// inflates to more bytes than it declares (the extra bytes are never stored).
    std::vector<uint8_t> read(size_t index, uint64_t limit) const;

private:
    std::string mPath;
    uint64_t mFileSize = 0;
    zip* mArchive = nullptr;
    std::vector<std::string> mNames;
    std::vector<uint64_t> mIndex;
};

class ZipWriter {
public:
    explicit ZipWriter(const std::string& path);
    ~ZipWriter();
    ZipWriter(const ZipWriter&) = delete;
    ZipWriter& operator=(const ZipWriter&) = delete;

    /// Stores `data` as `name` (already compressed data such as JPEG is stored, not deflated).
    void add(const std::string& name, const std::vector<uint8_t>& data, bool deflate);
    /// Writes the archive; throws IoError on failure (the partial file is removed).
    void close();

private:
    std::string mPath;
    zip* mArchive = nullptr;
};

} // namespace weft
