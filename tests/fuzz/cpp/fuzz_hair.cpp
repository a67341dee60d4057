// libFuzzer target: the input is the bytes of a .hair file (weft::parseHair, what loadHair and
// weft.load_hair / hair_from_bytes parse). A file that parses must be valid strands, and writing
// them back must give a file that parses to the same strands.
#include <cstring>

#include <weft/HairIo.h>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    weft::fuzz::expectResultOrWeftError([&] {
        const bool zUp = size > 0 && (data[size - 1] & 1); // both orientations, from the input
        const weft::HairStrands h = weft::parseHair(data, size, zUp, "fuzz.hair");
        try {
            h.validate();
        } catch (const weft::Error& e) {
            weft::fuzz::finding(std::string("parsed strands fail validate(): ") + e.what());
        }
        std::vector<uint8_t> bytes;
        weft::HairStrands back;
        try {
            bytes = weft::serializeHair(h, zUp);
            back = weft::parseHair(bytes.data(), bytes.size(), zUp, "round trip");
        } catch (const weft::Error& e) {
            weft::fuzz::finding(std::string("parsed strands do not round-trip: ") + e.what());
        }
        if (back.points.size() != h.points.size() || back.segments != h.segments ||
            back.thickness != h.thickness || back.transparency != h.transparency ||
            back.colors.size() != h.colors.size() || back.info != h.info)
            weft::fuzz::finding("round trip changed the strands' arrays");
        // The Z-up rotation (x, y, z) -> (x, z, -y) and its inverse are exact in float.
        if (std::memcmp(back.points.data(), h.points.data(), h.points.size() * sizeof(h.points[0])))
            weft::fuzz::finding("round trip changed the points");
    });
    return 0;
}
