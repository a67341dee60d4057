// Bindings of the IBL tools: weft.CubeMap and the conversion, filtering and light-extraction
// functions (wrapped with conveniences by weft.ibl); the sky is in bind_sky.cpp, ShadowDome and
// Environment in bind_environment.cpp, the array conversions in IblArrays.h.
#include <cstring>

#include <pybind11/stl.h>

#include <weft/IblGpu.h>
#include <weft/IblLights.h>

#include "IblArrays.h"

namespace weft::py_bind {

void bindSky(py::module_& m);         // bind_sky.cpp
void bindEnvironment(py::module_& m); // bind_environment.cpp

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
                return rowsArray(out);
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
            return rowsArray(n);
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
        "coat_albedo",
        [](double cosView, double alpha, double f0, int samples) {
            return coatAlbedo(cosView, alpha, f0, samples);
        },
        py::arg("cos_view"), py::arg("alpha"), py::arg("f0"), py::arg("samples") = 1024,
        "Directional albedo towards a view at cos n.v = cos_view of the GGX coat with alpha\n"
        "(0: a mirror) and normal-incidence reflectance f0: the integral of f(l, v) (n.l) with\n"
        "GGX D, separable Smith masking and the dielectric's exact Fresnel, by importance\n"
        "sampling (Hammersley). The weight a Material(specular_model='ggx')\n"
        "puts on its prefiltered environment reflection (the renderer samples a table of it).");
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
            return arrayOf<float>(lut, {size, size, 2});
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
            return py::make_tuple(out, arrayOf<int>(labels, {6, s, s}));
        },
        py::arg("radiance"), py::arg("downsample") = 32, py::arg("threshold") = 0.0f,
        py::arg("relative_threshold") = 8.0f, py::arg("max_lights") = 16, py::arg("labels") = false,
        "Threshold + connected components; list of dicts (direction, colour, solid_angle, texels),\n"
        "with labels=True also the (6, S, S) int array of light indices (-1: not a light).");

    bindEnvironment(m); // after CubeMap, which its signatures name
}

} // namespace weft::py_bind
