// weft._core: the compiled half of the weft Python package.
#include <cstring>

#include <pybind11/stl.h>

#include <weft/Demo.h>
#include <weft/Device.h>
#include <weft/Image.h>
#include <weft/ShaderReload.h>

#include "Convert.h"
#include "Fields.h"
#include <weft/DemoScene.h>
#include <weft/DemoScript.h>

namespace weft::py_bind {
void bindScene(py::module_& m);
void bindRender(py::module_& m);
void bindCloth(py::module_& m);
void bindHair(py::module_& m);
void bindBtf(py::module_& m);
void bindHairRender(py::module_& m);
void bindIbl(py::module_& m);
void bindModelIo(py::module_& m);
} // namespace weft::py_bind

using namespace weft::py_bind;

namespace {

PyObject* gError = nullptr;
PyObject* gInvalidArgument = nullptr;
PyObject* gIoError = nullptr;

PyObject* newException(const char* name, PyObject* bases, const char* doc) {
    PyObject* type = PyErr_NewExceptionWithDoc(name, doc, bases, nullptr);
    if (!type) throw py::error_already_set();
    return type;
}

} // namespace

PYBIND11_MODULE(_core, m) {
    m.doc() = "weft's compiled core (Vulkan renderer, scene, IO). Use the `weft` package.";
    m.attr("__version__") = WEFT_VERSION;

    gError = newException("weft.Error", PyExc_RuntimeError, "Base class of weft's errors.");
    PyObject* invalidBases = PyTuple_Pack(2, gError, PyExc_ValueError);
    gInvalidArgument = newException("weft.InvalidArgument", invalidBases,
                                    "An impossible argument: wrong shape, NaN/inf, out of range.");
    Py_DECREF(invalidBases);
    PyObject* ioBases = PyTuple_Pack(2, gError, PyExc_OSError);
    gIoError = newException("weft.IoError", ioBases, "A missing, unreadable or corrupt file.");
    Py_DECREF(ioBases);
    m.attr("Error") = py::handle(gError);
    m.attr("InvalidArgument") = py::handle(gInvalidArgument);
    m.attr("IoError") = py::handle(gIoError);
    // Messages may quote bytes of a corrupt file that are not UTF-8 (found by the loaders'
    // fuzzer): decoded with backslash escapes, never a UnicodeDecodeError in place of the error.
    static const auto raise = [](PyObject* type, const char* what) {
        PyObject* text =
            PyUnicode_DecodeUTF8(what, Py_ssize_t(std::strlen(what)), "backslashreplace");
        if (!text) return; // the decoder's own error stands
        PyErr_SetObject(type, text);
        Py_DECREF(text);
    };
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const weft::InvalidArgument& e) {
            raise(gInvalidArgument, e.what());
        } catch (const weft::IoError& e) {
            raise(gIoError, e.what());
        } catch (const weft::Error& e) { raise(gError, e.what()); }
    });

    m.def(
        "devices",
        [] {
            py::list out;
            for (const auto& d : weft::listDevices()) {
                py::dict e;
                e["index"] = d.index;
                e["name"] = d.name;
                e["type"] = d.type;
                e["api_version"] = d.apiVersion;
                e["driver"] = d.driver;
                e["selected"] = d.selected;
                out.append(e);
            }
            return out;
        },
        "Vulkan devices as dicts (index, name, type, api_version, driver, selected).\n"
        "Selection prefers discrete > integrated > virtual > CPU; WEFT_DEVICE overrides it.");
    m.def("validation_enabled", &weft::validationEnabled,
          "True when WEFT_VALIDATION=1 enables the Vulkan validation layers.");
    m.def("validation_messages", &weft::validationMessages,
          "Validation warnings/errors collected since the last clear.");
    m.def("clear_validation_messages", &weft::clearValidationMessages,
          "Forgets the validation messages collected so far.");
    m.def(
        "device_memory",
        [] {
            const weft::DeviceMemoryStats s = weft::deviceMemoryStats();
            py::dict d;
            d["blocks"] = s.blocks;
            d["reserved_bytes"] = s.reservedBytes;
            d["used_bytes"] = s.usedBytes;
            return d;
        },
        "Device memory weft's allocator holds (shared by all Renderers): blocks, reserved_bytes\n"
        "(obtained from Vulkan), used_bytes (handed out); zeros when no Renderer exists.");

    m.def(
        "load_png", [](const std::string& path) { return toNumpy(weft::loadPng(path)); },
        py::arg("path"), "Reads a PNG into a uint8 array (H, W, C).");
    m.def(
        "save_png",
        [](const std::string& path, py::handle image) { weft::savePng(path, fromNumpy(image)); },
        py::arg("path"), py::arg("image"), "Writes a uint8 array (H, W) or (H, W, 1-4) as PNG.");

    m.def(
        "load_exr", [](const std::string& path) { return toNumpy(weft::loadExr(path)); },
        py::arg("path"),
        "Reads an OpenEXR file into a float32 array (H, W, C): R, G, B [, A] "
        "or Y [, A].");
    m.def(
        "save_exr",
        [](const std::string& path, py::handle image) { weft::saveExr(path, fromNumpyF(image)); },
        py::arg("path"), py::arg("image"),
        "Writes a float array (H, W) or (H, W, 1-4) as 32-bit float OpenEXR (ZIP compression).");
    m.def(
        "load_hdr", [](const std::string& path) { return toNumpy(weft::loadHdr(path)); },
        py::arg("path"), "Reads a Radiance RGBE .hdr file into a float32 array (H, W, 3).");
    m.def(
        "save_hdr",
        [](const std::string& path, py::handle image) { weft::saveHdr(path, fromNumpyF(image)); },
        py::arg("path"), py::arg("image"),
        "Writes a float array (H, W), (H, W, 3) or (H, W, 4, alpha dropped) as Radiance RGBE "
        "(run-length encoded). Values must be finite and >= 0.");
    m.def(
        "load_image_float", [](const std::string& path) { return toNumpy(weft::loadImageF(path)); },
        py::arg("path"), "Reads .exr, .hdr or .png (values / 255) into a float32 (H, W, C) array.");

    m.def("shader_hot_reload_available", &weft::shaderHotReloadAvailable,
          "True when weft was built with libshaderc (shader hot reload).");
    m.def(
        "set_shader_directory", [](const std::string& dir) { weft::setShaderDirectory(dir); },
        py::arg("directory"),
        "Development: watch a directory laid out like glsl/; shaders changed there are\n"
        "recompiled (libshaderc) and replace the built-in ones at the next frame. '' stops.");
    m.def("shader_directory", &weft::shaderDirectory,
          "The directory watched for shader hot reload ('' when none; see "
          "set_shader_directory).");
    m.def(
        "poll_shader_changes",
        [] {
            py::gil_scoped_release release;
            return weft::pollShaderChanges();
        },
        "Recompiles changed shaders now (renderers also do it every frame); returns how many.");
    m.def("shader_errors", &weft::shaderErrors,
          "Compile errors of reloaded shaders since the last clear (name: file:line: message).");
    m.def("clear_shader_errors", &weft::clearShaderErrors,
          "Forgets the shader compile errors collected so far.");

    m.def(
        "demo_scene",
        [](py::object hour) {
            weft::app::DemoScene demo;
            if (!hour.is_none()) demo.setHour(hour.cast<float>());
            return py::make_tuple(std::make_shared<weft::Scene>(demo.scene()), demo.camera(),
                                  demo.clothPtr());
        },
        py::arg("hour") = py::none(),
        "The demo's scene (terrain, sphere, furry ball, sun and moon under the analytic sky, and\n"
        "the cloth in it) at `hour` (0..24, default 8.4), its camera and the cloth (step it to\n"
        "animate the scene), as (scene, camera, cloth).");

    m.def(
        "load_demo_script",
        [](const std::string& path) {
            py::list out;
            for (const weft::app::ScriptEvent& e : weft::app::loadScript(path))
                out.append(py::make_tuple(e.frame, e.action, e.key, e.x, e.y));
            return out;
        },
        py::arg("path"),
        "The events of a demo --script file as (frame, action, key code, x, y) tuples (what\n"
        "run_demo(script=...) plays); IoError names file:line of a malformed line.");

    using O = weft::DemoOptions;
    const auto demo = std::make_tuple(
        field("width", &O::width), field("height", &O::height), field("frames", &O::frames),
        field("headless", &O::headless), field("vsync", &O::vsync), field("out", &O::out),
        field("screenshot", &O::screenshot), field("stats_json", &O::statsJson),
        field("script", &O::script), field("shader_dir", &O::shaderDir),
        field("environment", &O::environment),
        field<py::object, O>(
            "hour",
            [](const O& o) { return o.hour < 0.0f ? py::object(py::none()) : py::float_(o.hour); },
            [](O& o, const py::object& hour) {
                if (hour.is_none()) return;
                o.hour = hour.cast<float>();
                if (!(o.hour >= 0.0f && o.hour <= 24.0f))
                    throw weft::InvalidArgument("hour (time of day) must be in [0, 24]");
            }),
        // checked by runDemo (RenderSettings::validate) before it builds anything
        field("msaa", &O::msaa), field("ambient_occlusion", &O::ambientOcclusion),
        field("bounce", &O::bounce), field("exposure", &O::exposure),
        enumField("tone_map", &O::toneMap, kToneMaps));
    defFunction(
        m, "run_demo",
        [](const O& o) {
            py::gil_scoped_release release;
            return weft::runDemo(o);
        },
        demo,
        "Runs the demo (the seed's cloth environment): a window when a display exists, else\n"
        "headless to `out` (see `weft-demo --help` for frames, scripts and output folders),\n"
        "with the renderer's anti-aliasing, ambient occlusion, bounce, exposure and tone map.");

    bindScene(m);
    bindModelIo(m);
    bindRender(m);
    bindCloth(m);
    bindHair(m);
    bindBtf(m);
    bindHairRender(m);
    bindIbl(m);
}
