// Bindings of the IBL tools: weft.CubeMap, weft.Environment, weft.ShadowDome and the conversion,
// filtering and light-extraction functions (wrapped with conveniences by weft.ibl).
#include <cmath>
#include <cstring>

#include <pybind11/stl.h>

#include <weft/CubeMap.h>
#include <weft/Environment.h>
#include <weft/IblConvert.h>
#include <weft/IblFilter.h>
#include <weft/IblGpu.h>
#include <weft/IblLights.h>
#include <weft/ShadowDome.h>

#include "Convert.h"

namespace weft::py_bind {

namespace {

using FloatArray = py::array_t<float, py::array::c_style | py::array::forcecast>;

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

// (H, W, 3) float image (also accepts (H, W), (H, W, 1) grey and (H, W, 4), alpha dropped).
struct RgbImage {
    std::vector<float> pixels;
    int width = 0, height = 0;
    RgbView view() const { return {pixels.data(), width, height}; }
};

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
    py::array_t<float> out({py::ssize_t(height), py::ssize_t(width), py::ssize_t(3)});
    std::memcpy(out.mutable_data(), pixels.data(), pixels.size() * sizeof(float));
    return out;
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

// A CubeMap argument: a weft.CubeMap (used in place, kept alive by the caller's reference) or a
// (6, S, S, 3) array (copied).
struct CubeArg {
    CubeMap owned;
    const CubeMap* borrowed = nullptr;
    const CubeMap& get() const { return borrowed ? *borrowed : owned; }
    operator const CubeMap&() const { return get(); }
};

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

py::array_t<float> vec3Array(const std::vector<glm::vec3>& v) {
    py::array_t<float> out({py::ssize_t(v.size()), py::ssize_t(3)});
    for (size_t k = 0; k < v.size(); ++k)
        for (int c = 0; c < 3; ++c) out.mutable_data()[k * 3 + c] = v[k][c];
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
    std::vector<glm::vec3> v(sh.coeffs.begin(), sh.coeffs.end());
    return vec3Array(v);
}

glm::mat4 optionalMat4(py::handle obj, const std::string& name) {
    return obj.is_none() ? glm::mat4(1.0f) : toMat4(obj, name);
}

py::array_t<bool> maskArray(const std::vector<uint8_t>& valid, int size) {
    py::array_t<bool> out({py::ssize_t(6), py::ssize_t(size), py::ssize_t(size)});
    for (size_t k = 0; k < valid.size(); ++k) out.mutable_data()[k] = valid[k] != 0;
    return out;
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
    return py::make_tuple(std::move(c.cube), maskArray(c.valid, s));
}

} // namespace

void bindSky(py::module_& m); // bind_sky.cpp

void bindIbl(py::module_& m) {
    bindSky(m);
    py::class_<CubeMap>(
        m, "CubeMap",
        "RGB float cube map: faces +X, -X, +Y, -Y, +Z, -Z (Vulkan/OpenGL convention), each S x S,\n"
        "NumPy view (6, S, S, 3); optional mip chain. See weft/CubeMap.h for the orientation.")
        .def(py::init<int>(), py::arg("size"),
             "A cube map of size x size texels per face, all zero, one mip level.")
        .def(py::init([](py::handle faces) { return cubeFromArray(faces, "faces"); }),
             py::arg("faces"))
        .def_property_readonly("size", &CubeMap::size)
        .def_property_readonly("levels", &CubeMap::levels)
        .def_property_readonly(
            "faces", [](py::object self) { return levelView(self.cast<CubeMap&>(), 0, self); },
            "Writable (6, S, S, 3) float32 view of level 0 (call clear_mips after editing).")
        .def(
            "level",
            [](py::object self, int level) {
                return levelView(self.cast<CubeMap&>(), level, self);
            },
            py::arg("level"), "Writable (6, s, s, 3) view of mip level `level`.")
        .def("build_mips", &CubeMap::buildMips, "Solid-angle weighted 2x2 mips down to 1x1.")
        .def("clear_mips", &CubeMap::clearMips,
             "Drops every mip level above 0 (call after editing level 0).")
        .def(
            "sample",
            [](const CubeMap& c, py::handle dirs, float lod) {
                auto d = directions(dirs, "directions");
                if (!std::isfinite(lod)) throw InvalidArgument("lod must be finite");
                std::vector<glm::vec3> out(d.size());
                {
                    py::gil_scoped_release release;
                    for (size_t k = 0; k < d.size(); ++k) out[k] = c.sampleLod(d[k], lod);
                }
                return vec3Array(out);
            },
            py::arg("directions"), py::arg("lod") = 0.0f,
            "Seamless (trilinear) samples at (N, 3) directions -> (N, 3).")
        .def(
            "copy", [](const CubeMap& c) { return CubeMap(c); },
            "An independent copy of this cube map.")
        .def("__repr__", [](const CubeMap& c) {
            return "<weft.CubeMap size=" + std::to_string(c.size()) +
                   " levels=" + std::to_string(c.levels()) + ">";
        });

    m.def(
        "cube_coords",
        [](py::handle dirs) {
            auto d = directions(dirs, "directions");
            py::array_t<int> face(py::ssize_t(d.size()));
            py::array_t<float> uv({py::ssize_t(d.size()), py::ssize_t(2)});
            for (size_t k = 0; k < d.size(); ++k) {
                const CubeCoord c = cubeCoord(d[k]);
                face.mutable_data()[k] = c.face;
                uv.mutable_data()[k * 2] = c.u;
                uv.mutable_data()[k * 2 + 1] = c.v;
            }
            return py::make_tuple(face, uv);
        },
        py::arg("directions"), "Face index (N,) and face coordinates u, v (N, 2) of directions.");
    m.def(
        "cube_texel_directions",
        [](int size) {
            requireCubeSize(size);
            const py::ssize_t s = size;
            py::array_t<float> out({py::ssize_t(6), s, s, py::ssize_t(3)});
            for (int f = 0; f < 6; ++f)
                for (int j = 0; j < size; ++j)
                    for (int i = 0; i < size; ++i) {
                        const glm::vec3 d = cubeTexelDirection(f, i, j, size);
                        for (int c = 0; c < 3; ++c)
                            out.mutable_data()[(((size_t(f) * size + j) * size + i) * 3) + c] =
                                d[c];
                    }
            return out;
        },
        py::arg("size"), "Unit directions of all texel centres, (6, S, S, 3).");
    m.def(
        "cube_texel_solid_angles",
        [](int size) {
            requireCubeSize(size);
            py::array_t<double> out({py::ssize_t(size), py::ssize_t(size)});
            for (int j = 0; j < size; ++j)
                for (int i = 0; i < size; ++i)
                    out.mutable_data()[size_t(j) * size + i] = cubeTexelSolidAngle(i, j, size);
            return out;
        },
        py::arg("size"),
        "Exact texel solid angles of one face, (S, S) float64 (same for all faces).");

    m.def(
        "sphere_to_cube",
        [](py::handle image, int size, py::handle worldToSphere, float wrap, int ss) {
            RgbImage img = rgbImage(image, "sphere map");
            const glm::mat4 mat = optionalMat4(worldToSphere, "world_to_sphere");
            CaptureCube c;
            {
                py::gil_scoped_release release;
                c = sphereToCube(img.view(), mat, wrap, size, ss);
            }
            return captureTuple(std::move(c));
        },
        py::arg("image"), py::arg("size"), py::arg("world_to_sphere") = py::none(),
        py::arg("wrap") = 1.0f, py::arg("supersample") = 2,
        "Sphere map -> (CubeMap, valid mask (6, S, S) bool) (SPEC §4.2).");
    m.def(
        "fisheye_to_cube",
        [](py::handle image, int size, float fov, py::handle worldToCamera, int ss) {
            RgbImage img = rgbImage(image, "fisheye image");
            const glm::mat4 mat = optionalMat4(worldToCamera, "world_to_camera");
            CaptureCube c;
            {
                py::gil_scoped_release release;
                c = fisheyeToCube(img.view(), mat, fov, size, ss);
            }
            return captureTuple(std::move(c));
        },
        py::arg("image"), py::arg("size"), py::arg("fov"), py::arg("world_to_camera") = py::none(),
        py::arg("supersample") = 2, "Equidistant fisheye -> (CubeMap, valid mask).");
    m.def(
        "equirect_to_cube",
        [](py::handle image, int size, int ss) {
            RgbImage img = rgbImage(image, "equirectangular image");
            py::gil_scoped_release release;
            return equirectToCube(img.view(), size, ss);
        },
        py::arg("image"), py::arg("size"), py::arg("supersample") = 2,
        "Resamples an equirectangular (2:1) RGB float image into a radiance CubeMap of `size` "
        "per face, supersample² samples per texel.");
    m.def(
        "cube_to_equirect",
        [](py::handle cube, int width, int height) {
            const CubeArg c = toCube(cube, "cube");
            std::vector<float> px;
            {
                py::gil_scoped_release release;
                px = cubeToEquirect(c, width, height);
            }
            return imageArray(px, height, width);
        },
        py::arg("cube"), py::arg("width"), py::arg("height"),
        "The cube map as an equirectangular float32 image (height, width, 3).");
    m.def(
        "cube_to_sphere",
        [](py::handle cube, int size, py::handle worldToSphere, float wrap) {
            const CubeArg c = toCube(cube, "cube");
            const glm::mat4 mat = optionalMat4(worldToSphere, "world_to_sphere");
            std::vector<float> px;
            {
                py::gil_scoped_release release;
                px = cubeToSphere(c, size, mat, wrap);
            }
            return imageArray(px, size, size);
        },
        py::arg("cube"), py::arg("size"), py::arg("world_to_sphere") = py::none(),
        py::arg("wrap") = 1.0f,
        "The cube map as a sphere-map (mirror ball) float32 image (size, size, 3), seen along "
        "world_to_sphere (4x4, None = identity); wrap < 1 shows only that fraction of the "
        "ball's radius.");
    m.def(
        "fill_unseen",
        [](py::handle cube, py::handle valid) {
            CubeMap c = toCube(cube, "cube").get();
            const auto mask = maskVector(valid, "valid", py::ssize_t(6) * c.size() * c.size());
            py::gil_scoped_release release;
            fillUnseen(c, mask);
            return c;
        },
        py::arg("cube"), py::arg("valid"), "Push-pull fill of texels where valid is False.");

    m.def(
        "project_sh9",
        [](py::handle cube) {
            const CubeArg c = toCube(cube, "radiance");
            Sh9 sh;
            {
                py::gil_scoped_release release;
                sh = projectSh9(c);
            }
            return shArray(sh);
        },
        py::arg("radiance"),
        "SH9 radiance coefficients (9, 3), see weft/IblFilter.h for the order.");
    m.def(
        "sh_irradiance",
        [](py::handle sh, py::handle normals) {
            const Sh9 s = shFromArray(sh);
            auto n = directions(normals, "normals");
            for (auto& v : n) v = shIrradiance(s, v);
            return vec3Array(n);
        },
        py::arg("sh"), py::arg("normals"), "Irradiance (N, 3) at unit normals (N, 3) from SH9.");
    m.def(
        "irradiance_from_sh",
        [](py::handle sh, int size) {
            const Sh9 s = shFromArray(sh);
            py::gil_scoped_release release;
            return irradianceFromSh(s, size);
        },
        py::arg("sh"), py::arg("size"),
        "Irradiance CubeMap of `size` per face from SH9 radiance coefficients (9, 3).");
    m.def(
        "irradiance_exact",
        [](py::handle cube, int size, int sourceSize) {
            const CubeArg c = toCube(cube, "radiance");
            py::gil_scoped_release release;
            return irradianceExact(c, size, sourceSize);
        },
        py::arg("radiance"), py::arg("size") = 32, py::arg("source_size") = 64,
        "Irradiance CubeMap by the exact cosine convolution of the radiance resampled to "
        "source_size (the reference; constant radiance L gives πL).");
    m.def(
        "irradiance_exact_gpu",
        [](py::handle cube, int size, int sourceSize) {
            const CubeArg c = toCube(cube, "radiance");
            py::gil_scoped_release release;
            return irradianceExactGpu(c, size, sourceSize);
        },
        py::arg("radiance"), py::arg("size") = 32, py::arg("source_size") = 64,
        "irradiance_exact as a Vulkan compute shader on the selected device.");
    m.def(
        "irradiance_box_blur",
        [](py::handle cube, int size, int sphereSize, int radius, int passes) {
            const CubeArg c = toCube(cube, "radiance");
            py::gil_scoped_release release;
            return irradianceBoxBlur(c, size, sphereSize, radius, passes);
        },
        py::arg("radiance"), py::arg("size") = 32, py::arg("sphere_size") = 64,
        py::arg("radius") = 12, py::arg("passes") = 2,
        "The seed's irradiance approximation: the radiance as a sphere map box-blurred "
        "(radius texels, `passes` times), back into a cube map of `size`.");
    m.def(
        "irradiance_rotational_blur",
        [](py::handle cube, int size, float halfAngle, int steps) {
            const CubeArg c = toCube(cube, "radiance");
            py::gil_scoped_release release;
            return irradianceRotationalBlur(c, size, halfAngle, steps);
        },
        py::arg("radiance"), py::arg("size") = 32, py::arg("half_angle") = 1.0f,
        py::arg("steps") = 16,
        "The seed's irradiance approximation: blurs about three axes through half_angle "
        "radians in `steps` steps.");
    m.def(
        "phong_exact",
        [](py::handle cube, float shininess, int size, int sourceSize) {
            const CubeArg c = toCube(cube, "radiance");
            py::gil_scoped_release release;
            return phongExact(c, shininess, size, sourceSize);
        },
        py::arg("radiance"), py::arg("shininess"), py::arg("size") = 32,
        py::arg("source_size") = 64,
        "Phong-lobe prefiltered radiance (exponent `shininess`) by exact convolution of the "
        "radiance resampled to source_size.");
    m.def(
        "phong_sampled",
        [](py::handle cube, float shininess, int size, int samples) {
            const CubeArg c = toCube(cube, "radiance");
            py::gil_scoped_release release;
            return phongSampled(c, shininess, size, samples);
        },
        py::arg("radiance"), py::arg("shininess"), py::arg("size") = 32, py::arg("samples") = 64,
        "Phong-lobe prefiltered radiance (exponent `shininess`) by filtered importance "
        "sampling with `samples` per texel.");
    m.def(
        "prefilter_ggx",
        [](py::handle cube, int size, int levels, int samples) {
            const CubeArg c = toCube(cube, "radiance");
            py::gil_scoped_release release;
            return prefilterGgx(c, size, levels, samples);
        },
        py::arg("radiance"), py::arg("size") = 128, py::arg("levels") = 5, py::arg("samples") = 64,
        "GGX split-sum chain: mip m holds roughness m / (levels - 1).");
    m.def(
        "prefilter_ggx_gpu",
        [](py::handle cube, int size, int levels, int samples) {
            const CubeArg c = toCube(cube, "radiance");
            double ms = 0.0;
            CubeMap out;
            {
                py::gil_scoped_release release;
                out = prefilterGgxGpu(c, size, levels, samples, &ms);
            }
            return py::make_tuple(std::move(out), ms);
        },
        py::arg("radiance"), py::arg("size") = 128, py::arg("levels") = 5, py::arg("samples") = 64,
        "prefilter_ggx as a Vulkan compute shader: (CubeMap, dispatch wall ms).");
    m.def(
        "dfg_lut",
        [](int size, int samples) {
            std::vector<float> lut;
            {
                py::gil_scoped_release release;
                lut = dfgLut(size, samples);
            }
            py::array_t<float> out({py::ssize_t(size), py::ssize_t(size), py::ssize_t(2)});
            std::memcpy(out.mutable_data(), lut.data(), lut.size() * sizeof(float));
            return out;
        },
        py::arg("size") = 32, py::arg("samples") = 256,
        "Split-sum DFG table (roughness rows, n.v columns, [scale, bias]).");

    m.def(
        "extract_lights",
        [](py::handle cube, int downsample, float threshold, float relative, int maxLights,
           bool withLabels) -> py::object {
            const CubeArg c = toCube(cube, "radiance");
            LightExtractionParams p;
            p.downsample = downsample;
            p.threshold = threshold;
            p.relativeThreshold = relative;
            p.maxLights = maxLights;
            std::vector<EnvLight> lights;
            std::vector<int> labels;
            {
                py::gil_scoped_release release;
                lights = extractLights(c, p, withLabels ? &labels : nullptr);
            }
            py::list out;
            for (const auto& l : lights) {
                py::dict d;
                d["direction"] = fromVec3(l.direction);
                d["colour"] = fromVec3(l.colour);
                d["solid_angle"] = l.solidAngle;
                d["texels"] = l.texels;
                out.append(d);
            }
            if (!withLabels) return std::move(out);
            const py::ssize_t s = c.get().size();
            py::array_t<int> lab({py::ssize_t(6), s, s});
            std::memcpy(lab.mutable_data(), labels.data(), labels.size() * sizeof(int));
            return py::make_tuple(out, lab);
        },
        py::arg("radiance"), py::arg("downsample") = 32, py::arg("threshold") = 0.0f,
        py::arg("relative_threshold") = 8.0f, py::arg("max_lights") = 16, py::arg("labels") = false,
        "Threshold + connected components; list of dicts (direction, colour, solid_angle, texels),\n"
        "with labels=True also the (6, S, S) int array of light indices (-1: not a light).");

    py::class_<ShadowDome>(m, "ShadowDome", "Dome of N shadow lights over +Y (seed eq. 2.21-2.23).")
        .def(py::init([](py::handle cube, int count, const std::string& layout, int sourceSize) {
                 const CubeArg c = toCube(cube, "radiance");
                 const DomeLayout l = domeLayout(layout);
                 py::gil_scoped_release release;
                 return ShadowDome(c, count, l, sourceSize);
             }),
             py::arg("radiance"), py::arg("count"), py::arg("layout") = "fibonacci",
             py::arg("source_size") = 128,
             "A dome of `count` shadow lights over +Y laid out as 'fibonacci' (or the other "
             "layouts layout_directions names), each with the radiance of its cell of the "
             "environment (resampled to source_size).")
        .def_static(
            "layout_directions",
            [](int count, const std::string& layout) {
                return vec3Array(ShadowDome::directions(count, domeLayout(layout)));
            },
            py::arg("count"), py::arg("layout") = "fibonacci",
            "The unit directions (count, 3) of a dome layout, without an environment.")
        .def_property_readonly("count", &ShadowDome::size)
        .def_property_readonly("directions",
                               [](const ShadowDome& d) {
                                   std::vector<glm::vec3> v;
                                   for (const auto& l : d.lights()) v.push_back(l.direction);
                                   return vec3Array(v);
                               })
        .def_property_readonly("intensities",
                               [](const ShadowDome& d) {
                                   std::vector<glm::vec3> v;
                                   for (const auto& l : d.lights()) v.push_back(l.intensity);
                                   return vec3Array(v);
                               })
        .def_property_readonly("solid_angles",
                               [](const ShadowDome& d) {
                                   py::array_t<float> out(py::ssize_t(d.size()));
                                   for (int i = 0; i < d.size(); ++i)
                                       out.mutable_data()[i] = d.lights()[size_t(i)].solidAngle;
                                   return out;
                               })
        .def_property_readonly(
            "angular_radii",
            [](const ShadowDome& d) {
                py::array_t<float> out(py::ssize_t(d.size()));
                for (int i = 0; i < d.size(); ++i)
                    out.mutable_data()[i] = d.lights()[size_t(i)].angularRadius;
                return out;
            },
            "Per light: half-angle (radians) of the cone with its cell's light spread.")
        .def(
            "diffuse_visible",
            [](const ShadowDome& d, py::handle normal, py::handle visible) {
                const auto mask = maskVector(visible, "visible", d.size());
                return fromVec3(d.diffuseVisible(toVec3(normal, "normal"), mask));
            },
            py::arg("normal"), py::arg("visible"), "Eq. 2.22: sum of visible T_i max(0, n.V_i).")
        .def(
            "diffuse_subtract",
            [](const ShadowDome& d, py::handle normal, py::handle irradiance, py::handle visible) {
                const auto mask = maskVector(visible, "visible", d.size());
                return fromVec3(d.diffuseSubtract(toVec3(normal, "normal"),
                                                  toVec3(irradiance, "irradiance"), mask));
            },
            py::arg("normal"), py::arg("irradiance"), py::arg("visible"),
            "Eq. 2.23: irradiance minus the sum over occluded lights.")
        .def("refresh_set", &ShadowDome::refreshSet, py::arg("frame"), py::arg("per_frame"),
             "Indices of the lights whose shadow maps update in `frame` (round robin).")
        .def("__repr__", [](const ShadowDome& d) {
            return "<weft.ShadowDome lights=" + std::to_string(d.size()) + ">";
        });

    py::class_<Environment, std::shared_ptr<Environment>>(
        m, "Environment",
        "An environment that re-filters only when its radiance changes (cached by version).")
        .def(py::init(
                 [](py::handle cube) { return new Environment(toCube(cube, "radiance").get()); }),
             py::arg("radiance"),
             "An environment from a radiance CubeMap or (6, S, S, 3) array; filtered results "
             "are cached until set_radiance.")
        .def(
            "set_radiance",
            [](Environment& e, py::handle cube) { e.setRadiance(toCube(cube, "radiance").get()); },
            py::arg("radiance"),
            "Replaces the radiance and invalidates every cached result (version + 1).")
        .def_property_readonly("radiance", [](const Environment& e) { return e.radiance(); })
        .def_property_readonly("version", &Environment::version)
        .def(
            "irradiance_sh",
            [](Environment& e) {
                Sh9 sh;
                {
                    py::gil_scoped_release release;
                    sh = e.irradianceSh();
                }
                return shArray(sh);
            },
            "SH9 radiance coefficients (9, 3), cached.")
        .def("irradiance_map", &Environment::irradianceMap, py::arg("size") = 32,
             py::call_guard<py::gil_scoped_release>(),
             "Irradiance CubeMap of `size` evaluated from SH9 (cached).")
        .def("specular_chain", &Environment::specularChain, py::arg("size") = 128,
             py::arg("levels") = 5, py::arg("samples") = 64,
             py::call_guard<py::gil_scoped_release>(),
             "GGX prefiltered radiance chain of `levels` mip levels, roughness rising with the "
             "level (cached).")
        .def(
            "shadow_dome",
            [](Environment& e, int count, const std::string& layout) {
                const DomeLayout l = domeLayout(layout);
                py::gil_scoped_release release;
                return e.shadowDome(count, l);
            },
            py::arg("count"), py::arg("layout") = "fibonacci",
            "A ShadowDome of `count` lights with intensities from this environment (cached).")
        .def_property_readonly("stats",
                               [](const Environment& e) {
                                   const EnvironmentStats s = e.stats();
                                   py::dict d;
                                   d["version"] = s.version;
                                   d["filter_runs"] = s.filterRuns;
                                   d["cache_hits"] = s.cacheHits;
                                   d["last_refiltered"] = s.lastRefiltered;
                                   return d;
                               })
        .def("__repr__", [](const Environment& e) {
            return "<weft.Environment size=" + std::to_string(e.radiance().size()) +
                   " version=" + std::to_string(e.version()) + ">";
        });
}

} // namespace weft::py_bind
