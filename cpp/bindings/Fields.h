#pragma once
// One declaration per bound field. A binding lists a struct's fields once -- the Python name, the
// member (or a getter and a setter where Python sees it otherwise), a docstring -- and these
// helpers make from the list the keyword constructor or function (defaults read from the struct's
// own initialisers, so no default is written twice), and the properties (each set through the
// struct's validate(): a refused value leaves the object as it was).
#include <functional>
#include <memory>
#include <string>
#include <tuple>
#include <utility>

#include <glm/glm.hpp>

#include "Convert.h"

namespace weft::py_bind {

/// Sets fields of a validated value type through `assign`, restoring it if validate() refuses.
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

/// How a member type shows in Python: `Arg` is the parameter type pybind11 converts a Python
/// value to (its name is what signatures and stubs show).
template <class M> struct PyValue {
    using Arg = M;
    static M toPython(const M& v) { return v; }
    static M fromPython(const Arg& v, const char*) { return v; }
};
template <> struct PyValue<glm::vec3> { // any sequence of 3 finite numbers; read as a tuple
    using Arg = py::handle;
    static py::tuple toPython(const glm::vec3& v) { return fromVec3(v); }
    static glm::vec3 fromPython(py::handle v, const char* name) { return toVec3(v, name); }
};
template <class T> struct PyValue<std::shared_ptr<const T>> { // None for none
    using Arg = std::shared_ptr<T>;
    static Arg toPython(const std::shared_ptr<const T>& v) { return std::const_pointer_cast<T>(v); }
    static std::shared_ptr<const T> fromPython(const Arg& v, const char*) { return v; }
};

/// A field of T as Python sees it: `get(const T&)` reads it, `set(T&, Arg)` stores it without
/// validating. `required`: a constructor argument without a default.
template <class T, class A, class Get, class Set, bool Required = false> struct Field {
    using Struct = T;
    using Arg = A;
    static constexpr bool required = Required;
    const char* name;
    Get get;
    Set set;
    const char* doc;
};

/// The member `member` of T, converted as PyValue says.
template <class T, class M> auto field(const char* name, M T::*member, const char* doc = nullptr) {
    using V = PyValue<M>;
    auto get = [member](const T& o) { return V::toPython(o.*member); };
    auto set = [member, name](T& o, const typename V::Arg& v) {
        o.*member = V::fromPython(v, name);
    };
    return Field<T, typename V::Arg, decltype(get), decltype(set)>{name, get, set, doc};
}

/// A field Python sees as an `A` other than its member (an enum by name, a pair of members).
template <class A, class T, class Get, class Set>
auto field(const char* name, Get get, Set set, const char* doc = nullptr) {
    return Field<T, A, Get, Set>{name, get, set, doc};
}

/// The enum value named `s` (`names` in the enum's order); else InvalidArgument
/// "<what> must be 'a', 'b' or 'c' (got 's')".
template <class E, size_t N>
E enumOf(const char* const (&names)[N], const std::string& s, const std::string& what) {
    std::string list;
    for (size_t i = 0; i < N; ++i) {
        if (s == names[i]) return E(i);
        list += std::string(i == 0 ? "'" : i + 1 == N ? " or '" : ", '") + names[i] + "'";
    }
    throw InvalidArgument(what + " must be " + list + " (got '" + s + "')");
}

/// The enum member `member` of T, seen in Python as one of `names` (in the enum's order).
template <class T, class E, size_t N>
auto enumField(const char* name, E T::*member, const char* const (&names)[N],
               const char* doc = nullptr) {
    const char* const(*table)[N] = &names; // the tables are static
    return field<std::string, T>(
        name, [member, table](const T& o) { return std::string((*table)[size_t(o.*member)]); },
        [member, table, name](T& o, const std::string& v) {
            o.*member = enumOf<E>(*table, v, name);
        },
        doc);
}

/// The field as a constructor argument without a default (it must come before those with one).
template <class T, class A, class G, class S> auto required(const Field<T, A, G, S>& f) {
    return Field<T, A, G, S, true>{f.name, f.get, f.set, f.doc};
}

/// The fields of S as fields of Outer, whose member `part` holds the S.
template <class Outer, class S, class... F>
auto within(S Outer::*part, const std::tuple<F...>& fs) {
    return std::apply(
        [part](const auto&... f) {
            return std::make_tuple(
                Field<Outer, typename std::decay_t<decltype(f)>::Arg,
                      std::function<decltype(f.get(std::declval<S>()))(const Outer&)>,
                      std::function<void(Outer&, const typename std::decay_t<decltype(f)>::Arg&)>,
                      std::decay_t<decltype(f)>::required>{
                    f.name, [part, f](const Outer& o) { return f.get(o.*part); },
                    [part, f](Outer& o, const typename std::decay_t<decltype(f)>::Arg& v) {
                        f.set(o.*part, v);
                    },
                    f.doc}...);
        },
        fs);
}

namespace detail {

template <class F, class T> auto argOf(const F& f, const T& defaults) {
    if constexpr (F::required)
        return py::arg(f.name);
    else
        return py::arg(f.name) = f.get(defaults);
}

// make(lead..., T) as a pybind11 callable taking the leading arguments (a method's self), then
// every field.
template <class T, class... Lead, class Make, class... F, size_t... I>
auto fieldCall(Make make, const std::tuple<F...>& fields, std::index_sequence<I...>) {
    return [make, fields](Lead... lead, typename F::Arg... v) {
        T o{};
        (std::get<I>(fields).set(o, v), ...);
        return make(lead..., std::move(o));
    };
}

template <class... F> using StructOf = typename std::tuple_element_t<0, std::tuple<F...>>::Struct;

} // namespace detail

/// A constructor taking the fields as arguments in the list's order, each defaulting to a
/// default-constructed struct's value; `make(struct)` returns what the class holds (checks it).
template <class Cls, class Make, class... F, class... Extra>
void defInit(Cls& cls, Make make, const std::tuple<F...>& fields, const Extra&... extra) {
    using T = detail::StructOf<F...>;
    const T defaults{};
    std::apply(
        [&](const auto&... f) {
            cls.def(py::init(detail::fieldCall<T>(make, fields, std::index_sequence_for<F...>{})),
                    detail::argOf(f, defaults)..., extra...);
        },
        fields);
}

/// A module function taking the fields as arguments (defaults as defInit) and returning
/// `call(struct)`.
template <class Call, class... F, class... Extra>
void defFunction(py::module_& m, const char* name, Call call, const std::tuple<F...>& fields,
                 const Extra&... extra) {
    using T = detail::StructOf<F...>;
    const T defaults{};
    std::apply(
        [&](const auto&... f) {
            m.def(name, detail::fieldCall<T>(call, fields, std::index_sequence_for<F...>{}),
                  detail::argOf(f, defaults)..., extra...);
        },
        fields);
}

/// The same with leading arguments of types Lead (named by `leadArgs`, py::arg each) before the
/// fields: `call(lead..., struct)`.
template <class... Lead, class Call, class... A, class... F, class... Extra>
void defFunctionWith(py::module_& m, const char* name, Call call, const std::tuple<A...>& leadArgs,
                     const std::tuple<F...>& fields, const Extra&... extra) {
    using T = detail::StructOf<F...>;
    const T defaults{};
    std::apply(
        [&](const auto&... lead) {
            std::apply(
                [&](const auto&... f) {
                    m.def(name,
                          detail::fieldCall<T, Lead...>(call, fields,
                                                        std::index_sequence_for<F...>{}),
                          lead..., detail::argOf(f, defaults)..., extra...);
                },
                fields);
        },
        leadArgs);
}

/// A method taking the fields as arguments (defaults as defInit) and returning
/// `call(self, struct)`.
template <class Cls, class Call, class... F, class... Extra>
void defMethod(Cls& cls, const char* name, Call call, const std::tuple<F...>& fields,
               const Extra&... extra) {
    using T = detail::StructOf<F...>;
    const T defaults{};
    std::apply(
        [&](const auto&... f) {
            cls.def(name,
                    detail::fieldCall<T, typename Cls::type&>(call, fields,
                                                              std::index_sequence_for<F...>{}),
                    detail::argOf(f, defaults)..., extra...);
        },
        fields);
}

/// A validated value type's constructor: the struct itself, validate()d.
template <class T> T validated(T o) {
    o.validate();
    return o;
}

/// One property per field on the class of T; a value validate() refuses leaves T unchanged.
template <class Cls, class... F> void defProperties(Cls& cls, const std::tuple<F...>& fields) {
    std::apply(
        [&](const auto&... f) {
            (cls.def_property(
                 f.name, [f](const typename Cls::type& o) { return f.get(o); },
                 [f](typename Cls::type& o, const typename std::decay_t<decltype(f)>::Arg& v) {
                     setChecked(o, [&](typename Cls::type& x) { f.set(x, v); });
                 },
                 f.doc ? f.doc : ""),
             ...);
        },
        fields);
}

/// One property per field of the settings an owner holds: `read(owner)` returns a copy,
/// `write(owner, settings)` checks and replaces them (refused: the owner keeps its settings).
template <class Cls, class Read, class Write, class... F>
void defSettingProperties(Cls& cls, Read read, Write write, const std::tuple<F...>& fields) {
    using O = typename Cls::type;
    std::apply(
        [&](const auto&... f) {
            (cls.def_property(
                 f.name, [f, read](const O& o) { return f.get(read(o)); },
                 [f, read, write](O& o, const typename std::decay_t<decltype(f)>::Arg& v) {
                     auto s = read(o);
                     f.set(s, v);
                     write(o, s);
                 },
                 f.doc ? f.doc : ""),
             ...);
        },
        fields);
}

} // namespace weft::py_bind
