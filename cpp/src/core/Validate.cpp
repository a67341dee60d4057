#include "core/Validate.h"

#include <cmath>
#include <sstream>

#include <weft/Error.h>

namespace weft {

void requireFinite(float v, const char* what) {
    if (!std::isfinite(v)) throw InvalidArgument(std::string(what) + " must be finite");
}

void requireFinite(const glm::vec3& v, const char* what) {
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(v[i]))
            throw InvalidArgument(std::string(what) + " must be finite (got NaN or inf)");
}

void requireFinite(const glm::mat4& m, const char* what) {
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 4; ++r)
            if (!std::isfinite(m[c][r]))
                throw InvalidArgument(std::string(what) + " must be finite (got NaN or inf)");
}

void requireNonNegative(const glm::vec3& v, const char* what) {
    requireFinite(v, what);
    if (v.x < 0 || v.y < 0 || v.z < 0)
        throw InvalidArgument(std::string(what) + " must not be negative");
}

void requirePositive(float v, const char* what) {
    if (!(std::isfinite(v) && v > 0)) {
        std::ostringstream msg;
        msg << what << " must be positive and finite (got " << v << ")";
        throw InvalidArgument(msg.str());
    }
}

void requireInvertible(const glm::mat4& m, const char* what) {
    requireFinite(m, what);
    const double det = glm::determinant(glm::dmat4(m));
    double scale = 0;
    for (int c = 0; c < 3; ++c) scale = std::max(scale, double(glm::length(glm::vec3(m[c]))));
    if (!(std::abs(det) > 1e-12 * std::pow(std::max(scale, 1e-30), 3.0)))
        throw InvalidArgument(std::string(what) + " must be invertible (determinant is 0)");
}

} // namespace weft
