#include <weft/Demo.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>

#include <GLFW/glfw3.h>

#include <weft/Device.h>
#include <weft/Renderer.h>
#include <weft/ShaderReload.h>
#include <weft/Window.h>

#include <weft/DemoScene.h>
#include <weft/DemoScript.h>

#include "app/DemoPanel.h"
#include "app/DemoSettings.h"
#include "app/StatsJson.h"
#include "core/FileRead.h"

namespace weft {
namespace {

using app::DemoControls;
using app::loadScript;
using app::ScriptEvent;
using Clock = std::chrono::steady_clock;

// Progress lines on stderr (results stay on stdout), each with the seconds since the run began,
// so the seconds spent building the scene and the first frame's pipelines are not silent.
class Progress {
public:
    explicit Progress(bool quiet) : mQuiet(quiet) {}
    void say(const std::string& what) const {
        if (mQuiet) return;
        std::cerr << "weft-demo: [" << std::fixed << std::setprecision(1) << seconds() << " s] "
                  << what << std::endl;
    }
    double seconds() const { return std::chrono::duration<double>(Clock::now() - mStart).count(); }

private:
    bool mQuiet;
    Clock::time_point mStart = Clock::now();
};

void writeImage(const std::string& path, const ImageU8& image) {
    const std::filesystem::path p(path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    savePng(path, image);
}

void writeStats(const std::string& path, const FrameStats& stats, const std::string& device) {
    if (path.empty()) return;
    const std::filesystem::path p(path);
    if (p.has_parent_path()) std::filesystem::create_directories(p.parent_path());
    std::ofstream out(path);
    if (!out) throw IoError("cannot write " + path);
    out << statsToJson(stats, device) << "\n";
}

// Orbits the camera around its target: left/right change the azimuth, up/down the elevation.
void orbit(Camera& camera, float dAzimuth, float dElevation) {
    glm::vec3 d = camera.position - camera.target;
    const float r = glm::length(d);
    float az = std::atan2(d.x, d.z) + dAzimuth;
    float el = std::asin(glm::clamp(d.y / r, -1.0f, 1.0f)) + dElevation;
    el = glm::clamp(el, -1.4f, 1.4f);
    camera.position = camera.target + r * glm::vec3(std::cos(el) * std::sin(az), std::sin(el),
                                                    std::cos(el) * std::cos(az));
}

// Applies a key to the scene and the camera; returns what changed (or "").
std::string applyKey(app::DemoScene& demo, int key) {
    const float step = 0.08f;
    if (key == GLFW_KEY_LEFT) orbit(demo.camera(), -step, 0);
    if (key == GLFW_KEY_RIGHT) orbit(demo.camera(), step, 0);
    if (key == GLFW_KEY_UP) orbit(demo.camera(), 0, step);
    if (key == GLFW_KEY_DOWN) orbit(demo.camera(), 0, -step);
    return demo.key(key);
}

void applyScript(app::DemoScene& demo, DemoControls& controls,
                 const std::vector<ScriptEvent>& script, size_t& next, int frame, int w, int h) {
    for (; next < script.size() && script[next].frame <= frame; ++next) {
        const ScriptEvent& e = script[next];
        if (e.action == "set") {
            std::cout << "weft-demo: frame " << frame << ": "
                      << app::applyDemoSetting(demo, controls, e.name, e.value) << "\n";
        } else if (e.action == "key") {
            const std::string what = applyKey(demo, e.key);
            if (!what.empty()) std::cout << "weft-demo: frame " << frame << ": " << what << "\n";
        } else if (e.action == "grab") {
            const bool hit = demo.grab(e.x, e.y, w, h);
            std::cout << "weft-demo: frame " << frame << ": grab at (" << e.x << ", " << e.y << ") "
                      << (hit ? "took the cloth" : "missed the cloth") << "\n";
        } else if (e.action == "drag") {
            demo.drag(e.x, e.y, w, h);
        } else {
            demo.release();
        }
    }
}

bool isPng(const std::string& path) {
    return path.size() >= 4 && path.compare(path.size() - 4, 4, ".png") == 0;
}

// Headless: with --frames N, N frames at one fixed 60 Hz step each, written as DIR/frame_NNNN.png
// (or only the last one when --out names a .png) plus DIR/stats.json; without, the cloth
// settles for 1.5 s and one frame is written to --out.
RenderSettings renderSettings(const DemoOptions& o) {
    RenderSettings s;
    s.msaa = o.msaa;
    s.ambientOcclusion = o.ambientOcclusion;
    s.bounce = o.bounce;
    s.exposure = o.exposure;
    s.toneMap = o.toneMap;
    s.validate();
    return s;
}

// The controls' renderer settings, once edited (panel, script), become the renderer's.
void applyControls(app::DemoScene& demo, DemoControls& controls, Renderer& renderer) {
    if (controls.renderChanged) {
        renderer.setSettings(controls.render);
        controls.renderChanged = false;
    }
    demo.applySettings(renderer);
}

int runHeadless(const DemoOptions& o, app::DemoScene& demo, const Progress& progress) {
    const std::vector<ScriptEvent> script = loadScript(o.script);
    DemoControls controls;
    controls.render = renderSettings(o);
    Renderer renderer(uint32_t(o.width), uint32_t(o.height), controls.render);
    size_t next = 0;
    const bool sequence = o.frames > 0 && !isPng(o.out);
    if (o.frames == 0) {
        progress.say("letting the cloth settle for 1.5 s (90 steps)...");
        for (int i = 0; i < 90; ++i) demo.update(1.0f / 60.0f);
    }
    const int frames = std::max(o.frames, 1);
    std::vector<FrameStats> history;
    std::string last;
    double lastSaid = progress.seconds();
    for (int f = 0; f < frames; ++f) {
        // The first frame builds the pipelines and takes the captures: seconds on a CPU device.
        if (f == 0)
            progress.say("rendering " + std::string(frames > 1 ? "the first frame" : "the frame") +
                         " (" + std::to_string(o.width) + "x" + std::to_string(o.height) +
                         ", pipelines and captures)...");
        applyScript(demo, controls, script, next, f, o.width, o.height);
        if (o.frames > 0) demo.update(1.0f / 60.0f);
        applyControls(demo, controls, renderer);
        const Frame frame = renderer.render(demo.scene(), demo.camera(), OutputColor);
        const bool write = sequence || f + 1 == frames;
        if (write) {
            char name[32];
            std::snprintf(name, sizeof name, "frame_%04d.png", f);
            last = sequence ? (std::filesystem::path(o.out) / name).string() : o.out;
            writeImage(last, frame.color);
        }
        history.push_back(renderer.stats());
        // A line at most every 2 s, and the last frame's.
        if (frames > 1 && (f + 1 == frames || progress.seconds() - lastSaid >= 2.0)) {
            std::ostringstream line;
            line << "frame " << f + 1 << "/" << frames << " (" << std::fixed << std::setprecision(0)
                 << renderer.stats().cpuMs << " ms)";
            progress.say(line.str());
            lastSaid = progress.seconds();
        }
    }
    if (sequence) {
        std::ofstream stats(std::filesystem::path(o.out) / "stats.json");
        if (!stats)
            throw IoError("cannot write " + (std::filesystem::path(o.out) / "stats.json").string());
        stats << statsToJson(history, renderer.deviceName());
    }
    writeStats(o.statsJson, renderer.stats(), renderer.deviceName());
    std::cout << "weft-demo: headless render (" << o.width << "x" << o.height << ", "
              << renderer.deviceName() << ", " << demo.status() << ") written to "
              << std::filesystem::absolute(sequence ? o.out : last).string() << std::endl;
    return 0;
}

// Detaches the panel when the window loop ends, normally or by an exception, before the window
// and the renderer it draws with go.
struct PanelAttachment {
    app::DemoPanel* panel;
    ~PanelAttachment() {
        if (panel) panel->detach();
    }
};

int runWindow(const DemoOptions& o, app::DemoScene& demo, app::DemoPanel* panel,
              const Progress& progress) {
    const std::vector<ScriptEvent> script = loadScript(o.script);
    DemoControls controls;
    controls.render = renderSettings(o);
    Window window(o.width, o.height, "weft demo", o.vsync);
    Renderer renderer(uint32_t(o.width), uint32_t(o.height), controls.render);
    std::cout << "weft-demo: " << app::DemoScene::controls() << std::endl;
    window.onKey([&](int key, int action) {
        if (action == 0) return;                                       // release
        if (panel && controls.panel && panel->wantsKeyboard()) return; // typing into the panel
        if (key == GLFW_KEY_F1 && panel) {
            controls.panel = !controls.panel;
            return;
        }
        if (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q) window.requestClose();
        const std::string what = applyKey(demo, key);
        if (!what.empty()) std::cout << "weft-demo: " << what << std::endl;
    });
    int fbw = o.width, fbh = o.height;
    window.onMouseButton([&](int button, int action, double x, double y) {
        if (button != GLFW_MOUSE_BUTTON_LEFT) return;
        // A press on the panel is the panel's; a release always ends a drag of the cloth.
        if (action == 1 && !(panel && controls.panel && panel->wantsMouse()))
            demo.grab(x, y, fbw, fbh);
        else if (action != 1)
            demo.release();
    });
    window.onCursor([&](double x, double y) { demo.drag(x, y, fbw, fbh); });
    if (panel) panel->attach(window, renderer);
    const PanelAttachment attachment{panel};
    size_t next = 0;
    auto lastTitle = Clock::now(), lastFrame = Clock::now();
    int frame = 0, framesSinceTitle = 0, stepsSinceTitle = 0;
    app::DemoRates rates;
    ImageU8 shot;
    progress.say("rendering the first frame (pipelines and captures)...");
    while (!window.shouldClose()) {
        window.pollEvents();
        window.framebufferSize(fbw, fbh);
        applyScript(demo, controls, script, next, frame, fbw, fbh);
        if (panel) panel->update(demo, controls, renderer.stats(), rates);
        // With --frames the run is reproducible: one fixed step per frame, as headless.
        const auto now = Clock::now();
        const float dt = std::min(std::chrono::duration<float>(now - lastFrame).count(), 0.1f);
        lastFrame = now;
        stepsSinceTitle += demo.update(o.frames > 0 ? 1.0f / 60.0f : dt);
        applyControls(demo, controls, renderer);
        const bool last = o.frames > 0 && frame + 1 >= o.frames;
        ImageU8 image =
            renderer.present(window, demo.scene(), demo.camera(), last && !o.screenshot.empty());
        if (last) shot = std::move(image);
        if (frame == 0) progress.say("first frame shown");
        ++frame;
        ++framesSinceTitle;
        const double elapsed = std::chrono::duration<double>(Clock::now() - lastTitle).count();
        if (elapsed > 0.5) {
            rates.fps = framesSinceTitle / elapsed;
            rates.simStepsPerSecond = stepsSinceTitle / elapsed;
            std::ostringstream title;
            title << "weft demo - " << std::lround(framesSinceTitle / elapsed) << " fps, "
                  << std::lround(stepsSinceTitle / elapsed) << " sim steps/s";
            for (const PassStats& p : renderer.stats().passes)
                title << " | " << p.name << " " << std::fixed << std::setprecision(2)
                      << (p.gpuMs >= 0 ? p.gpuMs : p.cpuMs) << " ms";
            title << " | " << demo.status();
            window.setTitle(title.str());
            lastTitle = Clock::now();
            framesSinceTitle = stepsSinceTitle = 0;
        }
        if (last) break;
    }
    if (!o.screenshot.empty()) {
        if (shot.pixels.empty()) throw Error("the window was closed before the screenshot frame");
        writeImage(o.screenshot, shot);
        std::cout << "weft-demo: " << frame << " frames in a window; screenshot written to "
                  << std::filesystem::absolute(o.screenshot).string() << std::endl;
    }
    writeStats(o.statsJson, renderer.stats(), renderer.deviceName());
    return 0;
}

} // namespace

int runDemo(const DemoOptions& o) { return runDemo(o, nullptr); }

int runDemo(const DemoOptions& o, app::DemoPanel* panel) {
    if (o.width <= 0 || o.height <= 0 || o.width > 16384 || o.height > 16384)
        throw InvalidArgument("demo size must be in [1, 16384] (got " + std::to_string(o.width) +
                              "x" + std::to_string(o.height) + ")");
    if (o.frames < 0) throw InvalidArgument("frames must be >= 0");
    renderSettings(o); // bad picture settings fail before the seconds of building the scene
    if (!o.shaderDir.empty()) {
        setShaderDirectory(o.shaderDir);
        std::cout << "weft-demo: shader hot reload: watching " << o.shaderDir << std::endl;
    }
    // Building the scene (terrain, cloth, fur, the fitted BTF material) and the renderer takes
    // seconds; say so rather than sit silent.
    const Progress progress(o.quiet);
    progress.say("building the scene (terrain, cloth, fur, materials)...");
    app::DemoScene demo;
    if (o.hour >= 0.0f || std::isnan(o.hour)) demo.setHour(o.hour);
    if (!o.environment.empty()) {
        progress.say("lighting it with " + o.environment + "...");
        demo.lightWith(o.environment);
    }
    const int rc = !o.headless && Window::displayAvailable() ? runWindow(o, demo, panel, progress)
                                                             : runHeadless(o, demo, progress);
    // With validation on, any message the layers reported makes the run fail visibly.
    const auto messages = validationMessages();
    for (const std::string& m : messages) std::cerr << "weft-demo: validation " << m << "\n";
    return messages.empty() ? rc : 3;
}

} // namespace weft
