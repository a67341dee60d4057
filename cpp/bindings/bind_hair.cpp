// Bindings of the hair subsystem: weft.HairStrands, .hair IO, hair and fur generators,
// tangents/ribbons, weft.HairMaterial and the GLSL shading evaluator.
#include <cmath>
#include <cstring>
#include <sstream>

#include <pybind11/stl.h>

#include <weft/HairGenerator.h>
#include <weft/HairGeometry.h>
#include <weft/HairIo.h>
#include <weft/HairMaterial.h>
#include <weft/HairShadeEval.h>

#include "Convert.h"
#include "Fields.h"

namespace weft::py_bind {

using HairPtr = std::shared_ptr<HairStrands>;

namespace {

std::vector<uint16_t> segmentsOf(py::handle obj) {
    py::array a = py::array::ensure(obj);
    if (a && a.ndim() != 1) throw InvalidArgument("segments must have shape (S,)");
    return integersOf<uint16_t>(obj, "segments", "segment count");
}

// A read-only NumPy view of `count` x `columns` floats owned by `owner`.
py::array floatView(const float* data, size_t count, int columns, py::handle owner) {
    std::vector<py::ssize_t> shape{py::ssize_t(count)}, strides{py::ssize_t(4 * columns)};
    if (columns > 1) {
        shape.push_back(columns);
        strides.push_back(4);
    }
    py::array view(py::dtype::of<float>(), shape, strides, data, owner);
    view.attr("setflags")(py::arg("write") = false);
    return view;
}

py::array perPoint(const HairStrands& h, const std::vector<float>& values, float fallback,
                   py::handle owner) {
    if (!values.empty()) return floatView(values.data(), values.size(), 1, owner);
    py::array_t<float> out(py::ssize_t(h.pointCount()));
    std::fill_n(out.mutable_data(), h.pointCount(), fallback);
    return out;
}

HairPtr makeStrands(py::handle points, py::object segments, py::object thickness,
                    py::object transparency, py::object colors, py::object defaultSegments,
                    float defaultThickness, float defaultTransparency, py::handle defaultColor,
                    const std::string& info) {
    auto h = std::make_shared<HairStrands>();
    h->points = rowsOf<glm::vec3, 3>(points, "points");
    if (!segments.is_none()) {
        h->segments = segmentsOf(segments);
        if (h->segments.empty()) throw InvalidArgument("segments must not be empty");
    } else if (!defaultSegments.is_none()) {
        const long long d = defaultSegments.cast<long long>();
        if (d < 0 || d > 65535) throw InvalidArgument("default_segments must be in [0, 65535]");
        h->defaultSegments = uint32_t(d);
    } else {
        throw InvalidArgument("HairStrands needs segments (per strand) or default_segments");
    }
    if (!thickness.is_none()) h->thickness = rowsOf<float, 1>(thickness, "thickness");
    if (!transparency.is_none()) h->transparency = rowsOf<float, 1>(transparency, "transparency");
    if (!colors.is_none()) h->colors = rowsOf<glm::vec3, 3>(colors, "colors");
    h->defaultThickness = defaultThickness;
    h->defaultTransparency = defaultTransparency;
    h->defaultColor = toVec3(defaultColor, "default_color");
    h->info = info;
    for (char c : info)
        if (c < 32 || c > 126) throw InvalidArgument("info must be printable ASCII");
    h->validate();
    return h;
}

const char* const kStyles[] = {"straight", "wavy", "curly"};
const char* const kModels[] = {"kajiya_kay", "marschner", "sadeghi"}; // HairModel's order

// generate_fur's arguments: the mesh, its parameters and an optional texture.
struct FurCall {
    std::shared_ptr<const Mesh> mesh;
    FurParams params;
    ImageU8 texture;
    bool hasTexture = false;
};

std::string materialRepr(const HairMaterial& m) {
    std::ostringstream s;
    auto v3 = [&](const glm::vec3& v) { s << "(" << v.x << ", " << v.y << ", " << v.z << ")"; };
    s << "<weft.HairMaterial " << kModels[int(m.model)] << " diffuse=";
    v3(m.diffuse);
    if (m.model == HairModel::KajiyaKay) {
        s << " specular=";
        v3(m.specular);
        s << " shininess=" << m.shininess;
    } else {
        s << " shift=";
        v3(m.shift);
        s << " width=";
        v3(m.width);
        if (m.model == HairModel::Marschner) {
            s << " eta=" << m.eta << " absorption=";
            v3(m.absorption);
            s << " caustic_width=" << m.causticWidth;
        } else {
            s << " intensity=";
            v3(m.intensity);
            s << " tt_azimuthal_width=" << m.ttAzimuthalWidth
              << " glint_intensity=" << m.glintIntensity;
        }
    }
    s << ">";
    return s.str();
}

} // namespace

void bindHair(py::module_& m) {
    py::class_<HairStrands, HairPtr>(
        m, "HairStrands",
        "Hair strands as stored in .hair files (SPEC §5.1): points root to tip, strand after\n"
        "strand, with per-strand segment counts (or one default) and optional per-point\n"
        "thickness, transparency and colour (linear RGB). Immutable once made; the array\n"
        "properties are read-only (zero-copy where the strands hold the array, else filled\n"
        "with the default).")
        .def(py::init(&makeStrands), py::arg("points"), py::arg("segments") = py::none(),
             py::arg("thickness") = py::none(), py::arg("transparency") = py::none(),
             py::arg("colors") = py::none(), py::kw_only(),
             py::arg("default_segments") = py::none(), py::arg("default_thickness") = 1.0f,
             py::arg("default_transparency") = 0.0f,
             py::arg("default_color") = py::make_tuple(1.0, 1.0, 1.0), py::arg("info") = "",
             "points (P,3); segments (S,) integers with sum(segments + 1) == P, or\n"
             "default_segments for strands of equal length; thickness, transparency (P,),\n"
             "colors (P,3). Raises weft.InvalidArgument for bad shapes, NaN/inf or counts.")
        .def_property_readonly("points",
                               [](py::object self) {
                                   const auto& h = self.cast<const HairStrands&>();
                                   return floatView(&h.points[0].x, h.pointCount(), 3, self);
                               })
        .def_property_readonly(
            "segments",
            [](const HairStrands& h) {
                py::array_t<uint16_t> out(py::ssize_t(h.strandCount()));
                for (size_t s = 0; s < h.strandCount(); ++s)
                    out.mutable_data()[s] =
                        h.segments.empty() ? uint16_t(h.defaultSegments) : h.segments[s];
                return out;
            },
            "Segments per strand (uint16, points = segments + 1).")
        .def_property_readonly(
            "offsets",
            [](const HairStrands& h) {
                const std::vector<uint64_t> o = h.offsets();
                py::array_t<int64_t> out(py::ssize_t(o.size()));
                for (size_t i = 0; i < o.size(); ++i) out.mutable_data()[i] = int64_t(o[i]);
                return out;
            },
            "First point of each strand, then the point count: (S + 1,) int64.")
        .def_property_readonly("thickness",
                               [](py::object self) {
                                   const auto& h = self.cast<const HairStrands&>();
                                   return perPoint(h, h.thickness, h.defaultThickness, self);
                               })
        .def_property_readonly("transparency",
                               [](py::object self) {
                                   const auto& h = self.cast<const HairStrands&>();
                                   return perPoint(h, h.transparency, h.defaultTransparency, self);
                               })
        .def_property_readonly("colors",
                               [](py::object self) -> py::array {
                                   const auto& h = self.cast<const HairStrands&>();
                                   if (!h.colors.empty())
                                       return floatView(&h.colors[0].x, h.pointCount(), 3, self);
                                   return rowsArray(
                                       std::vector<glm::vec3>(h.pointCount(), h.defaultColor));
                               })
        .def_property_readonly(
            "arrays",
            [](const HairStrands& h) {
                std::vector<std::string> out;
                if (!h.segments.empty()) out.push_back("segments");
                out.push_back("points");
                if (!h.thickness.empty()) out.push_back("thickness");
                if (!h.transparency.empty()) out.push_back("transparency");
                if (!h.colors.empty()) out.push_back("colors");
                return out;
            },
            "The arrays these strands hold (what save_hair writes), in file order.")
        .def_property_readonly("strand_count", &HairStrands::strandCount)
        .def_property_readonly("point_count", &HairStrands::pointCount)
        .def_property_readonly("default_segments",
                               [](const HairStrands& h) { return h.defaultSegments; })
        .def_property_readonly("default_thickness",
                               [](const HairStrands& h) { return h.defaultThickness; })
        .def_property_readonly("default_transparency",
                               [](const HairStrands& h) { return h.defaultTransparency; })
        .def_property_readonly("default_color",
                               [](const HairStrands& h) { return fromVec3(h.defaultColor); })
        .def_property_readonly("info", [](const HairStrands& h) { return h.info; })
        .def_property_readonly(
            "warnings", [](const HairStrands& h) { return h.warnings; },
            "What the loader tolerated (unknown flag bits, trailing bytes).")
        .def(
            "tangents",
            [](const HairStrands& h) {
                std::vector<glm::vec3> t;
                {
                    py::gil_scoped_release release;
                    t = strandTangents(h);
                }
                return rowsArray(t);
            },
            "Unit tangent per point (P,3): central differences, one-sided at strand ends.")
        .def(
            "ribbons",
            [](const HairStrands& h, py::handle eye, float widthScale) {
                const glm::vec3 e = toVec3(eye, "eye");
                std::vector<glm::vec3> r;
                {
                    py::gil_scoped_release release;
                    r = strandRibbons(h, e, widthScale);
                }
                return rowsArray(r);
            },
            py::arg("eye"), py::arg("width_scale") = 1.0f,
            "Camera-facing ribbon vertices (2P,3): point i gives p -/+ s * w / 2, s = unit(t x\n"
            "(eye - p)), w = width_scale * thickness.")
        .def(
            "ribbon_indices",
            [](const HairStrands& h) {
                const std::vector<uint32_t> idx = ribbonIndices(h);
                return arrayOf<uint32_t>(idx, {py::ssize_t(idx.size() / 3), 3});
            },
            "Triangles (T,3) uint32 over ribbons(): two per segment, facing the eye.")
        .def(
            "to_bytes",
            [](const HairStrands& h, bool zUp) {
                const std::vector<uint8_t> b = serializeHair(h, zUp);
                return py::bytes(reinterpret_cast<const char*>(b.data()), b.size());
            },
            py::arg("z_up") = false, "The .hair file bytes (see save_hair).")
        .def("__repr__", [](const HairStrands& h) {
            return "<weft.HairStrands " + std::to_string(h.strandCount()) + " strands, " +
                   std::to_string(h.pointCount()) + " points>";
        });

    m.def(
        "hair_from_bytes",
        [](py::bytes data, bool zUp) {
            const std::string s = data;
            py::gil_scoped_release release;
            return std::make_shared<HairStrands>(
                parseHair(reinterpret_cast<const uint8_t*>(s.data()), s.size(), zUp, "<bytes>"));
        },
        py::arg("data"), py::arg("z_up") = false, "Parses the bytes of a .hair file.");
    m.def(
        "load_hair",
        [](const std::string& path, bool zUp) {
            py::gil_scoped_release release;
            return std::make_shared<HairStrands>(loadHair(path, zUp));
        },
        py::arg("path"), py::arg("z_up") = false,
        "Reads a .hair file (weft.IoError if missing, truncated or inconsistent). z_up: the file\n"
        "is Z-up like the public models; points become Y-up, (x, y, z) -> (x, z, -y).");
    m.def(
        "save_hair",
        [](const std::string& path, const HairStrands& h, bool zUp) {
            py::gil_scoped_release release;
            saveHair(path, h, zUp);
        },
        py::arg("path"), py::arg("strands"), py::arg("z_up") = false,
        "Writes a .hair file with the arrays the strands hold (z_up: rotate back to Z-up).");

    const auto style = std::make_tuple(
        field("strands", &HairStyle::strands), field("points", &HairStyle::points),
        enumField("style", &HairStyle::kind, kStyles), field("length", &HairStyle::length),
        field("length_jitter", &HairStyle::lengthJitter),
        field("wave_amplitude", &HairStyle::waveAmplitude),
        field("wave_frequency", &HairStyle::waveFrequency),
        field("curl_radius", &HairStyle::curlRadius), field("droop", &HairStyle::droop),
        field("scalp_center", &HairStyle::scalpCenter),
        field("scalp_radii", &HairStyle::scalpRadii),
        field("scalp_cutoff", &HairStyle::scalpCutoff), field("seed", &HairStyle::seed),
        field("threads", &HairStyle::threads));
    defFunction(
        m, "generate_hair",
        [](const HairStyle& s) {
            py::gil_scoped_release release;
            return std::make_shared<HairStrands>(generateHair(s));
        },
        style,
        "Procedural hair on the upper part of an ellipsoid scalp (style 'straight', 'wavy' or\n"
        "'curly'). `points` is the total: each strand gets points // strands points and the\n"
        "first points % strands one more (the seed's sizes: 160,000 = 10,000 x 16, 687,532 and\n"
        "1,031,268 = 10,000 and 15,000 strands of 68-69 points). wave_frequency: waves (curly:\n"
        "turns) per metre; droop in [0, 1]: how far strands turn from the normal towards -Y.");

    using Fur = FurCall;
    const auto fur = std::tuple_cat(
        std::make_tuple(required(field<std::shared_ptr<Mesh>, Fur>(
            "mesh", [](const Fur& c) { return std::const_pointer_cast<Mesh>(c.mesh); },
            [](Fur& c, const std::shared_ptr<Mesh>& mesh) {
                if (!mesh) throw InvalidArgument("generate_fur: mesh must be a weft.Mesh");
                c.mesh = mesh;
            }))),
        within(&Fur::params, std::make_tuple(field("level", &FurParams::level),
                                             field("density", &FurParams::density),
                                             field("segments", &FurParams::segments),
                                             field("length", &FurParams::length),
                                             field("length_jitter", &FurParams::lengthJitter),
                                             field("direction_jitter", &FurParams::directionJitter),
                                             field("down", &FurParams::down))),
        std::make_tuple(field<py::object, Fur>(
            "texture", [](const Fur&) { return py::object(py::none()); },
            [](Fur& c, const py::object& t) {
                c.hasTexture = !t.is_none();
                if (c.hasTexture) c.texture = fromNumpy(t);
            })),
        within(&Fur::params, std::make_tuple(field("seed", &FurParams::seed),
                                             field("threads", &FurParams::threads))));
    defFunction(
        m, "generate_fur",
        [](const Fur& c) {
            py::gil_scoped_release release;
            return std::make_shared<HairStrands>(
                generateFur(*c.mesh, c.params, c.hasTexture ? &c.texture : nullptr));
        },
        fur,
        "Fur (002 listing 1): one strand per sub-triangle (level^2 per triangle, or\n"
        "round(sqrt(area * density)) ^ 2 when density > 0) from its centroid along the\n"
        "interpolated normal; `segments` segments of length / segments, each bent further by\n"
        "`down`. length_jitter (relative), direction_jitter (max radians) vary each strand;\n"
        "texture (uint8 sRGB image) colours each strand at its root's UV.");

    using HM = HairMaterial;
    const auto material = std::make_tuple(
        enumField("model", &HM::model, kModels), field("diffuse", &HM::diffuse),
        field("specular", &HM::specular), field("shininess", &HM::shininess),
        field("shift", &HM::shift), field("width", &HM::width), field("eta", &HM::eta),
        field("absorption", &HM::absorption), field("caustic_width", &HM::causticWidth),
        field("color_r", &HM::colorR), field("color_tt", &HM::colorTT),
        field("color_trt", &HM::colorTRT), field("intensity", &HM::intensity),
        field("tt_azimuthal_width", &HM::ttAzimuthalWidth),
        field("glint_intensity", &HM::glintIntensity), field("glint_width", &HM::glintWidth),
        field("glint_angle_min", &HM::glintAngleMin), field("glint_angle_max", &HM::glintAngleMax));
    py::class_<HM> hairMaterial(
        m, "HairMaterial",
        "Hair shading parameters (SPEC §5.2) for model 'kajiya_kay', 'marschner' or 'sadeghi'.\n"
        "Angles in radians; every setter validates (weft.InvalidArgument).");
    defInit(hairMaterial, validated<HM>, material,
            "A hair material of `model` with the other parameters as given (the rest at the\n"
            "defaults of weft/HairMaterial.h).");
    defProperties(hairMaterial, material);
    hairMaterial.def("__repr__", &materialRepr);

    m.def(
        "hair_shade_eval",
        [](const HairMaterial& material, py::handle t, py::handle l, py::handle v,
           py::object strandIds) {
            const auto tv = rowsOf<glm::vec3, 3>(t, "t"), lv = rowsOf<glm::vec3, 3>(l, "l"),
                       vv = rowsOf<glm::vec3, 3>(v, "v");
            std::vector<uint32_t> ids(tv.size(), 0);
            if (!strandIds.is_none()) {
                ids = integersOf<uint32_t>(strandIds, "strand_ids", "strand id");
                if (ids.size() != tv.size())
                    throw InvalidArgument("strand_ids must have shape (N,)");
            }
            std::vector<glm::vec3> out;
            {
                py::gil_scoped_release release;
                out = evaluateHairShading(material, tv, lv, vv, ids);
            }
            return rowsArray(out);
        },
        py::arg("material"), py::arg("t"), py::arg("l"), py::arg("v"),
        py::arg("strand_ids") = py::none(),
        "Testing/analysis entry point: evaluates glsl/common/hair_shading.glsl's hairShade() in a\n"
        "Vulkan compute shader for tangents t, light directions l and view directions v ((N,3),\n"
        "normalised here) and strand ids (glint angle); returns f (N,3) float32.");
}

} // namespace weft::py_bind
