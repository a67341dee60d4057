#include "BenchSets.h"

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iostream>
#include <memory>

#include <glm/gtc/matrix_transform.hpp>

#include <weft/HairGenerator.h>
#include <weft/Image.h>
#include <weft/Renderer.h>
#include <weft/Sky.h>

#include <weft/DemoScene.h>

namespace weft::bench {
namespace {

std::string gImageDir; // --images: the last timed frame of every row is saved here
int gImageCount = 0;

double median(std::vector<double> v) {
    if (v.empty()) return -1.0;
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

std::string thousands(long long n) {
    std::string s = std::to_string(n), out;
    for (size_t i = 0; i < s.size(); ++i) {
        if (i && (s.size() - i) % 3 == 0) out += ',';
        out += s[i];
    }
    return out;
}

// One warm-up frame (uploads, pipelines, environment bake), then `frames` timed frames;
// `beforeFrame(k)` runs untimed before each (k = -1 for the warm-up): a cloth step, a moved
// caster. Fills the row's medians and prints one progress line.
void measure(BenchRow& row, Renderer& renderer, const Scene& scene, const Camera& camera,
             int frames, const std::function<void(int)>& beforeFrame) {
    using Clock = std::chrono::steady_clock;
    if (beforeFrame) beforeFrame(-1);
    renderer.render(scene, camera);
    std::vector<double> wall, gpu;
    std::map<std::string, std::vector<double>> passes;
    for (int k = 0; k < frames; ++k) {
        if (beforeFrame) beforeFrame(k);
        const auto t0 = Clock::now();
        const Frame frame = renderer.render(scene, camera);
        wall.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        if (k == frames - 1 &&
            !gImageDir.empty()) { // after the clock: PNG encoding is not the frame
            char name[32];
            std::snprintf(name, sizeof name, "%02d_", gImageCount++);
            std::string file =
                name + row.set + "_" + std::to_string(row.vertices) + "_" + row.config;
            for (char& c : file)
                if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '+') c = '-';
            savePng(gImageDir + "/" + file + ".png", frame.color);
        }
        const FrameStats& s = renderer.stats();
        if (s.gpuMs >= 0) gpu.push_back(s.gpuMs);
        std::map<std::string, double> byName;
        for (const PassStats& p : s.passes) {
            if (p.gpuMs < 0) continue;
            if (std::find(row.passOrder.begin(), row.passOrder.end(), p.name) ==
                row.passOrder.end())
                row.passOrder.push_back(p.name);
            byName[p.name] += p.gpuMs;
        }
        for (const auto& [name, ms] : byName) passes[name].push_back(ms);
    }
    row.width = int(renderer.width());
    row.height = int(renderer.height());
    row.frames = frames;
    row.wallMs = median(wall);
    row.gpuMs = median(gpu);
    for (auto& [name, v] : passes) row.passGpuMs[name] = median(v);
    std::fprintf(stderr, "weft-bench: %-6s %-34s %-28s %4dx%-4d %9.2f ms wall, %9.2f ms GPU\n",
                 row.set.c_str(), row.workload.c_str(), row.config.c_str(), row.width, row.height,
                 row.wallMs, row.gpuMs);
}

// ---- seed 000: the demo scene ----------------------------------------------------------------

// The demo as weft-demo renders it (its default settings: 4x MSAA, 8 ambient-occlusion lights,
// bounce light), the cloth settled for 1.5 s and stepped once (1/60 s) before every frame.
void demoSet(const BenchOptions& o, std::vector<BenchRow>& rows) {
    const std::vector<std::pair<int, int>> sizes =
        o.quick ? std::vector<std::pair<int, int>>{{320, 180}}
                : std::vector<std::pair<int, int>>{{1280, 720}, {1920, 1080}};
    for (auto [w, h] : sizes) {
        app::DemoScene demo;
        for (int i = 0; i < 90; ++i) demo.update(1.0f / 60.0f);
        Renderer renderer(static_cast<uint32_t>(w), static_cast<uint32_t>(h));
        demo.applySettings(renderer);
        BenchRow row;
        row.set = "demo";
        row.workload = "seed-000 demo scene";
        row.config = "weft-demo defaults, cloth stepped";
        measure(row, renderer, demo.scene(), demo.camera(), o.frames,
                [&](int) { demo.update(1.0f / 60.0f); });
        rows.push_back(row);
    }
}

// The seeds' tables were measured without multisampling, bounce light or ambient occlusion;
// their rows are rendered so, to compare like with like.
RenderSettings seedSettings() {
    RenderSettings s;
    s.msaa = 1;
    s.bounce = false;
    s.ambientOcclusion = 0;
    return s;
}

// ---- seed 002: hair and fur (SPEC §5.5) ------------------------------------------------------

struct StrandItem {
    std::string label;
    std::function<HairStrands()> make;
    double seed[3]; // fps for B, B+S, B+S+T
};

std::vector<StrandItem> strandItems(const BenchOptions& o) {
    auto hair = [](uint32_t strands, uint64_t points) {
        return [=] {
            HairStyle s;
            s.kind = HairStyleKind::Wavy;
            s.strands = strands;
            s.points = points;
            return generateHair(s);
        };
    };
    // Fur on a UV sphere tessellated to the seed's exact vertex counts (the seed used a bunny):
    // 450 x 212 at level 1 gives 2,088,900 points, 198 x 212 at level 5 gives 22,977,900.
    auto fur = [](int segments, int rings, int level) {
        return [=] {
            FurParams p;
            p.level = level;
            return generateFur(Mesh::uvSphere(0.5f, segments, rings), p);
        };
    };
    if (o.quick) return {{"hair", hair(500, 8000), {0, 0, 0}}, {"fur", fur(32, 16, 2), {0, 0, 0}}};
    std::vector<StrandItem> items = {
        {"hair", hair(10000, 160000), {1221, 295, 146}},
        {"hair", hair(10000, 687532), {1141, 262, 96}},
        {"hair", hair(15000, 1031268), {831, 182, 66}},
        {"fur", fur(450, 212, 1), {87, 85, 80}},
    };
    if (o.fur23m) items.push_back({"fur", fur(198, 212, 5), {80, 39, 22}});
    return items;
}

// B: one directional light, no shadows; B+S: + its shadow map and deep opacity map; B+S+T: +
// every point at transparency 0.6 through weighted blended OIT. Sadeghi shading, 800 x 800.
void hairSet(const BenchOptions& o, std::vector<BenchRow>& rows) {
    const int size = o.quick ? 96 : 800;
    RenderSettings settings = seedSettings();
    settings.shadowMapSize = o.quick ? 256 : 2048;
    settings.hairDomSize = o.quick ? 64 : 512;
    // the shadow and deep opacity maps drawn every frame, as the seed's S column times them
    // (weft would keep them while the strands and the light stand still)
    settings.reuseShadowMaps = false;
    Renderer renderer(static_cast<uint32_t>(size), static_cast<uint32_t>(size), settings);
    HairMaterial material;
    material.model = HairModel::Sadeghi;
    material.diffuse = glm::vec3(0.08f, 0.05f, 0.03f);
    const char* configs[] = {"B", "B+S", "B+S+T"};
    for (const StrandItem& item : strandItems(o)) {
        auto strands = std::make_shared<HairStrands>(item.make());
        glm::vec3 lo(1e30f), hi(-1e30f);
        for (const glm::vec3& p : strands->points) {
            lo = glm::min(lo, p);
            hi = glm::max(hi, p);
        }
        const glm::vec3 center = 0.5f * (lo + hi);
        const float radius = 0.5f * glm::length(hi - lo);
        Camera camera;
        camera.position = center + glm::vec3(0.0f, 0.2f, 2.6f) * radius;
        camera.target = center;
        camera.fovY = 0.8f;
        auto seeThrough = std::make_shared<HairStrands>(*strands);
        seeThrough->transparency.assign(seeThrough->pointCount(), 0.6f);
        for (int c = 0; c < 3; ++c) {
            Scene scene;
            scene.setAmbient(glm::vec3(0.05f));
            DirectionalLight light;
            light.direction = glm::vec3(0.3f, -1.0f, -0.4f);
            light.color = glm::vec3(1.0f, 0.95f, 0.9f);
            light.intensity = 2.0f;
            light.castShadows = c > 0;
            scene.addLight(light);
            RenderSettings s = settings;
            s.hairTransparency = c == 2;
            renderer.setSettings(s);
            scene.addHair(c == 2 ? HairStrandsPtr(seeThrough) : HairStrandsPtr(strands), material);
            BenchRow row;
            row.set = "hair";
            row.vertices = (long long)strands->pointCount();
            row.workload = item.label + " " + thousands(row.vertices) + " vertices";
            row.config = configs[c];
            row.seedFps = item.seed[c];
            row.seedSource = "002 tab. 1-2, GTX 980 (SPEC 5.5)";
            measure(row, renderer, scene, camera, o.frames, nullptr);
            rows.push_back(row);
        }
    }
}

// ---- seed 001: shadow-light dome under an environment (SPEC §4.7) ----------------------------

// A scene of about the seed's 40 k vertices, most of them in the objects as in a scene of models
// (a finely tessellated ground would cost lavapipe 2-3x for its tiny triangles alone): a ground,
// a large and a middle sphere, four small ones and a box, every material lit by the
// environment (SH9 diffuse, GGX reflection F0 0.04). Returns the id of the large sphere.
uint32_t buildDomeScene(Scene& scene, Camera& camera, long long& vertices) {
    Material ground;
    ground.baseColor = glm::vec3(0.55f, 0.5f, 0.45f);
    Material red;
    red.baseColor = glm::vec3(0.75f, 0.18f, 0.15f);
    red.ks = glm::vec3(0.5f);
    red.shininess = 48.0f;
    Material green = red;
    green.baseColor = glm::vec3(0.2f, 0.55f, 0.3f);
    for (Material* m : {&ground, &red, &green}) {
        m->environmentDiffuse = 1.0f;
        m->reflectivity = glm::vec3(0.04f);
    }
    auto at = [](float x, float y, float z) {
        return glm::translate(glm::mat4(1.0f), glm::vec3(x, y, z));
    };
    auto add = [&](Mesh mesh, const Material& m, const glm::mat4& t, bool casts) {
        vertices += (long long)mesh.vertexCount();
        return scene.addMesh(std::make_shared<Mesh>(std::move(mesh)), m, t, casts);
    };
    add(Mesh::plane(8.0f, 8.0f, 16, 16), ground, glm::mat4(1.0f), false);
    const uint32_t moving = add(Mesh::uvSphere(0.75f, 192, 96), red, at(-0.9f, 0.75f, 0.0f), true);
    add(Mesh::uvSphere(0.4f, 128, 64), green, at(1.2f, 0.4f, -0.6f), true);
    for (int i = 0; i < 4; ++i)
        add(Mesh::uvSphere(0.25f, 64, 40), i % 2 ? red : green,
            at(-1.6f + 0.9f * float(i), 0.25f, 1.4f), true);
    add(Mesh::box(glm::vec3(0.8f)), green,
        glm::rotate(at(0.9f, 0.4f, 0.6f), 0.6f, glm::vec3(0, 1, 0)), true);
    scene.setAmbient(glm::vec3(0.0f));
    camera = Camera{};
    camera.position = glm::vec3(0.5f, 2.6f, 5.2f);
    camera.target = glm::vec3(0.0f, 0.4f, 0.0f);
    return moving;
}

void domeSet(const BenchOptions& o, std::vector<BenchRow>& rows) {
    const std::vector<std::pair<int, int>> sizes =
        o.quick ? std::vector<std::pair<int, int>>{{160, 120}}
                : std::vector<std::pair<int, int>>{{640, 480}, {1280, 1024}};
    const std::vector<int> counts = o.quick ? std::vector<int>{0, 8} : std::vector<int>{0, 16, 64};
    SkyParams sky;
    sky.sunDirection = glm::vec3(-0.5f, 0.6f, 0.35f);
    sky.scale = 0.05f; // kcd/m^2 -> radiance of order 1
    sky.sun = false;   // no disc: a sub-texel sun would only alias into the 32^2 cube
    auto environment = std::make_shared<Environment>(skyCube(sky, o.quick ? 16 : 32));
    for (auto [w, h] : sizes) {
        Renderer renderer(static_cast<uint32_t>(w), static_cast<uint32_t>(h), seedSettings());
        for (int n : counts) {
            const double seed = w == 640 ? (n == 0    ? 41
                                            : n == 16 ? 28
                                                      : 14)
                                         : (n == 0    ? 41
                                            : n == 16 ? 25
                                                      : 12);
            for (bool rerender : {false, true}) {
                Scene scene;
                Camera camera;
                long long vertices = 0;
                const uint32_t moving = buildDomeScene(scene, camera, vertices);
                EnvironmentLighting e;
                e.environment = environment;
                e.domeLights = n;
                scene.setEnvironment(e);
                const glm::mat4 base =
                    glm::translate(glm::mat4(1.0f), glm::vec3(-0.9f, 0.75f, 0.0f));
                BenchRow row;
                row.set = "dome";
                row.vertices = vertices;
                row.workload = thousands(vertices) + "-vertex scene";
                row.config = std::to_string(n) + " dome lights, maps " +
                             (rerender ? "re-rendered" : "reused");
                if (!o.quick) {
                    row.seedFps = seed;
                    row.seedSource = "001 tab. 4.1, GeForce of 2006 (SPEC 4.7)";
                }
                // Re-rendered: the sphere moves every frame, so every dome map is stale.
                measure(row, renderer, scene, camera, o.frames, [&](int k) {
                    if (rerender)
                        scene.setTransform(
                            moving, glm::translate(base, glm::vec3(0.01f * float(k + 2), 0, 0)));
                });
                rows.push_back(row);
            }
        }
    }
}

} // namespace

std::vector<BenchRow> runSets(const BenchOptions& o) {
    std::vector<BenchRow> rows;
    gImageDir = o.imageDir;
    if (!gImageDir.empty()) std::filesystem::create_directories(gImageDir);
    for (const std::string& set : o.sets) {
        if (set == "demo")
            demoSet(o, rows);
        else if (set == "hair")
            hairSet(o, rows);
        else if (set == "dome")
            domeSet(o, rows);
        else
            throw InvalidArgument("unknown benchmark set '" + set + "' (demo, hair, dome)");
    }
    return rows;
}

} // namespace weft::bench
