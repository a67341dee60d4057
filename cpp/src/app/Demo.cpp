#include <weft/Demo.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>

#include <GLFW/glfw3.h>

#include <weft/Device.h>
#include <weft/Renderer.h>
#include <weft/Window.h>

#include "app/StatsJson.h"

namespace weft {
namespace {

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

int runHeadless(const DemoOptions& o, const Scene& scene, const Camera& camera) {
    Renderer renderer(uint32_t(o.width), uint32_t(o.height));
    const Frame frame = renderer.render(scene, camera, OutputColor);
    writeImage(o.out, frame.color);
    writeStats(o.statsJson, renderer.stats(), renderer.deviceName());
    std::cout << "weft-demo: headless render (" << o.width << "x" << o.height << ", "
              << renderer.deviceName() << ") written to "
              << std::filesystem::absolute(o.out).string() << std::endl;
    return 0;
}

int runWindow(const DemoOptions& o, const Scene& scene, Camera camera) {
    Window window(o.width, o.height, "weft demo", o.vsync);
    Renderer renderer(uint32_t(o.width), uint32_t(o.height));
    window.onKey([&](int key, int action) {
        if (action == 0) return; // release
        const float step = 0.08f;
        if (key == GLFW_KEY_ESCAPE || key == GLFW_KEY_Q) window.requestClose();
        if (key == GLFW_KEY_LEFT) orbit(camera, -step, 0);
        if (key == GLFW_KEY_RIGHT) orbit(camera, step, 0);
        if (key == GLFW_KEY_UP) orbit(camera, 0, step);
        if (key == GLFW_KEY_DOWN) orbit(camera, 0, -step);
    });
    using Clock = std::chrono::steady_clock;
    auto lastTitle = Clock::now();
    int frame = 0, framesSinceTitle = 0;
    ImageU8 shot;
    while (!window.shouldClose()) {
        window.pollEvents();
        const bool last = o.frames > 0 && frame + 1 >= o.frames;
        ImageU8 image = renderer.present(window, scene, camera, last && !o.screenshot.empty());
        if (last) shot = std::move(image);
        ++frame;
        ++framesSinceTitle;
        const double elapsed = std::chrono::duration<double>(Clock::now() - lastTitle).count();
        if (elapsed > 0.5) {
            std::ostringstream title;
            title << "weft demo - " << std::lround(framesSinceTitle / elapsed) << " fps";
            for (const PassStats& p : renderer.stats().passes)
                title << " | " << p.name << " " << std::fixed << std::setprecision(2)
                      << (p.gpuMs >= 0 ? p.gpuMs : p.cpuMs) << " ms";
            window.setTitle(title.str());
            lastTitle = Clock::now();
            framesSinceTitle = 0;
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

int runDemo(const DemoOptions& o) {
    if (o.width <= 0 || o.height <= 0 || o.width > 16384 || o.height > 16384)
        throw InvalidArgument("demo size must be in [1, 16384] (got " + std::to_string(o.width) +
                              "x" + std::to_string(o.height) + ")");
    if (o.frames < 0) throw InvalidArgument("frames must be >= 0");
    Scene scene;
    Camera camera;
    makeDefaultScene(scene, camera);
    const int rc = !o.headless && Window::displayAvailable() ? runWindow(o, scene, camera)
                                                             : runHeadless(o, scene, camera);
    // With validation on, any message the layers reported makes the run fail visibly.
    const auto messages = validationMessages();
    for (const std::string& m : messages) std::cerr << "weft-demo: validation " << m << "\n";
    return messages.empty() ? rc : 3;
}

} // namespace weft
