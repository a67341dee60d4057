// Bindings of the renderer: offscreen frames as NumPy arrays, statistics, shadow data.
#include <algorithm>
#include <cmath>
#include <cstring>

#include <pybind11/stl.h>

#include <weft/Debug.h>
#include <weft/Renderer.h>

#include "Convert.h"
#include "Fields.h"

namespace weft::py_bind {

namespace {

py::array_t<float> floatImage(const std::vector<float>& data, int h, int w, int channels, int take,
                              int offset) {
    py::array_t<float> out(take == 1 ? std::vector<py::ssize_t>{h, w}
                                     : std::vector<py::ssize_t>{h, w, take});
    float* dst = out.mutable_data();
    const size_t n = size_t(h) * w;
    for (size_t i = 0; i < n; ++i)
        for (int k = 0; k < take; ++k) dst[i * take + k] = data[i * channels + offset + k];
    return out;
}

py::object ms(double v) { return v < 0 ? py::object(py::none()) : py::object(py::float_(v)); }

py::dict statsDict(const FrameStats& s) {
    py::dict d;
    d["frame_index"] = s.frameIndex;
    d["cpu_ms"] = s.cpuMs;
    d["gpu_ms"] = ms(s.gpuMs);
    py::list passes;
    for (const PassStats& p : s.passes) {
        py::dict e;
        e["name"] = p.name;
        e["cpu_ms"] = p.cpuMs;
        e["gpu_ms"] = ms(p.gpuMs);
        passes.append(e);
    }
    d["passes"] = passes;
    d["culled"] = s.culled;
    d["reused"] = s.reused;
    d["mesh_uploads"] = s.meshUploads;
    d["upload_bytes"] = s.uploadBytes;
    d["environment_bakes"] = s.environmentBakes;
    d["environment_bake_ms"] = s.environmentBakeMs;
    return d;
}

Frame renderFrame(Renderer& r, const Scene& scene, const Camera& camera, uint32_t outputs) {
    py::gil_scoped_release release;
    return r.render(scene, camera, outputs);
}

// Renderer(width, height, settings...): the size is checked here so that a refused size names
// the range (RenderSettings::validate checks the rest).
struct RendererSetup {
    int64_t width = 0, height = 0;
    RenderSettings settings;
};

void checkSize(int64_t width, int64_t height) {
    if (width <= 0 || height <= 0 || width > 65535 || height > 65535)
        throw InvalidArgument("render target size must be 1..65535 pixels per side (got " +
                              std::to_string(width) + "x" + std::to_string(height) + ")");
}

} // namespace

const char* const kToneMaps[] = {"clamp", "aces", "agx", "neutral"};

void bindRender(py::module_& m) {
    using S = RenderSettings;
    const auto settings = std::make_tuple(
        field("shadow_map_size", &S::shadowMapSize,
              "Texels per side of each shadow map, in [16, 16384]."),
        field("pcf_radius", &S::pcfRadius,
              "PCF kernel radius r in [0, 7]: (2r + 1)^2 shadow-map taps."),
        field("bias_constant", &S::biasConstant,
              "Shadow depth bias, constant part (the light's NDC depth units); the bias is "
              "bias_constant + bias_slope tan(angle between n and l), at most bias_max."),
        field("bias_slope", &S::biasSlope,
              "Shadow depth bias per tan(angle between n and l) (see bias_constant)."),
        field("bias_max", &S::biasMax, "The largest shadow depth bias (see bias_constant)."),
        field("normal_offset", &S::normalOffset,
              "Receiver offset along the normal, in shadow-map texels."),
        field("reuse_shadow_maps", &S::reuseShadowMaps,
              "Keep the last frame's shadow maps when no shadow view and no caster changed (and\n"
              "the hair's deep opacity maps when no map's view and no strand in it changed);\n"
              "when only some casters moved, keep the others' depth and draw the moving ones."),
        field("msaa", &S::msaa,
              "Multisample anti-aliasing samples per pixel (1, 2, 4, 8; default 4), lowered "
              "to what\nthe device supports (msaa_samples). render_debug frames are not "
              "multisampled."),
        field("exposure", &S::exposure,
              "Exposure in photographic stops: the colour output shows linear radiance x "
              "2^exposure\n(render_linear is not exposed)."),
        enumField(
            "tone_map", &S::toneMap, kToneMaps,
            "'clamp' (the seed's look), 'aces' (Narkowicz's ACES fit), 'agx' (Blender's AgX) or\n"
            "'neutral' (Khronos PBR Neutral): how exposed radiance maps to the 8-bit colour "
            "output."),
        field("bounce", &S::bounce,
              "One bounce of diffuse light: what the receivers (instances that cast no "
              "shadow, such as a ground) reflect onto the shadow casters, and the sky and "
              "ambient they hide from them (a small SH9 capture per caster, at most 8)."),
        field("ambient_occlusion", &S::ambientOcclusion,
              "Ambient occlusion of a scene without an environment: its constant ambient is "
              "read as a uniform sky, occluded by the shadow casters through a dome of this "
              "many soft shadow lights (0: off; a multiple of 8 up to 64)."),
        field("ambient_occlusion_blur", &S::ambientOcclusionBlur,
              "Blur radius in pixels of the ambient occlusion (0: per pixel)."),
        field("probe_size", &S::probeSize,
              "Texels per face of the dynamic reflection capture, in [4, 2048]."),
        field("dome_interleave", &S::domeInterleave,
              "Where a dome's shadows are blurred (ambient occlusion, an environment's "
              "dome_blur), each pixel of a 2 x 2 block evaluates every fourth dome light and "
              "a gather pass combines the block's quarters before the blur: a quarter of the "
              "dome's cost. False: every pixel evaluates every light."));
    using Setup = RendererSetup;
    const auto size = std::make_tuple(required(field("width", &Setup::width)),
                                      required(field("height", &Setup::height)));
    py::class_<Renderer> cls(
        m, "Renderer",
        "Vulkan renderer drawing a Scene from a Camera into an offscreen image of width x height.");
    defInit(
        cls,
        [](const Setup& s) {
            checkSize(s.width, s.height);
            return std::make_unique<Renderer>(uint32_t(s.width), uint32_t(s.height), s.settings);
        },
        std::tuple_cat(size, within(&Setup::settings, settings)),
        "An offscreen renderer of width x height pixels on the selected Vulkan device, "
        "with its shadow, anti-aliasing (msaa 1/2/4/8), exposure, tone-map ('clamp', "
        "'aces', 'agx', 'neutral'), bounce and ambient-occlusion settings. Raises "
        "InvalidArgument for out-of-range settings, Error when no Vulkan device works.");
    defSettingProperties(
        cls, [](const Renderer& r) { return r.settings(); },
        [](Renderer& r, const S& s) { r.setSettings(s); }, settings);
    cls.def_property_readonly("width", &Renderer::width)
        .def_property_readonly("height", &Renderer::height)
        .def_property_readonly("device_name", &Renderer::deviceName)
        .def(
            "resize",
            [](Renderer& r, int64_t w, int64_t h) {
                checkSize(w, h);
                r.resize(uint32_t(w), uint32_t(h));
            },
            py::arg("width"), py::arg("height"),
            "Changes the output size (1..65535 pixels per side); the next render reallocates "
            "its targets.")
        .def_property_readonly("msaa_samples", &Renderer::msaaSamples,
                               "The samples per pixel the device renders for the msaa setting.");
    cls.def(
           "render",
           [](Renderer& r, const Scene& scene, const Camera& camera) {
               return toNumpy(renderFrame(r, scene, camera, OutputColor).color);
           },
           py::arg("scene"), py::arg("camera"), "sRGB-encoded RGBA uint8 image (H, W, 4).")
        .def(
            "render_linear",
            [](Renderer& r, const Scene& scene, const Camera& camera) {
                Frame f = renderFrame(r, scene, camera, OutputLinear);
                return floatImage(f.linear, f.height, f.width, 4, 4, 0);
            },
            py::arg("scene"), py::arg("camera"),
            "Linear radiance RGBA float32 (H, W, 4), rendered in half floats (11 significant bits; "
            "weft.reference.LINEAR_STORAGE_RTOL).")
        .def(
            "render_debug",
            [](Renderer& r, const Scene& scene, const Camera& camera) {
                Frame f = renderFrame(r, scene, camera, OutputColor | OutputLinear | OutputDebug);
                const int h = f.height, w = f.width;
                py::dict d;
                d["color"] = toNumpy(f.color);
                d["linear"] = floatImage(f.linear, h, w, 4, 4, 0);
                d["position"] = floatImage(f.position, h, w, 4, 3, 0);
                py::array_t<bool> mask({h, w});
                for (size_t i = 0; i < size_t(h) * w; ++i)
                    mask.mutable_data()[i] = f.position[i * 4 + 3] > 0.5f;
                d["mask"] = mask;
                d["normal"] = floatImage(f.normal, h, w, 4, 3, 0);
                d["shadow"] = floatImage(f.normal, h, w, 4, 1, 3);
                d["uv"] = floatImage(f.surface, h, w, 4, 2, 0);
                d["albedo"] = floatImage(f.albedo, h, w, 4, 3, 0);
                d["specular_map"] = floatImage(f.albedo, h, w, 4, 1, 3);
                d["light_depth"] = floatImage(f.surface, h, w, 4, 1, 2);
                py::array_t<int32_t> instance({h, w});
                for (size_t i = 0; i < size_t(h) * w; ++i)
                    instance.mutable_data()[i] =
                        int32_t(std::max(0L, std::lround(f.surface[i * 4 + 3]))) - 1;
                d["instance"] = instance;
                py::array_t<int32_t> hair({h, w}); // hair pixels store -(hair id + 1) in surface.w
                for (size_t i = 0; i < size_t(h) * w; ++i)
                    hair.mutable_data()[i] = f.surface[i * 4 + 3] < -0.5f
                                                 ? -int32_t(std::lround(f.surface[i * 4 + 3])) - 1
                                                 : -1;
                d["hair"] = hair;
                return d;
            },
            py::arg("scene"), py::arg("camera"),
            "One frame's colour, linear radiance and the inputs of its shading (position, mask,\n"
            "normal, shadow visibility of the first shadow-casting light, uv, light_depth,\n"
            "albedo: T = base colour * texture sample (what eq. 2.10 multiplies),\n"
            "specular_map: the green channel of the specular-map sample (1 without a map),\n"
            "instance: the mesh id drawn at each pixel or -1; hair: the hair id or -1, where hair\n"
            "is drawn opaque normal holds its unit tangent, shadow its visibility, uv[..., 0]\n"
            "its strand index and albedo its diffuse colour).")
        .def_property_readonly(
            "stats", [](const Renderer& r) { return statsDict(r.stats()); },
            "The last frame: passes run with CPU/GPU ms, culled passes.")
        .def(
            "shadow_map",
            [](Renderer& r, int light, int view) {
                uint32_t size = 0;
                std::vector<float> data = debug::shadowMap(r, light, &size, view);
                return arrayOf<float>(data, {size, size});
            },
            py::arg("light_index") = 0, py::arg("view") = 0,
            "Depth in [0,1] of the last frame's shadow map of a light (`view`: one of a point\n"
            "light's six views +X, -X, +Y, -Y, +Z, -Z).")
        .def(
            "reflection_probe",
            [](Renderer& r) {
                uint32_t size = 0;
                std::vector<float> data = debug::reflectionProbe(r, &size);
                return arrayOf<float>(data, {6, size, size, 4});
            },
            "The last frame's dynamic reflection capture, (6, S, S, 4) linear RGBA (faces +X, -X,\n"
            "+Y, -Y, +Z, -Z as weft.ibl.CubeMap).")
        .def(
            "shadow_info",
            [](const Renderer& r, int light) {
                const ShadowInfo i = debug::shadowInfo(r, light);
                py::dict d;
                d["active"] = i.active;
                d["size"] = i.size;
                d["view_proj"] = fromMat4(i.viewProj);
                d["normal_offset_world"] = i.normalOffsetWorld;
                d["layer"] = i.layer;
                d["perspective"] = i.perspective;
                d["near"] = i.zNear;
                d["far"] = i.zFar;
                py::list views;
                for (const glm::mat4& v : i.views) views.append(fromMat4(v));
                d["views"] = views;
                d["bias_constant"] = i.settings.biasConstant;
                d["bias_slope"] = i.settings.biasSlope;
                d["bias_max"] = i.settings.biasMax;
                d["pcf_radius"] = i.settings.pcfRadius;
                return d;
            },
            py::arg("light_index") = 0, "What the shadow test of a light used in the last frame.")
        .def("__repr__", [](const Renderer& r) {
            return "<weft.Renderer " + std::to_string(r.width()) + "x" +
                   std::to_string(r.height()) + " on " + r.deviceName() + ">";
        });
}

} // namespace weft::py_bind
