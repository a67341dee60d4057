#pragma once
// NumPy <-> IBL conversions with their argument checks, shared by bind_ibl.cpp (cube maps,
// filters, lights) and bind_environment.cpp (ShadowDome, Environment).
#include <string>
#include <vector>

#include <weft/CubeMap.h>
#include <weft/IblConvert.h>
#include <weft/IblFilter.h>
#include <weft/ShadowDome.h>

#include "Convert.h"

namespace weft::py_bind {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

/// A finite float array of any float dtype; integer images must be linearised first.
FloatArray floatArray(py::handle obj, const std::string& name);

// (H, W, 3) float image (also accepts (H, W), (H, W, 1) grey and (H, W, 4), alpha dropped).
struct RgbImage {
    std::vector<float> pixels;
    int width = 0, height = 0;
    RgbView view() const { return {pixels.data(), width, height}; }
};

RgbImage rgbImage(py::handle obj, const std::string& name);
py::array_t<float> imageArray(const std::vector<float>& pixels, int height, int width);
CubeMap cubeFromArray(py::handle obj, const std::string& name);

// A CubeMap argument: a weft.CubeMap (used in place, kept alive by the caller's reference) or a
// (6, S, S, 3) array (copied).
struct CubeArg {
    CubeMap owned;
    const CubeMap* borrowed = nullptr;
    const CubeMap& get() const { return borrowed ? *borrowed : owned; }
    operator const CubeMap&() const { return get(); }
};

CubeArg toCube(py::handle obj, const std::string& name);
/// Level `level` of `cube` as a (6, s, s, 3) array viewing its memory, kept alive by `owner`.
py::array levelView(CubeMap& cube, int level, py::handle owner);
/// Non-zero directions from an (N, 3) array.
std::vector<glm::vec3> directions(py::handle obj, const std::string& name);
Sh9 shFromArray(py::handle obj);
py::array_t<float> shArray(const Sh9& sh);
glm::mat4 optionalMat4(py::handle obj, const std::string& name);
std::vector<uint8_t> maskVector(py::handle obj, const std::string& name, py::ssize_t expected);
void requireCubeSize(int size);
DomeLayout domeLayout(const std::string& name);
py::tuple captureTuple(CaptureCube&& c);

} // namespace weft::py_bind
