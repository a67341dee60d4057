// Bindings of the BTF subsystem (private; the Python API is the weft.btf package):
// BtfSamples, Bonn-layout IO, synthetic rendering, linear/specular/Blinn-Phong fits, errors.
// Material maps cross as dicts of NumPy arrays (H, W, 3) float32 (see weft.btf.BtfMaterial).
#include <cmath>
#include <cstring>

#include <pybind11/stl.h>

#include <weft/BtfIo.h>
#include <weft/BtfNonlinear.h>
#include <weft/BtfSynth.h>

#include <weft/BtfRenderMaterial.h>

#include "Convert.h"
#include "Fields.h"
#include "btf/BtfImageCodec.h"

namespace weft::py_bind {

namespace {

std::vector<float> floatArray(py::handle obj, const std::string& name,
                              const std::vector<py::ssize_t>& shape) {
    auto a = numericArray(obj, name);
    std::string want = "(";
    for (size_t i = 0; i < shape.size(); ++i) want += (i ? ", " : "") + std::to_string(shape[i]);
    want += ")";
    bool ok = a.ndim() == py::ssize_t(shape.size());
    for (size_t i = 0; ok && i < shape.size(); ++i) ok = a.shape(py::ssize_t(i)) == shape[i];
    if (!ok) throw InvalidArgument(name + " must have shape " + want);
    std::vector<float> out(size_t(a.size()));
    const double* d = a.data();
    for (size_t i = 0; i < out.size(); ++i) {
        if (!std::isfinite(d[i])) throw InvalidArgument(name + " must be finite (got NaN or inf)");
        out[i] = float(d[i]);
    }
    return out;
}

const char* const kGammas[] = {"raw", "linear"};

std::vector<BtfAngles> anglesFrom(py::handle obj) {
    auto a = numericArray(obj, "angles");
    if (a.ndim() != 2 || a.shape(1) != 4 || a.shape(0) < 1)
        throw InvalidArgument("angles must have shape (S, 4): θ_l, φ_l, θ_v, φ_v in degrees");
    std::vector<BtfAngles> out;
    auto r = a.unchecked<2>();
    for (py::ssize_t s = 0; s < a.shape(0); ++s)
        out.push_back({float(r(s, 0)), float(r(s, 1)), float(r(s, 2)), float(r(s, 3))});
    return out;
}

BtfMaterialMaps mapsFrom(py::ssize_t h, py::ssize_t w, py::dict d) {
    BtfMaterialMaps m;
    m.width = int(w);
    m.height = int(h);
    m.normal = floatArray(d["normal"], "normal", {h, w, 3});
    m.albedo = floatArray(d["albedo"], "albedo", {h, w, 3});
    m.ambient = floatArray(d["ambient"], "ambient", {h, w, 3});
    if (d.contains("specular") && !d["specular"].is_none())
        m.specular = floatArray(d["specular"], "specular", {h, w, 3});
    if (d.contains("exponent_map") && !d["exponent_map"].is_none())
        m.exponentMap = floatArray(d["exponent_map"], "exponent_map", {h, w});
    m.exponent = d.contains("exponent") ? d["exponent"].cast<float>() : 1.0f;
    m.flatSpecularNormal =
        d.contains("flat_specular_normal") && d["flat_specular_normal"].cast<bool>();
    m.clampDiffuse = d.contains("clamp_diffuse") && d["clamp_diffuse"].cast<bool>();
    for (size_t i = 0; i < m.normal.size(); i += 3) {
        const float len = std::sqrt(m.normal[i] * m.normal[i] + m.normal[i + 1] * m.normal[i + 1] +
                                    m.normal[i + 2] * m.normal[i + 2]);
        if (std::fabs(len - 1.0f) > 1e-3f) throw InvalidArgument("normals must have unit length");
    }
    m.validate();
    return m;
}

BtfMaterialMaps mapsFrom(const BtfSamples& samples, py::dict d) {
    return mapsFrom(samples.height(), samples.width(), d);
}

py::dict mapsTo(const BtfMaterialMaps& m) {
    const py::ssize_t h = m.height, w = m.width;
    py::dict d;
    d["normal"] = arrayOf<float>(m.normal, {h, w, 3});
    d["albedo"] = arrayOf<float>(m.albedo, {h, w, 3});
    d["ambient"] = arrayOf<float>(m.ambient, {h, w, 3});
    d["specular"] =
        m.specular.empty() ? py::object(py::none()) : arrayOf<float>(m.specular, {h, w, 3});
    d["exponent"] = m.exponent;
    d["exponent_map"] =
        m.exponentMap.empty() ? py::object(py::none()) : arrayOf<float>(m.exponentMap, {h, w});
    d["flat_specular_normal"] = m.flatSpecularNormal;
    d["clamp_diffuse"] = m.clampDiffuse;
    return d;
}

py::dict linearTo(const BtfLinearFit& f) {
    const py::ssize_t h = f.height, w = f.width;
    py::dict d;
    d["texture"] = arrayOf<float>(f.texture, {h, w, 3});
    d["normal"] = arrayOf<float>(f.normal, {h, w, 3});
    d["ambient"] = arrayOf<float>(f.ambient, {h, w, 3});
    d["dark"] = boolArray(f.dark, {h, w});
    d["dark_texels"] = f.darkTexels;
    d["dark_channels"] = f.darkChannels;
    return d;
}

BtfLinearFit linearFrom(const BtfSamples& samples, py::dict d) {
    const py::ssize_t h = samples.height(), w = samples.width();
    BtfLinearFit f;
    f.width = samples.width();
    f.height = samples.height();
    f.texture = floatArray(d["texture"], "texture", {h, w, 3});
    f.normal = floatArray(d["normal"], "normal", {h, w, 3});
    f.ambient = floatArray(d["ambient"], "ambient", {h, w, 3});
    return f;
}

const char* const kSolvers[] = {"auto", "builtin", "ceres"};

} // namespace

void bindBtf(py::module_& m) {
    m.def(
        "btf_render_material",
        [](py::dict maps) {
            py::array normal = py::array::ensure(maps["normal"]);
            if (!normal || normal.ndim() != 3) throw InvalidArgument("normal must be (H, W, 3)");
            return btfRenderMaterial(mapsFrom(normal.shape(0), normal.shape(1), maps));
        },
        py::arg("maps"), "The renderer's Material for BTF maps (BtfMaterial.core_maps()).");
    m.def(
        "btf_drawn_maps",
        [](py::dict maps) {
            py::array normal = py::array::ensure(maps["normal"]);
            if (!normal || normal.ndim() != 3) throw InvalidArgument("normal must be (H, W, 3)");
            return mapsTo(btfDrawnMaps(mapsFrom(normal.shape(0), normal.shape(1), maps)));
        },
        py::arg("maps"), "BTF maps as the renderer draws them (BtfMaterial.as_drawn()).");

    py::class_<BtfSamples>(m, "BtfSamples",
                           "BTF measurements: per sample (light, view) an RGB image; values "
                           "float32 (S, 3, H, W), angles (S, 4) degrees θ_l, φ_l, θ_v, φ_v.")
        .def(py::init([](py::handle values, py::handle angles) {
                 auto ang = anglesFrom(angles);
                 auto a = numericArray(values, "values");
                 if (a.ndim() != 4 || a.shape(0) != py::ssize_t(ang.size()) || a.shape(1) != 3)
                     throw InvalidArgument(
                         "values must have shape (S, 3, H, W) with S = len(angles)");
                 BtfSamples s(int(a.shape(3)), int(a.shape(2)), ang);
                 const double* d = a.data();
                 for (size_t i = 0; i < s.values().size(); ++i) s.values()[i] = float(d[i]);
                 s.requireFinite();
                 return s;
             }),
             py::arg("values"), py::arg("angles"),
             "Samples from values (S, 3, H, W) and angles (S, 4): (θ_l, φ_l, θ_v, φ_v) in "
             "degrees per sample. Values must be finite (InvalidArgument otherwise).")
        .def_property_readonly("width", &BtfSamples::width)
        .def_property_readonly("height", &BtfSamples::height)
        .def_property_readonly("count", &BtfSamples::count)
        .def_property_readonly(
            "values",
            [](const BtfSamples& s) {
                return arrayOf<float>(s.values(), {s.count(), 3, s.height(), s.width()});
            },
            "A copy of the samples, float32 (S, 3, H, W).")
        .def_property_readonly(
            "angles",
            [](const BtfSamples& s) {
                py::array_t<float> out({s.count(), 4});
                for (int i = 0; i < s.count(); ++i) {
                    const BtfAngles& a = s.angles()[size_t(i)];
                    const float v[4] = {a.thetaLight, a.phiLight, a.thetaView, a.phiView};
                    std::memcpy(out.mutable_data() + i * 4, v, sizeof v);
                }
                return out;
            })
        .def_property_readonly("light_dirs",
                               [](const BtfSamples& s) {
                                   py::array_t<float> out({s.count(), 3});
                                   for (int i = 0; i < s.count(); ++i)
                                       for (int k = 0; k < 3; ++k)
                                           out.mutable_data()[i * 3 + k] = s.light(i)[k];
                                   return out;
                               })
        .def_property_readonly("view_dirs",
                               [](const BtfSamples& s) {
                                   py::array_t<float> out({s.count(), 3});
                                   for (int i = 0; i < s.count(); ++i)
                                       for (int k = 0; k < 3; ++k)
                                           out.mutable_data()[i * 3 + k] = s.view(i)[k];
                                   return out;
                               })
        .def_property_readonly(
            "jpeg_cells",
            [](const BtfSamples& s) -> py::object {
                const BtfJpegCells* cells = s.jpegCells();
                if (!cells) return py::none();
                const size_t count = size_t(s.count()), nc = cells->components.size();
                py::list comps;
                for (size_t c = 0; c < nc; ++c) {
                    const auto& comp = cells->components[c];
                    const size_t bh = size_t(comp.blocksHigh), bw = size_t(comp.blocksWide);
                    py::array_t<int16_t> coef({count, bh, bw, size_t(8), size_t(8)});
                    py::array_t<uint16_t> quant({count, size_t(8), size_t(8)});
                    int16_t* co = coef.mutable_data();
                    uint16_t* qo = quant.mutable_data();
                    for (size_t k = 0; k < count; ++k) {
                        const int16_t* src = cells->coefficients.data() +
                                             k * cells->coefficientsPerSample + comp.offset;
                        std::copy(src, src + bh * bw * 64, co + k * bh * bw * 64);
                        const uint16_t* q = cells->quant.data() + (k * nc + c) * 64;
                        std::copy(q, q + 64, qo + k * 64);
                    }
                    py::dict d;
                    d["coefficients"] = coef;
                    d["quant"] = quant;
                    d["sampling"] = py::make_tuple(comp.hSampling, comp.vSampling);
                    comps.append(d);
                }
                py::dict out;
                out["ycbcr"] = cells->ycbcr;
                out["components"] = comps;
                return out;
            })
        .def("__repr__", [](const BtfSamples& s) {
            return "<weft.BtfSamples " + std::to_string(s.count()) + " samples of " +
                   std::to_string(s.width()) + "x" + std::to_string(s.height()) + " RGB>";
        });

    m.def(
        "btf_standard_directions",
        [] {
            const auto& d = btfStandardDirections();
            py::array_t<float> out({py::ssize_t(d.size()), py::ssize_t(2)});
            for (size_t i = 0; i < d.size(); ++i) {
                out.mutable_data()[i * 2] = d[i].x;
                out.mutable_data()[i * 2 + 1] = d[i].y;
            }
            return out;
        },
        "The 81 directions the Bonn database uses for lights and views, (81, 2) as (θ, φ) in "
        "degrees: rings θ = 0, 15, ..., 75, each by increasing φ.");
    m.def(
        "btf_decode_image",
        [](py::bytes data, const std::string& name) -> py::object {
            const std::string raw = data;
            const std::vector<uint8_t> bytes(raw.begin(), raw.end());
            DecodedImage img;
            {
                py::gil_scoped_release release;
                img = decodeBtfImage(bytes, name);
            }
            const std::vector<py::ssize_t> shape = {img.height, img.width, img.channels};
            if (!img.pixels16.empty()) return py::array_t<uint16_t>(shape, img.pixels16.data());
            return py::array_t<uint8_t>(shape, img.pixels.data());
        },
        py::arg("data"), py::arg("name") = "<bytes>",
        "Decodes JPEG or PNG bytes as the BTF reader does (values as stored, (H, W, C) uint8, or\n"
        "uint16 for 16-bit PNG); IoError for anything else or anything corrupt.");
    m.def(
        "btf_parse_file_name",
        [](const std::string& name) -> py::object {
            BtfAngles a;
            if (!parseBtfFileName(name, a)) return py::none();
            return py::make_tuple(a.thetaLight, a.phiLight, a.thetaView, a.phiView);
        },
        py::arg("name"),
        "(θ_l, φ_l, θ_v, φ_v) in degrees parsed from a Bonn file name's tl/pl/tv/pv keys, or "
        "None when one of them is missing.");
    const auto load = std::make_tuple(
        required(field<py::object, BtfLoadOptions>(
            "views", [](const BtfLoadOptions&) { return py::object(py::none()); },
            [](BtfLoadOptions& o, const py::object& views) {
                o.views.clear();
                if (views.is_none()) return;
                for (const glm::vec2& v : rowsOf<glm::vec2, 2>(views, "views"))
                    o.views.push_back(v);
                if (o.views.empty())
                    throw InvalidArgument("views must have shape (V, 2): θ_v, φ_v in degrees");
            })),
        enumField("gamma", &BtfLoadOptions::gamma, kGammas),
        field("threads", &BtfLoadOptions::threads),
        field("jpeg_cells", &BtfLoadOptions::jpegCells));
    defFunctionWith<const std::string&>(
        m, "btf_load",
        [](const std::string& path, const BtfLoadOptions& o) {
            py::gil_scoped_release release;
            return loadBtf(path, o);
        },
        std::make_tuple(py::arg("path")), load,
        "Loads a BTF in the Bonn layout (a folder or a zip) as BtfSamples: `views` (V, 2) "
        "(θ_v, φ_v) degrees picks views (None = all); gamma 'raw' keeps the stored values, "
        "'linear' linearises them (value^2.2); jpeg_cells also keeps JPEG files' quantised DCT cells. Raises "
        "IoError naming the file (or the missing angles).");
    using W = BtfWriteOptions;
    const auto write = std::make_tuple(
        field<std::string, W>(
            "format", [](const W& o) { return o.format == BtfImageFormat::Jpeg ? "jpg" : "png"; },
            [](W& o, const std::string& format) {
                if (format != "jpg" && format != "jpeg" && format != "png")
                    throw InvalidArgument("format must be 'jpg' or 'png', got '" + format + "'");
                o.format = format == "png" ? BtfImageFormat::Png : BtfImageFormat::Jpeg;
            }),
        field("quality", &W::jpegQuality), field("zip", &W::zip),
        enumField("gamma", &W::gamma, kGammas), field("prefix", &W::prefix));
    defFunctionWith<const std::string&, const BtfSamples&>(
        m, "btf_write",
        [](const std::string& path, const BtfSamples& samples, const W& o) {
            py::gil_scoped_release release;
            writeBtf(path, samples, o);
        },
        std::make_tuple(py::arg("path"), py::arg("samples")), write,
        "Writes samples (values in [0, 1], clipped, 8 bits) in the Bonn layout under "
        "path/UBO2003/MANYFILES/tvTTT_pvPPP/ as 'jpg' or 'png', optionally zipped; angles "
        "must be whole degrees.");
    m.def(
        "btf_render",
        [](py::dict maps, py::handle angles, py::object height, bool wrap, int threads) {
            auto ang = anglesFrom(angles);
            auto n = numericArray(maps["normal"], "normal");
            if (n.ndim() != 3) throw InvalidArgument("normal must have shape (H, W, 3)");
            BtfSamples shape(int(n.shape(1)), int(n.shape(0)), {ang[0]});
            BtfMaterialMaps mm = mapsFrom(shape, maps);
            BtfShadowing sh;
            sh.wrap = wrap;
            if (!height.is_none())
                sh.height = floatArray(height, "height", {n.shape(0), n.shape(1)});
            py::gil_scoped_release release;
            return renderBtf(mm, ang, sh, threads);
        },
        py::arg("maps"), py::arg("angles"), py::arg("height") = py::none(), py::arg("wrap") = true,
        py::arg("threads") = 0,
        "Renders material maps (normal, diffuse, ... as from a fit) for each of `angles` (S, "
        "4) into BtfSamples; with a height field (H, W) a texel whose ray to the light passes "
        "below it gets only the ambient term (wrap: the field tiles).");
    using LO = BtfLinearOptions;
    defFunctionWith<const BtfSamples&>(
        m, "btf_fit_linear",
        [](const BtfSamples& s, const LO& o) {
            BtfLinearFit f;
            {
                py::gil_scoped_release release;
                f = fitBtfLinear(s, o);
            }
            return linearTo(f);
        },
        std::make_tuple(py::arg("samples")),
        std::make_tuple(
            field("robust", &LO::robust), field("robust_iterations", &LO::robustIterations),
            field("dark_threshold", &LO::darkThreshold), field("threads", &LO::threads)),
        "Per-texel linear fit of all samples (normal, albedo, ambient; SPEC §4), optionally "
        "robust (samples darker than the fit by dark_threshold dropped over robust_iterations "
        "rounds). Returns a dict of arrays. Raises InvalidArgument when the lights do not "
        "span 3D.");
    m.def(
        "btf_solve_linear",
        [](const BtfSamples& s, py::handle texture, int threads) {
            auto t = floatArray(texture, "texture", {s.height(), s.width(), 3});
            BtfLinearFit f;
            {
                py::gil_scoped_release release;
                LO o;
                o.darkThreshold = 0.0f;
                o.threads = threads;
                f = solveBtfLinear(s, t, o);
            }
            return linearTo(f);
        },
        py::arg("samples"), py::arg("texture"), py::arg("threads") = 0,
        "The linear least squares for a given texture (H, W, 3) instead of the sample mean: "
        "per texel the normal and ambient that best explain the samples. Returns the same "
        "dict as btf_fit_linear.");
    m.def(
        "btf_material_from_linear",
        [](const BtfSamples& s, py::dict linear) {
            return mapsTo(btfMaterialFromLinear(linearFrom(s, linear)));
        },
        py::arg("samples"), py::arg("linear"),
        "The seed's material maps (no specular) from a btf_fit_linear result.");
    using SO = BtfSpecularOptions;
    defFunctionWith<const BtfSamples&, py::dict>(
        m, "btf_fit_specular",
        [](const BtfSamples& s, py::dict linear, const SO& o) {
            const BtfLinearFit f = linearFrom(s, linear);
            BtfSpecularFit r;
            {
                py::gil_scoped_release release;
                r = fitBtfSpecular(s, f, o);
            }
            py::dict d;
            d["maps"] = mapsTo(r.maps);
            d["curve"] = arrayOf<double>(r.curve, {py::ssize_t(r.curve.size())});
            d["specular_sample"] = r.specularSample;
            return d;
        },
        std::make_tuple(py::arg("samples"), py::arg("linear")),
        std::make_tuple(field("flat_specular_normal", &SO::flatSpecularNormal),
                        field("max_exponent", &SO::maxExponent), field("per_texel", &SO::perTexel),
                        field("threads", &SO::threads)),
        "Specular map from the residual of the θ_l = 0 sample and the exponent minimising the "
        "total squared error (SPEC eq. 4.29/4.30). Returns {'maps', 'curve' (error per "
        "candidate exponent), 'specular_sample'}.");
    m.def(
        "btf_sample_errors",
        [](const BtfSamples& s, py::dict maps, bool reconstruct, int threads) -> py::object {
            const BtfMaterialMaps mm = mapsFrom(s, maps);
            std::vector<float> recon;
            std::vector<double> errors;
            {
                py::gil_scoped_release release;
                errors = btfSampleErrors(s, mm, reconstruct ? &recon : nullptr, threads);
            }
            auto e = arrayOf<double>(errors, {py::ssize_t(errors.size())});
            if (!reconstruct) return e;
            return py::make_tuple(e, arrayOf<float>(recon, {s.count(), 3, s.height(), s.width()}));
        },
        py::arg("samples"), py::arg("maps"), py::arg("reconstruct") = false, py::arg("threads") = 0,
        "Per-sample mean squared error (S,) of `maps` against the samples; with "
        "reconstruct=True also the model's samples (S, 3, H, W), as a tuple.");
    m.def(
        "btf_fit_lafortune",
        [](const BtfSamples& s, py::dict seed, int lobes, int maxIterations, int threads,
           bool visibility, bool fixedNormal) {
            const BtfMaterialMaps mm = mapsFrom(s, seed);
            BtfLafortuneFit f;
            {
                py::gil_scoped_release release;
                f = fitBtfLafortune(s, mm, lobes, maxIterations, threads, visibility, fixedNormal);
            }
            const py::ssize_t h = f.height, w = f.width, l = f.lobes;
            py::dict d;
            d["normal"] = arrayOf<float>(f.normal, {h, w, 3});
            d["diffuse"] = arrayOf<float>(f.diffuse, {h, w, 3});
            d["ambient"] = arrayOf<float>(f.ambient, {h, w, 3});
            d["lobe_albedo"] = arrayOf<float>(f.lobeAlbedo, {h, w, l, 3});
            d["lobe_shape"] = arrayOf<float>(f.lobeShape, {h, w, l, 4});
            d["mean_iterations"] = f.meanIterations;
            return d;
        },
        py::arg("samples"), py::arg("seed"), py::arg("lobes") = 1, py::arg("max_iterations") = 30,
        py::arg("threads") = 0, py::arg("visibility") = false, py::arg("fixed_normal") = false,
        "Per-texel Lafortune fit (`lobes` lobes, Levenberg-Marquardt) seeded from `seed` "
        "maps. Returns normal, diffuse, ambient, lobe_albedo (H, W, L, 3), lobe_shape (H, W, "
        "L, 4) and mean_iterations.");
    m.def(
        "btf_lafortune_errors",
        [](const BtfSamples& s, py::dict fit, int threads) {
            const py::ssize_t h = s.height(), w = s.width();
            BtfLafortuneFit f;
            f.width = s.width();
            f.height = s.height();
            auto shape = numericArray(fit["lobe_shape"], "lobe_shape");
            if (shape.ndim() != 4) throw InvalidArgument("lobe_shape must be (H, W, lobes, 4)");
            f.lobes = int(shape.shape(2));
            f.normal = floatArray(fit["normal"], "normal", {h, w, 3});
            f.diffuse = floatArray(fit["diffuse"], "diffuse", {h, w, 3});
            f.ambient = floatArray(fit["ambient"], "ambient", {h, w, 3});
            f.lobeAlbedo = floatArray(fit["lobe_albedo"], "lobe_albedo", {h, w, f.lobes, 3});
            f.lobeShape = floatArray(fit["lobe_shape"], "lobe_shape", {h, w, f.lobes, 4});
            std::vector<double> errors;
            {
                py::gil_scoped_release release;
                errors = btfLafortuneErrors(s, f, nullptr, threads);
            }
            return arrayOf<double>(errors, {py::ssize_t(errors.size())});
        },
        py::arg("samples"), py::arg("fit"), py::arg("threads") = 0,
        "Per-sample mean squared error (S,) of a btf_fit_lafortune result against the "
        "samples.");
    m.def("btf_have_ceres", &btfHaveCeres,
          "True when weft was built with Ceres Solver (btf_fit_blinn_phong solver='ceres').");
    m.def("btf_resolvable_exponent", &btfResolvableExponent, py::arg("samples"),
          py::arg("fraction") = 0.01,
          "The largest Blinn-Phong exponent the sampling resolves: a lobe at one sample's half "
          "vector keeps `fraction` of its peak at the nearest neighbouring half vector.");
    // The nonlinear fits' options, one declaration each: btf_fit_blinn_phong takes them all,
    // btf_blinn_phong_noise those that decide its noise estimate.
    using NL = BtfNonlinearOptions;
    const auto minExponent = field("min_exponent", &NL::minExponent);
    const auto maxExponent = field("max_exponent", &NL::maxExponent);
    const auto threads = field("threads", &NL::threads);
    const auto flat = field("flat_specular_normal", &NL::flatSpecularNormal);
    const auto luminance = field("luminance_normals", &NL::luminanceNormals);
    const auto seedArgs = std::make_tuple(py::arg("samples"), py::arg("seed"));
    defFunctionWith<const BtfSamples&, py::dict>(
        m, "btf_blinn_phong_noise",
        [](const BtfSamples& s, py::dict seed, const NL& o) {
            const BtfMaterialMaps mm = mapsFrom(s, seed);
            py::gil_scoped_release release;
            return btfBlinnPhongNoise(s, mm, o);
        },
        seedArgs, std::make_tuple(minExponent, maxExponent, threads, flat, luminance),
        "The data's noise level (σ of a sample's channel sum) that btf_fit_blinn_phong "
        "estimates for its cast-shadow classification when given noise=0.");
    defFunctionWith<const BtfSamples&, py::dict>(
        m, "btf_fit_blinn_phong",
        [](const BtfSamples& s, py::dict seed, const NL& o) {
            const BtfMaterialMaps mm = mapsFrom(s, seed);
            BtfNonlinearFit r;
            {
                py::gil_scoped_release release;
                r = fitBtfBlinnPhong(s, mm, o);
            }
            py::dict d;
            d["maps"] = mapsTo(r.maps);
            d["mean_iterations"] = r.meanIterations;
            d["solver"] = r.solver;
            d["shadowed_fraction"] = r.shadowedFraction;
            d["noise"] = r.noise;
            return d;
        },
        seedArgs,
        std::make_tuple(enumField("solver", &NL::solver, kSolvers),
                        field("max_iterations", &NL::maxIterations), minExponent, maxExponent,
                        threads, flat, field("visibility", &NL::visibility), luminance,
                        field("noise", &NL::noise), field("fixed_exponent", &NL::fixedExponent)),
        "Nonlinear per-texel Blinn-Phong fit (normal, ρ, a, k, exponent) seeded from `seed` "
        "maps, with the built-in Levenberg-Marquardt or Ceres ('auto', 'builtin', 'ceres'); "
        "visibility leaves estimated cast shadows out, their test bounded by the data's noise "
        "(noise 0: estimated, btf_blinn_phong_noise); fixed_exponent keeps the seed's exponent "
        "map. Returns {'maps', 'mean_iterations', 'solver', 'shadowed_fraction', 'noise'}.");
}

} // namespace weft::py_bind
