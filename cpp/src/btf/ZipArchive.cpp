#include "btf/ZipArchive.h"

#include <weft/Error.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <new>

#include <zip.h>

namespace weft {

namespace {

std::string zipErrorText(int code) {
    zip_error_t error;
    zip_error_init_with_code(&error, code);
    std::string text = zip_error_strerror(&error);
    zip_error_fini(&error);
    return text;
}

} // namespace

ZipReader::ZipReader(const std::string& path) : mPath(path) {
    std::error_code ec;
    mFileSize = uint64_t(std::filesystem::file_size(path, ec));
    if (ec) throw IoError("cannot open zip '" + path + "': " + ec.message());
    int code = 0;
    mArchive = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &code);
    if (!mArchive) throw IoError("cannot open zip '" + path + "': " + zipErrorText(code));
    const zip_int64_t count = zip_get_num_entries(mArchive, 0);
    if (count < 0 || uint64_t(count) > kMaxZipEntries) {
        zip_discard(mArchive);
        mArchive = nullptr;
        throw IoError("zip '" + path + "' lists " + std::to_string(count) +
                      " entries, more than the " + std::to_string(kMaxZipEntries) +
                      " a BTF zip may have");
    }
    for (zip_int64_t i = 0; i < count; ++i) {
        const char* name = zip_get_name(mArchive, zip_uint64_t(i), 0);
        if (!name) continue;
        std::string s(name);
        if (s.empty() || s.back() == '/') continue;
        mNames.push_back(s);
        mIndex.push_back(uint64_t(i));
    }
}

ZipReader::~ZipReader() {
    if (mArchive) zip_discard(mArchive);
}

uint64_t ZipReader::checkedSize(size_t index, uint64_t limit) const {
    const std::string& name = mNames.at(index);
    const std::string where = "'" + name + "' in zip '" + mPath + "'";
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(mArchive, mIndex[index], 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
        throw IoError("cannot stat " + where);
    if (st.valid & ZIP_STAT_COMP_SIZE) {
        if (st.comp_size > mFileSize)
            throw IoError(where + " declares " + std::to_string(st.comp_size) +
                          " compressed bytes in a " + std::to_string(mFileSize) +
                          "-byte archive (corrupt)");
        const bool method = (st.valid & ZIP_STAT_COMP_METHOD) != 0;
        if (method && st.comp_method == ZIP_CM_STORE && st.size != st.comp_size)
            throw IoError(where + " is stored uncompressed but declares two different sizes "
                                  "(corrupt)");
        // Deflate cannot do better than about 1032:1.
        if (method && st.comp_method == ZIP_CM_DEFLATE && st.size > 1100 * st.comp_size + 4096)
            throw IoError(where + " declares " + std::to_string(st.size) + " bytes from " +
                          std::to_string(st.comp_size) +
                          " deflated bytes, impossible for deflate (corrupt)");
    }
    if (st.size > limit)
        throw IoError(where + " declares " + std::to_string(st.size) +
                      " bytes uncompressed, more than the " + std::to_string(limit) +
                      " a BTF image may have (a zip bomb or not a BTF)");
    return st.size;
}

std::vector<uint8_t> ZipReader::read(size_t index, uint64_t limit) const {
    const std::string& name = mNames.at(index);
    const uint64_t size = checkedSize(index, limit);
    zip_file_t* file = zip_fopen_index(mArchive, mIndex[index], 0);
    if (!file)
        throw IoError("cannot open '" + name + "' in zip '" + mPath +
                      "': " + zip_strerror(mArchive));
    std::vector<uint8_t> data;
    try {
        data.resize(static_cast<size_t>(size));
    } catch (const std::bad_alloc&) {
        zip_fclose(file);
        throw IoError("out of memory reading '" + name + "' (" + std::to_string(size) +
                      " bytes) in zip '" + mPath + "'");
    }
    const zip_int64_t got = data.empty() ? 0 : zip_fread(file, data.data(), size);
    // One byte more than declared means the entry lies about its size: refuse it rather than
    // trusting either number.
    uint8_t extra = 0;
    const zip_int64_t more = got < 0 || uint64_t(got) != size ? 0 : zip_fread(file, &extra, 1);
    std::string error = got < 0 || more < 0 ? zip_file_strerror(file) : "";
    zip_fclose(file);
    if (more > 0)
        throw IoError("'" + name + "' in zip '" + mPath + "' inflates to more than the " +
                      std::to_string(size) + " bytes it declares (corrupt or a zip bomb)");
    if (got < 0 || more < 0 || uint64_t(got) != size)
        throw IoError("cannot read '" + name + "' in zip '" + mPath + "' (truncated or corrupt)" +
                      (error.empty() ? "" : ": " + error));
    return data;
}

ZipWriter::ZipWriter(const std::string& path) : mPath(path) {
    int code = 0;
    mArchive = zip_open(path.c_str(), ZIP_CREATE | ZIP_TRUNCATE, &code);
    if (!mArchive) throw IoError("cannot create zip '" + path + "': " + zipErrorText(code));
}

ZipWriter::~ZipWriter() {
    if (mArchive) zip_discard(mArchive);
}

void ZipWriter::add(const std::string& name, const std::vector<uint8_t>& data, bool deflate) {
    // An empty entry gets no buffer: libzip keeps no data pointer for length 0 and so would
    // never free one it was asked to own (a 1-byte leak per empty entry, found by fuzz.btftree).
    void* copy = data.empty() ? nullptr : std::malloc(data.size());
    if (!data.empty() && !copy)
        throw IoError("out of memory adding '" + name + "' to zip '" + mPath + "'");
    if (copy) std::memcpy(copy, data.data(), data.size());
    zip_source_t* source = zip_source_buffer(mArchive, copy, data.size(), copy ? 1 : 0);
    if (!source) {
        std::free(copy);
        throw IoError("cannot add '" + name + "' to zip '" + mPath + "'");
    }
    const zip_int64_t index = zip_file_add(mArchive, name.c_str(), source, ZIP_FL_ENC_UTF_8);
    if (index < 0) {
        zip_source_free(source);
        throw IoError("cannot add '" + name + "' to zip '" + mPath +
                      "': " + zip_strerror(mArchive));
    }
    zip_set_file_compression(mArchive, zip_uint64_t(index), deflate ? ZIP_CM_DEFLATE : ZIP_CM_STORE,
                             0);
}

void ZipWriter::close() {
    if (zip_close(mArchive) != 0) {
        const std::string error = zip_strerror(mArchive);
        zip_discard(mArchive);
        mArchive = nullptr;
        std::remove(mPath.c_str());
        throw IoError("cannot write zip '" + mPath + "': " + error);
    }
    mArchive = nullptr;
}

} // namespace weft
