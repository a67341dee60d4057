#include <weft/HairIo.h>

#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "core/FileRead.h"
#include <weft/Error.h>

namespace weft {

namespace {

constexpr size_t kHeaderBytes = 128;
constexpr uint32_t kSegments = 1, kPoints = 2, kThickness = 4, kTransparency = 8, kColors = 16;
constexpr uint32_t kKnownFlags = kSegments | kPoints | kThickness | kTransparency | kColors;

uint32_t readU32(const uint8_t* p) {
    return uint32_t(p[0]) | uint32_t(p[1]) << 8 | uint32_t(p[2]) << 16 | uint32_t(p[3]) << 24;
}

float readF32(const uint8_t* p) {
    const uint32_t bits = readU32(p);
    float f;
    std::memcpy(&f, &bits, 4);
    return f;
}

void writeU32(std::vector<uint8_t>& out, uint32_t v) {
    for (int i = 0; i < 4; ++i) out.push_back(uint8_t(v >> (8 * i)));
}

void writeF32(std::vector<uint8_t>& out, float f) {
    uint32_t bits;
    std::memcpy(&bits, &f, 4);
    writeU32(out, bits);
}

std::string hexString(uint32_t v) {
    char buf[16];
    std::snprintf(buf, sizeof buf, "0x%x", v);
    return buf;
}

glm::vec3 fromZUp(const glm::vec3& p) { return {p.x, p.z, -p.y}; }
glm::vec3 toZUp(const glm::vec3& p) { return {p.x, -p.z, p.y}; }

// Reads consecutive little-endian arrays, every size checked against what is left.
class Reader {
public:
    Reader(const uint8_t* data, size_t size, const std::string& name)
        : mData(data), mSize(size), mName(name) {}

