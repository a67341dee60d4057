#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <weft/Device.h>
#include <weft/Renderer.h>
#include <weft/Scene.h>

namespace {

std::vector<std::string> passNames(const weft::Renderer& r) {
    std::vector<std::string> out;
    for (const auto& p : r.stats().passes) out.push_back(p.name);
    return out;
}

class RendererTest : public ::testing::Test {
protected:
    void SetUp() override { weft::clearValidationMessages(); }
    void TearDown() override {
        for (const auto& m : weft::validationMessages()) ADD_FAILURE() << "validation: " << m;
    }
};

} // namespace

TEST_F(RendererTest, DefaultSceneRunsAllPassesAndLooksLit) {
    weft::Scene scene;
    weft::Camera camera;
    weft::makeDefaultScene(scene, camera);
    weft::Renderer r(80, 60);
    const weft::Frame f = r.render(scene, camera, weft::OutputColor | weft::OutputLinear);
    EXPECT_EQ(passNames(r), (std::vector<std::string>{"shadow[0]", "forward", "output", "readback"}));
    ASSERT_EQ(f.linear.size(), 80u * 60u * 4u);
    // sRGB output equals the encoded linear output within one level.
    int worst = 0;
    for (size_t i = 0; i < f.linear.size(); i += 4) {
        for (int c = 0; c < 3; ++c) {
            const double x = std::clamp(double(f.linear[i + c]), 0.0, 1.0);
            const double s = x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1 / 2.4) - 0.055;
            worst = std::max(worst, std::abs(int(std::lround(s * 255)) - int(f.color.pixels[i + c])));
        }
        EXPECT_EQ(f.color.pixels[i + 3], 255);
    }
    EXPECT_LE(worst, 1);
}

TEST_F(RendererTest, LinearOnlyCullsTheOutputPass) {
    weft::Scene scene;
    weft::Camera camera;
    weft::makeDefaultScene(scene, camera);
    weft::Renderer r(32, 32);
    r.render(scene, camera, weft::OutputLinear);
    EXPECT_EQ(passNames(r), (std::vector<std::string>{"shadow[0]", "forward", "readback"}));
    EXPECT_EQ(r.stats().culled, std::vector<std::string>{"output"});
}

TEST_F(RendererTest, NoShadowCastingLightMeansNoShadowPass) {
    weft::Scene scene;
    scene.addMesh(std::make_shared<weft::Mesh>(weft::Mesh::uvSphere(0.5f, 16, 8)));
    weft::DirectionalLight light;
    light.castShadows = false;
    scene.addLight(light);
    weft::Camera camera;
    weft::Renderer r(32, 32);
    r.render(scene, camera);
    EXPECT_EQ(passNames(r), (std::vector<std::string>{"forward", "output", "readback"}));
    EXPECT_FALSE(r.shadowInfo(0).active);
}

TEST_F(RendererTest, BadInputThrowsCleanly) {
    EXPECT_THROW(weft::Renderer(0, 10), weft::InvalidArgument);
    weft::Renderer r(8, 8);
    EXPECT_THROW(r.resize(8, 0), weft::InvalidArgument);
    weft::RenderSettings s;
    s.pcfRadius = 99;
    EXPECT_THROW(r.setSettings(s), weft::InvalidArgument);
    weft::Scene scene;
    weft::Camera camera;
    camera.target = camera.position;
    EXPECT_THROW(r.render(scene, camera), weft::InvalidArgument);
    glm::mat4 nan(1.0f);
    nan[3][0] = NAN;
    EXPECT_THROW(scene.addMesh(std::make_shared<weft::Mesh>(weft::Mesh::box()), {}, nan),
                 weft::InvalidArgument);
}

TEST_F(RendererTest, DevicesListExactlyOneSelected) {
    const auto devices = weft::listDevices();
    ASSERT_FALSE(devices.empty());
    EXPECT_EQ(std::count_if(devices.begin(), devices.end(), [](auto& d) { return d.selected; }), 1);
}
