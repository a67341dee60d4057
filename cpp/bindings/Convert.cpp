#include "Convert.h"

#include <cmath>

namespace weft::py_bind {

py::array_t<double> numericArray(py::handle obj, const std::string& name) {
    py::array generic;
    try {
        generic = py::array::ensure(obj);
    } catch (const py::error_already_set&) {}
    if (!generic || generic.dtype().kind() == 'O' || generic.dtype().kind() == 'U' ||
        generic.dtype().kind() == 'S' || generic.dtype().kind() == 'c') {
        PyErr_Clear();
        throw py::type_error(name + " must be numeric, got " +
                             std::string(py::str(py::type::of(obj))));
    }
    return py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(generic);
}

glm::vec3 toVec3(py::handle obj, const std::string& name) {
    auto a = numericArray(obj, name);
    if (a.ndim() != 1 || a.size() != 3) throw InvalidArgument(name + " must have 3 components");
    auto r = a.unchecked<1>();
    glm::vec3 v(float(r(0)), float(r(1)), float(r(2)));
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(v[i])) throw InvalidArgument(name + " must be finite (got NaN or inf)");
    return v;
}

glm::mat4 toMat4(py::handle obj, const std::string& name) {
    auto a = numericArray(obj, name);
    if (a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
        throw InvalidArgument(name + " must be a 4x4 matrix");
    auto r = a.unchecked<2>();
    glm::mat4 m;
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) {
            m[col][row] = float(r(row, col)); // NumPy rows act on column vectors
            if (!std::isfinite(m[col][row]))
                throw InvalidArgument(name + " must be finite (got NaN or inf)");
        }
    return m;
}

py::array_t<float> fromMat4(const glm::mat4& m) {
    py::array_t<float> out({4, 4});
    auto w = out.mutable_unchecked<2>();
    for (int row = 0; row < 4; ++row)
        for (int col = 0; col < 4; ++col) w(row, col) = m[col][row];
    return out;
}

template <class Vec, int K>
std::vector<Vec> rowsOf(py::handle obj, const std::string& name, size_t rows) {
    auto a = numericArray(obj, name);
    if (K == 1 ? a.ndim() != 1 : (a.ndim() != 2 || a.shape(1) != K))
        throw InvalidArgument(name + " must have shape (N" +
                              (K == 1 ? std::string(",)") : ", " + std::to_string(K) + ")"));
    if (rows != size_t(-1) && size_t(a.shape(0)) != rows)
        throw InvalidArgument(name + " must have " + std::to_string(rows) + " rows");
    std::vector<Vec> out(size_t(a.shape(0)));
    const double* d = a.data();
    for (size_t i = 0; i < out.size() * K; ++i) {
        if (!std::isfinite(d[i]) || std::abs(d[i]) > 3.0e38)
            throw InvalidArgument(name + " must be finite (got NaN or inf)");
        reinterpret_cast<float*>(out.data())[i] = float(d[i]);
    }
    return out;
}
template std::vector<float> rowsOf<float, 1>(py::handle, const std::string&, size_t);
template std::vector<glm::vec2> rowsOf<glm::vec2, 2>(py::handle, const std::string&, size_t);
template std::vector<glm::vec3> rowsOf<glm::vec3, 3>(py::handle, const std::string&, size_t);

std::vector<int64_t> integersOf(py::handle obj, const std::string& name, const char* what,
                                int64_t lo, int64_t hi) {
    py::array a = py::array::ensure(obj);
    if (!a || (a.dtype().kind() != 'i' && a.dtype().kind() != 'u'))
        throw py::type_error(name + " must be integers");
    auto i64 = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(a);
    std::vector<int64_t> out(i64.data(), i64.data() + i64.size());
    for (size_t i = 0; i < out.size(); ++i)
        if (out[i] < lo || out[i] > hi)
            throw InvalidArgument(name + ": " + what + " " + std::to_string(out[i]) + " (entry " +
                                  std::to_string(i) + ") out of range [" + std::to_string(lo) +
                                  ", " + std::to_string(hi) + "]");
    return out;
}

py::array_t<bool> boolArray(const std::vector<uint8_t>& flags, std::vector<py::ssize_t> shape) {
    py::array_t<bool> out(std::move(shape));
    if (size_t(out.size()) != flags.size()) throw Error("boolArray: the shape does not fit");
    for (size_t i = 0; i < flags.size(); ++i) out.mutable_data()[i] = flags[i] != 0;
    return out;
}

py::tuple fromVec3(const glm::vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

py::array_t<uint8_t> toNumpy(const ImageU8& img) {
    return arrayOf<uint8_t>(img.pixels, {img.height, img.width, img.channels});
}

ImageU8 fromNumpy(py::handle obj) {
    py::array a = py::array::ensure(obj);
    if (!a) throw py::type_error("image must be a NumPy array");
    if (a.dtype().kind() != 'u' || a.itemsize() != 1)
        throw InvalidArgument("image must have dtype uint8, got " +
                              std::string(py::str(a.dtype())));
    if (a.ndim() != 2 && a.ndim() != 3) throw InvalidArgument("image must be (H, W) or (H, W, C)");
    const int c = a.ndim() == 3 ? int(a.shape(2)) : 1;
    if (c < 1 || c > 4) throw InvalidArgument("image must have 1 to 4 channels");
    ImageU8 img(int(a.shape(1)), int(a.shape(0)), c);
    if (img.width == 0 || img.height == 0) throw InvalidArgument("image must not be empty");
    auto contiguous = py::array_t<uint8_t, py::array::c_style | py::array::forcecast>::ensure(a);
    std::memcpy(img.pixels.data(), contiguous.data(), img.pixels.size());
    return img;
}

py::array_t<float> toNumpy(const ImageF& img) {
    return arrayOf<float>(img.pixels, {img.height, img.width, img.channels});
}

ImageF fromNumpyF(py::handle obj) {
    py::array a = py::array::ensure(obj);
    if (!a) throw py::type_error("image must be a NumPy array");
    if (a.dtype().kind() != 'f' && a.dtype().kind() != 'u' && a.dtype().kind() != 'i')
        throw py::type_error("float image must be numeric, got dtype " +
                             std::string(py::str(a.dtype())));
    if (a.ndim() != 2 && a.ndim() != 3) throw InvalidArgument("image must be (H, W) or (H, W, C)");
    const int c = a.ndim() == 3 ? int(a.shape(2)) : 1;
    if (c < 1 || c > 4) throw InvalidArgument("image must have 1 to 4 channels");
    if (a.shape(0) == 0 || a.shape(1) == 0) throw InvalidArgument("image must not be empty");
    ImageF img(int(a.shape(1)), int(a.shape(0)), c);
    auto contiguous = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(a);
    std::memcpy(img.pixels.data(), contiguous.data(), img.pixels.size() * sizeof(float));
    img.requireFinite("image");
    return img;
}

} // namespace weft::py_bind
