// The header walk of checkExrHeaderSizes, after the OpenEXR file layout: the magic number
// 20000630, a 4-byte version field (bit 12, 0x1000: multi-part), then per part a list of
// attributes -- name and type name (each NUL-terminated, at most 255 characters), a 4-byte
// little-endian size, the value -- ended by an empty name; a multi-part file ends its list of
// headers with an empty header. OpenEXR 3.1 reads the value of a known type by its structure,
// not by the declared size: a channel list up to its empty channel name, the fixed-size types
// (box2i, v3f, ...) by their size, a float vector in whole floats; the walk does the same, so
// it stays where the library is in a file whose declared sizes are wrong.
#include "core/ExrHeader.h"

#include <algorithm>
#include <cstring>
#include <fstream>

#include <weft/Error.h>

namespace weft {

namespace {

constexpr unsigned char kMagic[4] = {0x76, 0x2f, 0x31, 0x01};
constexpr uint32_t kMultiPart = 0x1000;
constexpr size_t kMaxNameBytes = 256;  // 255 characters and the NUL
constexpr uint64_t kChannelBytes = 16; // pixel type, pLinear + 3 reserved, x and y sampling

// Bytes OpenEXR reads for the value of a fixed-size attribute type; 0 for the others.
uint64_t fixedValueBytes(const std::string& type) {
    static const struct {
        const char* type;
        uint64_t bytes;
    } table[] = {{"box2i", 16},
                 {"box2f", 16},
                 {"chromaticities", 32},
                 {"compression", 1},
                 {"deepImageState", 1},
                 {"double", 8},
                 {"envmap", 1},
                 {"float", 4},
                 {"int", 4},
                 {"keycode", 28},
                 {"lineOrder", 1},
                 {"m33f", 36},
                 {"m33d", 72},
                 {"m44f", 64},
                 {"m44d", 128},
                 {"rational", 8},
                 {"tiledesc", 9},
                 {"timecode", 8},
                 {"v2i", 8},
                 {"v2f", 8},
                 {"v2d", 16},
                 {"v3i", 12},
                 {"v3f", 12},
                 {"v3d", 24}};
    for (const auto& entry : table)
        if (type == entry.type) return entry.bytes;
    return 0;
}

// Reads a NUL-terminated string; false when the file ends or the string is too long first.
bool readName(std::istream& in, uint64_t& pos, std::string& out) {
    out.clear();
    for (size_t i = 0; i < kMaxNameBytes; ++i) {
        const int c = in.get();
        if (c == std::char_traits<char>::eof()) return false;
        ++pos;
        if (c == 0) return true;
        out.push_back(char(c));
    }
    return false;
}

bool readU32(std::istream& in, uint64_t& pos, uint32_t& out) {
    unsigned char b[4];
    if (!in.read(reinterpret_cast<char*>(b), 4)) return false;
    pos += 4;
    out = uint32_t(b[0]) | uint32_t(b[1]) << 8 | uint32_t(b[2]) << 16 | uint32_t(b[3]) << 24;
    return true;
}

bool skip(std::istream& in, uint64_t& pos, uint64_t bytes) {
    if (!in.seekg(std::streamoff(bytes), std::ios::cur)) return false;
    pos += bytes;
    return true;
}

} // namespace

ExrHeaderFacts checkExrHeaderSizes(const std::string& path, uint64_t fileSize) {
    ExrHeaderFacts facts;
    std::ifstream in(path, std::ios::binary);
    unsigned char magic[4];
    uint32_t version = 0;
    uint64_t pos = 0;
    if (!in.read(reinterpret_cast<char*>(magic), 4) || std::memcmp(magic, kMagic, 4) != 0)
        return facts;
    pos = 4;
    if (!readU32(in, pos, version)) return facts;
    const bool multiPart = (version & kMultiPart) != 0;
    std::string name, type, channel;
    for (bool first = true;; first = false) { // headers
        bool empty = true;
        for (;;) { // attributes
            if (!readName(in, pos, name)) return facts;
            if (name.empty()) break;
            empty = false;
            uint32_t size = 0;
            if (!readName(in, pos, type) || !readU32(in, pos, size)) return facts;
            if (int32_t(size) < 0 || size > fileSize - pos)
                throw IoError("EXR '" + path + "': header attribute '" + name + "' (" + type +
                              ") declares " + std::to_string(int32_t(size)) + " bytes, but " +
                              std::to_string(fileSize - pos) + " follow it (corrupt)");
            if (type == "chlist") {
                for (;;) {
                    if (!readName(in, pos, channel)) return facts;
                    if (channel.empty()) break;
                    if (fileSize - pos < kChannelBytes || !skip(in, pos, kChannelBytes))
                        return facts;
                }
                continue;
            }
            if (first && name == "dataWindow" && type == "box2i") {
                uint32_t box[4]; // min x, min y, max x, max y
                for (uint32_t& v : box)
                    if (!readU32(in, pos, v)) return facts;
                facts.haveDataWindow = true;
                facts.width = int64_t(int32_t(box[2])) - int32_t(box[0]) + 1;
                facts.height = int64_t(int32_t(box[3])) - int32_t(box[1]) + 1;
                continue;
            }
            uint64_t bytes = fixedValueBytes(type);
            if (bytes == 0) bytes = type == "floatvector" ? size / 4 * 4 : size;
            if (bytes > fileSize - pos || !skip(in, pos, bytes)) return facts;
        }
        if (!multiPart || empty) return facts;
    }
}

} // namespace weft
