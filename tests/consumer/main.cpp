// Renders one frame of the default scene through the installed weft package and checks it.
#include <cstdio>
#include <set>

#include <weft/Device.h>
#include <weft/Renderer.h>
#include <weft/Scene.h>

int main() {
    try {
        weft::Scene scene;
        weft::Camera camera;
        weft::makeDefaultScene(scene, camera);
        weft::Renderer renderer(96, 64);
        const weft::Frame frame = renderer.render(scene, camera, weft::OutputColor);
        if (frame.color.width != 96 || frame.color.height != 64 || frame.color.channels != 4) {
            std::fprintf(stderr, "unexpected image size\n");
            return 1;
        }
        // A lit, textured, shadowed scene has many distinct colours; a failed frame has one.
        std::set<unsigned> colours;
        for (size_t i = 0; i < frame.color.pixels.size(); i += 4)
            colours.insert(unsigned(frame.color.pixels[i]) << 16 | frame.color.pixels[i + 1] << 8 |
                           frame.color.pixels[i + 2]);
        if (colours.size() < 50) {
            std::fprintf(stderr, "frame has only %zu colours\n", colours.size());
            return 1;
        }
        for (const auto& m : weft::validationMessages())
            std::fprintf(stderr, "validation: %s\n", m.c_str());
        if (!weft::validationMessages().empty()) return 1;
        std::printf("consumer: rendered %dx%d on %s with %zu colours, passes:", frame.color.width,
                    frame.color.height, renderer.deviceName().c_str(), colours.size());
        for (const auto& p : renderer.stats().passes) std::printf(" %s", p.name.c_str());
        std::printf("\n");
        return 0;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "consumer failed: %s\n", e.what());
        return 1;
    }
}
