#pragma once
// Renderer properties for RenderSettings fields, one declaration each: the setter copies the
// settings, changes the field and hands them to Renderer::setSettings, which checks them
// (RenderSettings::validate), so no binding repeats a range.
#include <cstdint>
#include <limits>
#include <string>

#include <weft/Renderer.h>

#include "Convert.h"

namespace weft::py_bind {

/// A Python integer (a constructor argument) for an integer field; outside the field's type (a
/// negative count would wrap around) is InvalidArgument.
template <typename T> T settingInteger(int64_t v, const char* name) {
    if (v < int64_t(std::numeric_limits<T>::min()) || v > int64_t(std::numeric_limits<T>::max()))
        throw InvalidArgument(std::string(name) + " out of range (got " + std::to_string(v) + ")");
    return T(v);
}

/// The property `name` of RenderSettings::*field. The setter takes the field's own type: pybind
/// refuses a negative value for an unsigned field (weft.ArgumentError names the property).
template <typename T>
void settingProperty(py::class_<Renderer>& cls, const char* name, T RenderSettings::*field,
                     const char* doc) {
    cls.def_property(
        name, [field](const Renderer& r) { return r.settings().*field; },
        [field](Renderer& r, T v) {
            RenderSettings s = r.settings();
            s.*field = v;
            r.setSettings(s);
        },
        doc);
}

/// A property shown to Python as `Arg` (a name for an enum, ...): get(settings) returns it,
/// set(settings&, value) stores it.
template <typename Arg, typename Get, typename Set>
void settingProperty(py::class_<Renderer>& cls, const char* name, Get get, Set set,
                     const char* doc) {
    cls.def_property(
        name, [get](const Renderer& r) { return get(r.settings()); },
        [set](Renderer& r, const Arg& v) {
            RenderSettings s = r.settings();
            set(s, v);
            r.setSettings(s);
        },
        doc);
}

} // namespace weft::py_bind
