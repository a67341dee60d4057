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

py::tuple fromVec3(const glm::vec3& v) { return py::make_tuple(v.x, v.y, v.z); }

} // namespace weft::py_bind
