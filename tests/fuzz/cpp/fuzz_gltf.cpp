// libFuzzer target: a glTF 2.0 file read by weft::loadGltf (weft.load_gltf): the input is a
// binary .glb when it starts with "glTF", else a .gltf (JSON). Beside it lie a valid 2x2 PNG
// "t.png" and a 1 KiB buffer "b.bin" (a quad) for external URIs. Every part must be a valid
// mesh with a valid material.
#include <cstring>

#include <weft/ModelIo.h>
#include <weft/Texture.h>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
    weft::ImageU8 texture(2, 2, 4);
    for (size_t i = 0; i < texture.pixels.size(); ++i) texture.pixels[i] = uint8_t(60 * i);
    weft::savePng((weft::fuzz::scratchDir() / "t.png").string(), texture);
    // b.bin: a unit quad -- positions (4 vec3, offset 0), normals (4 vec3, 48), UVs (4 vec2,
    // 96), uint16 indices 0 1 2 0 2 3 (128) -- then zeros up to 1 KiB
    const float quad[32] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 0,
                            0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 1, 1, 0, 1};
    const uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
    std::vector<uint8_t> buffer(1024, 0);
    std::memcpy(buffer.data(), quad, sizeof quad);
    std::memcpy(buffer.data() + sizeof quad, indices, sizeof indices);
    weft::fuzz::writeFile(weft::fuzz::scratchDir() / "b.bin", buffer.data(), buffer.size());
    return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const bool binary = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
    const std::string path = weft::fuzz::scratchFile(binary ? "in.glb" : "in.gltf", data, size);
    weft::fuzz::expectResultOrWeftError([&] {
        for (const weft::MeshPart& part : weft::loadGltf(path)) {
            try {
                part.mesh.validate();
                part.material.validate();
                if (part.material.texture) part.material.texture->image().validate();
                if (part.material.normalMap) part.material.normalMap->image().validate();
            } catch (const weft::Error& e) {
                weft::fuzz::finding(std::string("glTF part fails validation: ") + e.what());
            }
        }
    });
    return 0;
}