    const uint8_t* take(uint64_t count, uint64_t elementBytes, const char* what) {
        // count < 2^32 and elementBytes <= 12, so the product fits in 64 bits.
        const uint64_t bytes = count * elementBytes;
        if (bytes > mSize - mPos)
            throw IoError(mName + ": truncated .hair file: the " + what + " array needs " +
                          std::to_string(bytes) + " bytes at offset " + std::to_string(mPos) +
                          " but the file has " + std::to_string(mSize) + " bytes");
        const uint8_t* p = mData + mPos;
        mPos += size_t(bytes);
        return p;
    }
    size_t position() const { return mPos; }
    void skipTo(size_t pos) { mPos = pos; }

private:
    const uint8_t* mData;
    size_t mSize;
    size_t mPos = 0;
    const std::string& mName;
};

std::vector<float> readFloats(Reader& r, uint64_t count, const char* what) {
    const uint8_t* p = r.take(count, 4, what);
    std::vector<float> out(static_cast<size_t>(count));
    for (size_t i = 0; i < out.size(); ++i) out[i] = readF32(p + 4 * i);
    return out;
}

std::vector<glm::vec3> readVec3s(Reader& r, uint64_t count, const char* what) {
    const uint8_t* p = r.take(count, 12, what);
    std::vector<glm::vec3> out(static_cast<size_t>(count));
    for (size_t i = 0; i < out.size(); ++i)
        out[i] = {readF32(p + 12 * i), readF32(p + 12 * i + 4), readF32(p + 12 * i + 8)};
    return out;
}

} // namespace

HairStrands parseHair(const uint8_t* data, size_t size, bool zUp, const std::string& name) {
    if (size < kHeaderBytes)
        throw IoError(name + ": not a .hair file: " + std::to_string(size) +
                      " bytes, shorter than the 128-byte header");
    if (std::memcmp(data, "HAIR", 4) != 0)
        throw IoError(name + ": not a .hair file: the signature is not 'HAIR'");
    const uint64_t hairCount = readU32(data + 4);
    const uint64_t pointCount = readU32(data + 8);
    const uint32_t flags = readU32(data + 12);
    HairStrands h;
    h.defaultSegments = readU32(data + 16);
    h.defaultThickness = readF32(data + 20);
    h.defaultTransparency = readF32(data + 24);
    h.defaultColor = {readF32(data + 28), readF32(data + 32), readF32(data + 36)};
    const char* info = reinterpret_cast<const char*>(data + 40);
    h.info.assign(info, strnlen(info, 88));
    for (char& c : h.info)
        if (c < 32 || c > 126) c = '?';

    if (!(flags & kPoints)) throw IoError(name + ": .hair file without a points array");
    if (flags & ~kKnownFlags)
        h.warnings.push_back("unknown array flag bits " + hexString(flags & ~kKnownFlags) +
                             " ignored");
    if (hairCount == 0) throw IoError(name + ": .hair file with no strands");

    Reader r(data, size, name);
    r.skipTo(kHeaderBytes);
    if (flags & kSegments) {
        const uint8_t* p = r.take(hairCount, 2, "segments");
        h.segments.resize(size_t(hairCount));
        uint64_t sum = 0;
        for (size_t i = 0; i < h.segments.size(); ++i) {
            h.segments[i] = uint16_t(p[2 * i] | p[2 * i + 1] << 8);
            sum += uint64_t(h.segments[i]) + 1;
        }
        if (sum != pointCount)
            throw IoError(name + ": inconsistent .hair file: the segments add up to " +
                          std::to_string(sum) + " points, the header says " +
                          std::to_string(pointCount));
    } else {
        const uint64_t per = uint64_t(h.defaultSegments) + 1;
        if (pointCount % hairCount != 0 || pointCount / hairCount != per)
            throw IoError(name + ": inconsistent .hair file: " + std::to_string(hairCount) +
                          " strands of " + std::to_string(per) + " points (default segments) " +
                          "are not the " + std::to_string(pointCount) + " points in the header");
    }
    h.points = readVec3s(r, pointCount, "points");
    if (flags & kThickness) h.thickness = readFloats(r, pointCount, "thickness");
    if (flags & kTransparency) h.transparency = readFloats(r, pointCount, "transparency");
    if (flags & kColors) h.colors = readVec3s(r, pointCount, "colours");
    if (r.position() < size)
        h.warnings.push_back(std::to_string(size - r.position()) + " trailing bytes ignored");
    try {
        h.validate();
    } catch (const InvalidArgument& e) {
        throw IoError(name + ": corrupt .hair file: " + e.what());
    }
    if (zUp)
        for (glm::vec3& p : h.points) p = fromZUp(p);
    return h;
}

HairStrands loadHair(const std::string& path, bool zUp) {
    const std::vector<uint8_t> bytes = readInputFile(path, ".hair file");
    return parseHair(bytes.data(), bytes.size(), zUp, path);
}

std::vector<uint8_t> serializeHair(const HairStrands& h, bool zUp) {
    h.validate();
    if (h.points.size() > UINT32_MAX || h.strandCount() > UINT32_MAX)
        throw InvalidArgument("hair: too many points or strands for a .hair file (2^32 - 1)");
    uint32_t flags = kPoints;
    if (!h.segments.empty()) flags |= kSegments;
    if (!h.thickness.empty()) flags |= kThickness;
    if (!h.transparency.empty()) flags |= kTransparency;
    if (!h.colors.empty()) flags |= kColors;
    std::vector<uint8_t> out;
    out.reserve(kHeaderBytes + h.points.size() * 32 + h.segments.size() * 2);
    out.insert(out.end(), {'H', 'A', 'I', 'R'});
    writeU32(out, uint32_t(h.strandCount()));
    writeU32(out, uint32_t(h.points.size()));
    writeU32(out, flags);
    writeU32(out, h.defaultSegments);
    writeF32(out, h.defaultThickness);
    writeF32(out, h.defaultTransparency);
    for (int i = 0; i < 3; ++i) writeF32(out, h.defaultColor[i]);
    char info[88] = {};
    std::memcpy(info, h.info.data(), h.info.size());
    out.insert(out.end(), info, info + 88);
    for (uint16_t s : h.segments) {
        out.push_back(uint8_t(s));
        out.push_back(uint8_t(s >> 8));
    }
    for (const glm::vec3& p : h.points) {
        const glm::vec3 q = zUp ? toZUp(p) : p;
        for (int i = 0; i < 3; ++i) writeF32(out, q[i]);
    }
    for (float t : h.thickness) writeF32(out, t);
    for (float a : h.transparency) writeF32(out, a);
    for (const glm::vec3& c : h.colors)
        for (int i = 0; i < 3; ++i) writeF32(out, c[i]);
    return out;
}

void saveHair(const std::string& path, const HairStrands& strands, bool zUp) {
    const std::vector<uint8_t> bytes = serializeHair(strands, zUp);
    std::ofstream f(path, std::ios::binary);
    if (!f) throw IoError("cannot create .hair file '" + path + "'");
    f.write(reinterpret_cast<const char*>(bytes.data()), std::streamsize(bytes.size()));
    if (!f) throw IoError("cannot write .hair file '" + path + "'");
}

} // namespace weft
