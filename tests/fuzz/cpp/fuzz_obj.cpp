// libFuzzer target: an OBJ file with its material library, read by weft::loadObjParts
// (weft.load_obj_parts) and weft::loadObj (weft.load_obj). The input up to a line "#mtl" is the
// OBJ (in.obj), the rest the file "m.mtl" beside it (seeds say `mtllib m.mtl`); a valid 2x2 PNG
// "t.png" lies there too for map_Kd. Every part must be a valid mesh with a valid material.
#include <cstring>

#include <weft/Mesh.h>
#include <weft/ModelIo.h>
#include <weft/Texture.h>

#include "FuzzCommon.h"

namespace {

void checkMesh(const weft::Mesh& mesh) {
    try {
        mesh.validate();
    } catch (const weft::Error& e) {
        weft::fuzz::finding(std::string("loaded OBJ mesh fails validate(): ") + e.what());
    }
}

} // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    weft::ImageU8 texture(2, 2, 4);
    for (size_t i = 0; i < texture.pixels.size(); ++i) texture.pixels[i] = uint8_t(60 * i);
    weft::savePng((weft::fuzz::scratchDir() / "t.png").string(), texture);
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    static const char kSplit[] = "\n#mtl\n";
    const char* text = reinterpret_cast<const char*>(data);
    const char* split = static_cast<const char*>(memmem(text, size, kSplit, sizeof kSplit - 1));
    const size_t objBytes = split ? size_t(split - text) + 1 : size;
    const size_t mtlStart = split ? objBytes + sizeof kSplit - 2 : size;
    const std::string obj = weft::fuzz::scratchFile("in.obj", data, objBytes);
    weft::fuzz::scratchFile("m.mtl", data + mtlStart, size - mtlStart);
    weft::fuzz::expectResultOrWeftError([&] {
        for (const weft::MeshPart& part : weft::loadObjParts(obj)) {
            checkMesh(part.mesh);
            try {
                part.material.validate();
            } catch (const weft::Error& e) {
                weft::fuzz::finding(std::string("OBJ material fails validate(): ") + e.what());
            }
            if (part.material.texture) {
                try {
                    part.material.texture->image().validate();
                } catch (const weft::Error& e) {
                    weft::fuzz::finding(std::string("OBJ texture fails validate(): ") + e.what());
                }
            }
        }
    });
    // The geometry reader alone (materials ignored).
    weft::fuzz::expectResultOrWeftError([&] { checkMesh(weft::loadObj(obj)); });
    return 0;
}
