// Hair through the C++ API: Scene::addHair validates, bounds include hair, and a frame adds the
// hair passes only for what the scene has.
#include <gtest/gtest.h>

#include <memory>
#include <string>
#include <vector>

#include <weft/Debug.h>
#include <weft/Device.h>
#include <weft/Renderer.h>
#include <weft/Scene.h>

namespace {

std::vector<std::string> passNames(const weft::Renderer& r) {
    std::vector<std::string> out;
    for (const auto& p : r.stats().passes) out.push_back(p.name);
    return out;
}

std::shared_ptr<weft::HairStrands> twoStrands(float transparency) {
    auto h = std::make_shared<weft::HairStrands>();
    h->points = {{-0.5f, 0.0f, 0.0f}, {0.5f, 0.0f, 0.0f}, {-0.5f, 0.2f, 0.0f}, {0.5f, 0.2f, 0.0f}};
    h->defaultSegments = 1;
    h->defaultTransparency = transparency;
    return h;
}

} // namespace

TEST(HairScene, AddHairValidatesAndExtendsBounds) {
    weft::Scene scene;
    EXPECT_THROW(scene.addHair(nullptr), weft::InvalidArgument);
    auto bad = twoStrands(0.0f);
    bad->defaultSegments = 2; // 4 points are not strands of 3
    EXPECT_THROW(scene.addHair(bad), weft::InvalidArgument);
    const uint32_t id = scene.addHair(twoStrands(0.0f), {}, glm::mat4(2.0f));
    EXPECT_EQ(id, 0u);
    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    EXPECT_FLOAT_EQ(lo.x, -1.0f);
    EXPECT_FLOAT_EQ(hi.y, 0.4f);
    EXPECT_THROW(scene.setHairTransform(1, glm::mat4(1.0f)), weft::InvalidArgument);
    EXPECT_THROW(scene.setHairTransform(0, glm::mat4(0.0f)), weft::InvalidArgument);
}

TEST(HairScene, FrameRunsOnlyTheHairPassesTheSceneNeeds) {
    weft::clearValidationMessages();
    weft::Scene scene;
    scene.addHair(twoStrands(0.0f));
    weft::DirectionalLight sun;
    sun.direction = {0.0f, -1.0f, 0.0f};
    sun.castShadows = true;
    scene.addLight(sun);
    weft::Camera camera;
    camera.position = {0.0f, 0.1f, 2.0f};
    camera.target = {0.0f, 0.1f, 0.0f};
    weft::RenderSettings settings;
    settings.shadowMapSize = 64;
    settings.hairDomSize = 32;
    settings.ambientOcclusion = 0; // the hair would occlude the ambient through a dome
    weft::Renderer r(32, 32, settings);
    r.render(scene, camera, weft::OutputLinear);
    // anti-aliased (msaa 4, the default): opaque strands' partly covered pixels are accumulated
    // and composited after the entirely covered ones
    EXPECT_EQ(passNames(r), (std::vector<std::string>{"shadow[0]", "forward", "hair_dom_depth",
                                                      "hair_dom_opacity", "hair", "hair_fringe",
                                                      "hair_composite", "readback"}));
    EXPECT_EQ(weft::debug::hairDeepOpacity(r, 0).texels.size(), 32u * 32u * 4u);
    scene.addHair(twoStrands(0.5f));
    settings.hairDeepOpacity = false;
    r.setSettings(settings);
    r.render(scene, camera, weft::OutputLinear);
    EXPECT_EQ(passNames(r), (std::vector<std::string>{"shadow[0]", "forward", "hair", "hair_fringe",
                                                      "hair_oit", "hair_composite", "readback"}));
    settings.msaa = 1; // no anti-aliasing: one strand per pixel (the shadow map is reused)
    r.setSettings(settings);
    r.render(scene, camera, weft::OutputLinear);
    EXPECT_EQ(passNames(r), (std::vector<std::string>{"forward", "hair", "hair_oit",
                                                      "hair_composite", "readback"}));
    for (const auto& m : weft::validationMessages()) ADD_FAILURE() << "validation: " << m;
}
