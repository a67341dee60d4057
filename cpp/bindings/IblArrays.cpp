// The NumPy <-> IBL conversions the IBL bindings share (bind_ibl.cpp, bind_environment.cpp),
// each with its argument checks.
#include "IblArrays.h"

#include <cmath>
#include <cstring>

namespace weft::py_bind {

// A float array of any float dtype; integer images must be linearised first.
FloatArray floatArray(py::handle obj, const std::string& name) {
    py::array a = py::array::ensure(obj);
    if (!a) throw py::type_error(name + " must be a NumPy array");
    if (a.dtype().kind() != 'f')
        throw InvalidArgument(name + " must be a float array (linear radiance), got dtype " +
                              std::string(py::str(a.dtype())) +
                              "; decode 8-bit images with weft.ibl.srgb_to_linear");
    FloatArray f = FloatArray::ensure(a);
    const float* p = f.data();
    for (py::ssize_t k = 0; k < f.size(); ++k)
        if (!std::isfinite(p[k])) throw InvalidArgument(name + " must be finite (found NaN/inf)");
    return f;
}

RgbImage rgbImage(py::handle obj, const std::string& name) {
    FloatArray a = floatArray(obj, name);
    if (a.ndim() != 2 && a.ndim() != 3)
        throw InvalidArgument(name + " must have shape (H, W) or (H, W, C)");
    const int c = a.ndim() == 3 ? int(a.shape(2)) : 1;
    if (c < 1 || c > 4) throw InvalidArgument(name + " must have 1 to 4 channels");
    if (a.shape(0) < 1 || a.shape(1) < 1) throw InvalidArgument(name + " must not be empty");
    RgbImage img;
    img.height = int(a.shape(0));
    img.width = int(a.shape(1));
    img.pixels.resize(size_t(img.width) * img.height * 3);
    const float* p = a.data();
    for (size_t k = 0; k < size_t(img.width) * img.height; ++k)
        for (int ch = 0; ch < 3; ++ch) img.pixels[k * 3 + ch] = p[k * c + (c >= 3 ? ch : 0)];
    return img;
}

py::array_t<float> imageArray(const std::vector<float>& pixels, int height, int width) {
    return arrayOf<float>(pixels, {height, width, 3});
}

CubeMap cubeFromArray(py::handle obj, const std::string& name) {
    FloatArray a = floatArray(obj, name);
    if (a.ndim() != 4 || a.shape(0) != 6 || a.shape(1) != a.shape(2) || a.shape(3) != 3 ||
        a.shape(1) < 1)
        throw InvalidArgument(name + " must have shape (6, S, S, 3) with S >= 1");
    CubeMap cube(int(a.shape(1)));
    std::memcpy(cube.data(), a.data(), cube.floatCount() * sizeof(float));
    return cube;
}

CubeArg toCube(py::handle obj, const std::string& name) {
    CubeArg arg;
    if (py::isinstance<CubeMap>(obj))
        arg.borrowed = &obj.cast<const CubeMap&>();
    else
        arg.owned = cubeFromArray(obj, name);
    return arg;
}

py::array levelView(CubeMap& cube, int level, py::handle owner) {
    if (level < 0 || level >= cube.levels())
        throw InvalidArgument("level must be in [0, " + std::to_string(cube.levels() - 1) + "]");
    const py::ssize_t s = cube.levelSize(level);
    const py::ssize_t f = sizeof(float);
    return py::array(py::dtype::of<float>(), {py::ssize_t(6), s, s, py::ssize_t(3)},
                     {s * s * 3 * f, s * 3 * f, 3 * f, f}, cube.data(level), owner);
}

std::vector<glm::vec3> directions(py::handle obj, const std::string& name) {
    FloatArray a = floatArray(obj, name);
    if (a.ndim() != 2 || a.shape(1) != 3) throw InvalidArgument(name + " must have shape (N, 3)");
    std::vector<glm::vec3> out(size_t(a.shape(0)));
    for (size_t k = 0; k < out.size(); ++k) {
        out[k] = glm::vec3(a.data()[k * 3], a.data()[k * 3 + 1], a.data()[k * 3 + 2]);
        if (glm::dot(out[k], out[k]) == 0.0f) throw InvalidArgument(name + " must be non-zero");
    }
    return out;
}

Sh9 shFromArray(py::handle obj) {
    FloatArray a = floatArray(obj, "sh");
    if (a.ndim() != 2 || a.shape(0) != 9 || a.shape(1) != 3)
        throw InvalidArgument("sh must have shape (9, 3)");
    Sh9 sh;
    for (int k = 0; k < 9; ++k)
        sh.coeffs[size_t(k)] = glm::vec3(a.data()[k * 3], a.data()[k * 3 + 1], a.data()[k * 3 + 2]);
    return sh;
}

py::array_t<float> shArray(const Sh9& sh) {
    return rowsArray(std::vector<glm::vec3>(sh.coeffs.begin(), sh.coeffs.end()));
}

glm::mat4 optionalMat4(py::handle obj, const std::string& name) {
    return obj.is_none() ? glm::mat4(1.0f) : toMat4(obj, name);
}

std::vector<uint8_t> maskVector(py::handle obj, const std::string& name, py::ssize_t expected) {
    py::array a = py::array::ensure(obj);
    if (!a) throw py::type_error(name + " must be an array");
    auto b = py::array_t<bool, py::array::c_style | py::array::forcecast>::ensure(a);
    if (b.size() != expected)
        throw InvalidArgument(name + " must have " + std::to_string(expected) + " entries, got " +
                              std::to_string(b.size()));
    return std::vector<uint8_t>(b.data(), b.data() + b.size());
}

void requireCubeSize(int size) {
    if (size < 1 || size > 8192)
        throw InvalidArgument("cube map size must be in [1, 8192], got " + std::to_string(size));
}

DomeLayout domeLayout(const std::string& name) {
    if (name == "fibonacci") return DomeLayout::Fibonacci;
    if (name == "rings") return DomeLayout::Rings;
    throw InvalidArgument("dome layout must be 'fibonacci' or 'rings', got '" + name + "'");
}

py::tuple captureTuple(CaptureCube&& c) {
    const int s = c.cube.size();
    return py::make_tuple(std::move(c.cube), boolArray(c.valid, {6, s, s}));
}

} // namespace weft::py_bind
