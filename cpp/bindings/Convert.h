#pragma once
// NumPy <-> weft conversions with the argument checks every binding shares.
#include <string>

#include <glm/glm.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <weft/Error.h>
#include <weft/Image.h>

namespace weft {
enum class ToneMap; // weft/Renderer.h
}

namespace weft::py_bind {

namespace py = pybind11;

/// A float64 view of any numeric array-like; non-numeric input raises TypeError.
py::array_t<double> numericArray(py::handle obj, const std::string& name);
glm::vec3 toVec3(py::handle obj, const std::string& name);
glm::mat4 toMat4(py::handle obj, const std::string& name);
py::array_t<float> fromMat4(const glm::mat4& m);
py::tuple fromVec3(const glm::vec3& v);
/// Images <-> (H, W, C) arrays (defined in module.cpp); float input must be finite.
py::array_t<uint8_t> toNumpy(const ImageU8& img);
ImageU8 fromNumpy(py::handle obj);
py::array_t<float> toNumpy(const ImageF& img);
ImageF fromNumpyF(py::handle obj);
/// 'clamp', 'aces', 'agx' or 'neutral' (defined in bind_render.cpp); else InvalidArgument.
ToneMap toneMapOf(const std::string& name);
std::string toneMapName(ToneMap t);

} // namespace weft::py_bind
