// libFuzzer target: an environment file as weft-demo's --environment reads it
// (weft::loadEnvironmentCube: loadImageF, then equirectangular or sphere map -> cube). The first
// byte picks the extension (byte % 4: .hdr, .exr, .pic, .png -- the slots of the atheris env
// target, tests/fuzz/fuzz_text.py, whose third is .npy, which only Python reads), the rest is the
// file. A cube that loads must hold finite radiance >= 0.
#include <weft/IblConvert.h>

#include "FuzzCommon.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    if (size == 0) return 0;
    static const char* const kExtensions[4] = {".hdr", ".exr", ".pic", ".png"};
    const std::string path =
        weft::fuzz::scratchFile(std::string("env") + kExtensions[data[0] % 4], data + 1, size - 1);
    weft::fuzz::expectResultOrWeftError([&] {
        const weft::CubeMap cube = weft::loadEnvironmentCube(path, 4);
        weft::fuzz::requireFiniteValues(cube.data(), cube.floatCount(), "environment cube", true);
    });
    return 0;
}
