#pragma once
// NumPy <-> weft conversions with the argument checks every binding shares.
#include <cstring>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <weft/Error.h>
#include <weft/Image.h>

namespace weft::py_bind {

namespace py = pybind11;

/// A float64 view of any numeric array-like; non-numeric input raises TypeError.
py::array_t<double> numericArray(py::handle obj, const std::string& name);
glm::vec3 toVec3(py::handle obj, const std::string& name);
glm::mat4 toMat4(py::handle obj, const std::string& name);
py::array_t<float> fromMat4(const glm::mat4& m);
py::tuple fromVec3(const glm::vec3& v);
/// "(x, y, z)" for the reprs.
inline std::string vecRepr(const glm::vec3& v) {
    std::ostringstream s;
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
}
/// Rows of K finite numbers, (N, K) (or (N,) for K = 1), as Vec (glm::vecK, or float for K =
/// 1); with `rows` set exactly that many. Shape or values refused: InvalidArgument naming `name`.
template <class Vec, int K>
std::vector<Vec> rowsOf(py::handle obj, const std::string& name, size_t rows = size_t(-1));
/// Integers of any shape, flattened, each in [lo, hi]; an entry outside names `what` and its
/// place ("pin: particle index -1 (entry 1) out of range [0, 2147483647]").
std::vector<int64_t> integersOf(py::handle obj, const std::string& name, const char* what,
                                int64_t lo, int64_t hi);
/// The same as I (an integer type), in [lo, hi] (default: I's range).
template <class I>
std::vector<I> integersOf(py::handle obj, const std::string& name, const char* what,
                          int64_t lo = int64_t(std::numeric_limits<I>::min()),
                          int64_t hi = int64_t(std::numeric_limits<I>::max())) {
    const std::vector<int64_t> v = integersOf(obj, name, what, lo, hi);
    return std::vector<I>(v.begin(), v.end());
}
/// A NumPy array of `shape` holding a copy of `data` (rows of glm vectors as their scalars).
template <class Scalar, class T>
py::array_t<Scalar> arrayOf(const std::vector<T>& data, std::vector<py::ssize_t> shape) {
    py::array_t<Scalar> out(std::move(shape));
    if (size_t(out.size()) * sizeof(Scalar) != data.size() * sizeof(T))
        throw Error("arrayOf: the shape does not fit the data");
    if (!data.empty()) std::memcpy(out.mutable_data(), data.data(), data.size() * sizeof(T));
    return out;
}
/// Flags (non-zero = True) as a bool array of `shape`.
py::array_t<bool> boolArray(const std::vector<uint8_t>& flags, std::vector<py::ssize_t> shape);
/// Rows of glm vectors (or floats) as an (N, K) float32 array.
template <class Vec> py::array_t<float> rowsArray(const std::vector<Vec>& v) {
    return arrayOf<float>(v, {py::ssize_t(v.size()), py::ssize_t(sizeof(Vec) / sizeof(float))});
}
/// Images <-> (H, W, C) arrays; float input must be finite.
py::array_t<uint8_t> toNumpy(const ImageU8& img);
ImageU8 fromNumpy(py::handle obj);
py::array_t<float> toNumpy(const ImageF& img);
ImageF fromNumpyF(py::handle obj);
/// The tone maps' Python names in ToneMap's order (defined in bind_render.cpp).
extern const char* const kToneMaps[4];

} // namespace weft::py_bind
