#pragma once
// Helpers of the bindings of validated value types (materials, lights, camera): a property set
// through validate() that restores the old value when validation refuses the new one.
#include <sstream>
#include <string>

#include <glm/glm.hpp>

#include "Convert.h"

namespace weft::py_bind {

// Sets one field of a validated value type, restoring it if validation fails.
template <typename T, typename F> void setChecked(T& obj, F&& assign) {
    T before = obj;
    assign(obj);
    try {
        obj.validate();
    } catch (...) {
        obj = before;
        throw;
    }
}

#define WEFT_VEC3_PROPERTY(cls, pyname, field)                                                     \
    def_property(                                                                                  \
        pyname, [](const cls& o) { return fromVec3(o.field); },                                    \
        [](cls& o, py::handle v) {                                                                 \
            glm::vec3 value = toVec3(v, pyname);                                                   \
            setChecked(o, [&](cls& x) { x.field = value; });                                       \
        })

inline std::string vecRepr(const glm::vec3& v) {
    std::ostringstream s;
    s << "(" << v.x << ", " << v.y << ", " << v.z << ")";
    return s.str();
}

} // namespace weft::py_bind
