#include "btf/ZipArchive.h"

#include <weft/Error.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>

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
    int code = 0;
    mArchive = zip_open(path.c_str(), ZIP_RDONLY | ZIP_CHECKCONS, &code);
    if (!mArchive) throw IoError("cannot open zip '" + path + "': " + zipErrorText(code));
    const zip_int64_t count = zip_get_num_entries(mArchive, 0);
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

std::vector<uint8_t> ZipReader::read(size_t index) const {
    const std::string& name = mNames.at(index);
    zip_stat_t st;
    zip_stat_init(&st);
    if (zip_stat_index(mArchive, mIndex[index], 0, &st) != 0 || !(st.valid & ZIP_STAT_SIZE))
        throw IoError("cannot stat '" + name + "' in zip '" + mPath + "'");
    if (st.size > (uint64_t(1) << 31))
        throw IoError("entry '" + name + "' in zip '" + mPath + "' is implausibly large");
    zip_file_t* file = zip_fopen_index(mArchive, mIndex[index], 0);
    if (!file)
        throw IoError("cannot open '" + name + "' in zip '" + mPath + "': " +
                      zip_strerror(mArchive));
    std::vector<uint8_t> data(static_cast<size_t>(st.size));
    const zip_int64_t got = data.empty() ? 0 : zip_fread(file, data.data(), st.size);
    std::string error = got < 0 ? zip_file_strerror(file) : "";
    zip_fclose(file);
    if (got < 0 || uint64_t(got) != st.size)
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
    void* copy = std::malloc(data.empty() ? 1 : data.size());
    if (!copy) throw IoError("out of memory adding '" + name + "' to zip '" + mPath + "'");
    if (!data.empty()) std::memcpy(copy, data.data(), data.size());
    zip_source_t* source = zip_source_buffer(mArchive, copy, data.size(), 1);
    if (!source) {
        std::free(copy);
        throw IoError("cannot add '" + name + "' to zip '" + mPath + "'");
    }
    const zip_int64_t index = zip_file_add(mArchive, name.c_str(), source, ZIP_FL_ENC_UTF_8);
    if (index < 0) {
        zip_source_free(source);
        throw IoError("cannot add '" + name + "' to zip '" + mPath + "': " +
                      zip_strerror(mArchive));
    }
    zip_set_file_compression(mArchive, zip_uint64_t(index),
                             deflate ? ZIP_CM_DEFLATE : ZIP_CM_STORE, 0);
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
