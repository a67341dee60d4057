#include <weft/DemoScene.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <GLFW/glfw3.h>
#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <weft/BtfRenderMaterial.h>
#include <weft/BtfSynth.h>
#include <weft/Environment.h>
#include <weft/HairGenerator.h>
#include <weft/IblConvert.h>
#include <weft/Sky.h>
#include <weft/SunLight.h>

#include "core/Srgb.h"

namespace weft::app {

namespace {

constexpr int kClothN = 32; // the seed's 32 x 32 particles
constexpr float kTerrainSize = 16.0f;
constexpr int kTerrainCells = 96;
const glm::vec3 kSphereCenter(0.0f, 0.6f, 0.0f);
constexpr float kSphereRadius = 0.6f;
// The analytic sky (weft/Sky.h): a clear day; radiance scaled so that the noon sun's light has
// intensity ~1 as the seed's had (E ~ 100 klx -> E / pi / 32); with no exposure control yet the
// night sky is raised from the natural night's ~1e-7 kcd/m^2 to a moonlit blue that shows.
constexpr float kTurbidity = 3.0f;
constexpr float kSkyScale = 1.0f / 32.0f;
const glm::vec3 kNightSky = glm::vec3(0.012f, 0.018f, 0.04f) / kSkyScale;
// the sky seen behind the scene: ~1.4 deg per texel, bilinear over a smooth sky
constexpr int kSkyCubeSize = 64;
const float kSkyRegenCos = std::cos(glm::radians(1.0f)); // regenerate after the sun moved 1 deg

float smoothstep(float e0, float e1, float x) {
    const float t = std::clamp((x - e0) / (e1 - e0), 0.0f, 1.0f);
    return t * t * (3.0f - 2.0f * t);
}

// Rolling hills that flatten towards the middle, where the sphere and the cloth are.
float terrainHeight(float x, float z) {
    const float hills = 0.45f * std::sin(0.45f * x + 0.3f) * std::cos(0.35f * z) +
                        0.25f * std::sin(0.9f * x - 0.7f * z) +
                        0.08f * std::cos(1.7f * x + 1.1f * z);
    return hills * smoothstep(2.0f, 5.0f, std::sqrt(x * x + z * z));
}

// Grass-like ground: green noise from a few octaves of hashed values. `meanAlbedo`: the texels'
// mean linear colour (the sky's ground beyond the terrain takes it).
TexturePtr grassTexture(int size, glm::vec3& meanAlbedo) {
    ImageU8 img(size, size, 4);
    auto hash = [](int x, int y) {
        uint32_t h = uint32_t(x) * 374761393u + uint32_t(y) * 668265263u;
        h = (h ^ (h >> 13)) * 1274126177u;
        return float(h & 0xffff) / 65535.0f;
    };
    glm::dvec3 sum(0.0);
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const float n =
                0.5f * hash(x, y) + 0.3f * hash(x / 4, y / 4) + 0.2f * hash(x / 16, y / 16);
            const glm::vec3 c =
                glm::mix(glm::vec3(0.18f, 0.32f, 0.10f), glm::vec3(0.42f, 0.55f, 0.22f), n);
            uint8_t* p = img.at(x, y);
            for (int k = 0; k < 3; ++k) {
                p[k] = uint8_t(std::lround(255.0f * c[k]));
                const float e = float(p[k]) / 255.0f; // sRGB-encoded: decoded when sampled
                sum[k] += srgbToLinear(e);
            }
            p[3] = 255;
        }
    meanAlbedo = glm::vec3(sum / double(size * size));
    return std::make_shared<Texture>(std::move(img), true, true);
}

// Woven cloth: alternating warp and weft threads.
TexturePtr weaveTexture(int size, int threads) {
    ImageU8 img(size, size, 4);
    const int cell = size / threads;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool warp = ((x / cell) + (y / cell)) % 2 == 0;
            const float f = float(warp ? x % cell : y % cell) / float(cell);
            const float shade = 0.75f + 0.25f * std::sin(glm::pi<float>() * f);
            const glm::vec3 c =
                (warp ? glm::vec3(0.72f, 0.16f, 0.12f) : glm::vec3(0.85f, 0.72f, 0.45f)) * shade;
            uint8_t* p = img.at(x, y);
            for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::lround(255.0f * c[k]));
            p[3] = 255;
        }
    return std::make_shared<Texture>(std::move(img), true, true);
}

// The weave's tangent-space normals: each thread is a half cylinder across its width.
TexturePtr weaveNormals(int size, int threads) {
    ImageU8 img(size, size, 4);
    const int cell = size / threads;
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool warp = ((x / cell) + (y / cell)) % 2 == 0;
            const float f = (float(warp ? x % cell : y % cell) + 0.5f) / float(cell) * 2.0f - 1.0f;
            const float slope = 0.8f * f;
            glm::vec3 n = warp ? glm::vec3(slope, 0.0f, 1.0f) : glm::vec3(0.0f, -slope, 1.0f);
            n = glm::normalize(n) * 0.5f + 0.5f;
            uint8_t* p = img.at(x, y);
            for (int k = 0; k < 3; ++k) p[k] = uint8_t(std::lround(255.0f * n[k]));
            p[3] = 255;
        }
    return std::make_shared<Texture>(std::move(img), false, true);
}

// The cloth's BTF material the way the seed made one (SPEC §3): a woven fabric's BTF rendered
// for the 81 frontal light directions, then fitted (linear fit + specular search, eq. 4.30).
Material fittedWeaveBtf(int size, int threads) {
    BtfMaterialMaps truth;
    truth.width = truth.height = size;
    const int cell = size / threads;
    std::vector<float> height(size_t(size) * size_t(size));
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool warp = ((x / cell) + (y / cell)) % 2 == 0;
            const float f = (float(warp ? x % cell : y % cell) + 0.5f) / float(cell);
            height[size_t(y * size + x)] = 2.0f * std::sin(glm::pi<float>() * f);
        }
    auto h = [&](int x, int y) {
        return height[size_t(((y + size) % size) * size + (x + size) % size)];
    };
    for (int y = 0; y < size; ++y)
        for (int x = 0; x < size; ++x) {
            const bool warp = ((x / cell) + (y / cell)) % 2 == 0;
            // normals: x right, y up (rows grow down), from the height field in texel units
            const glm::vec3 n = glm::normalize(glm::vec3(-0.5f * (h(x + 1, y) - h(x - 1, y)),
                                                         0.5f * (h(x, y + 1) - h(x, y - 1)), 1.0f));
            const glm::vec3 a =
                warp ? glm::vec3(0.55f, 0.12f, 0.1f) : glm::vec3(0.75f, 0.62f, 0.35f);
            for (int c = 0; c < 3; ++c) {
                truth.normal.push_back(n[c]);
                truth.albedo.push_back(a[c]);
                truth.ambient.push_back(0.12f);
                truth.specular.push_back(0.25f);
            }
        }
    truth.exponent = 40.0f;
    truth.flatSpecularNormal = true;
    std::vector<BtfAngles> angles;
    for (const glm::vec2& d : btfStandardDirections()) angles.push_back({d.x, d.y, 0.0f, 0.0f});
    const BtfSamples samples = renderBtf(truth, angles);
    const BtfSpecularFit fit = fitBtfSpecular(samples, fitBtfLinear(samples));
    return btfRenderMaterial(fit.maps);
}

} // namespace

DemoScene::DemoScene() {
    buildTerrain();

    Material sphere;
    sphere.baseColor = glm::vec3(0.55f, 0.58f, 0.62f);
    sphere.ks = glm::vec3(0.6f);
    sphere.shininess = 64.0f;
    mSphereMaterial = sphere;
    mSphereId =
        mScene.addMesh(std::make_shared<Mesh>(Mesh::uvSphere(kSphereRadius - 0.01f, 48, 24)),
                       sphere, glm::translate(glm::mat4(1.0f), kSphereCenter));

    // A furry ball next to the cloth (SPEC §5.1: fur grown from a mesh, seed listing 1).
    const auto ballMesh = std::make_shared<Mesh>(Mesh::uvSphere(0.28f, 24, 12));
    const glm::mat4 ballAt = glm::translate(glm::mat4(1.0f), glm::vec3(1.35f, 0.3f, 0.55f));
    Material skin;
    skin.baseColor = glm::vec3(0.35f, 0.22f, 0.1f);
    mBallMaterial = skin;
    mBallId = mScene.addMesh(ballMesh, skin, ballAt);
    FurParams fur;
    fur.density = 9000.0f; // strands per square metre
    fur.segments = 6;
    fur.length = 0.09f;
    fur.lengthJitter = 0.3f;
    fur.directionJitter = 0.35f;
    fur.down = glm::vec3(0.0f, -6.0f, 0.0f);
    mFurMaterial.model = HairModel::KajiyaKay;
    mFurMaterial.diffuse = glm::vec3(0.5f, 0.32f, 0.15f);
    mFurMaterial.specular = glm::vec3(0.15f);
    HairStrands strands = generateFur(*ballMesh, fur);
    strands.defaultTransparency = 0.25f; // drawn through weighted blended OIT (SPEC §5.4)
    mFurId =
        mScene.addHair(std::make_shared<HairStrands>(std::move(strands)), mFurMaterial, ballAt);

    ClothParams p;
    p.nx = p.ny = kClothN;
    p.size = glm::vec2(1.8f, 1.8f);
    p.origin = glm::vec3(-0.9f, 1.75f, -0.5f); // held above the back of the sphere
    p.axisU = glm::vec3(1, 0, 0);
    p.axisV = glm::vec3(0, 0, 1);
    p.iterations = 4;
    p.substeps = 2;
    p.tethers = true;
    p.thickness = 0.015f;
    mCloth = std::make_shared<Cloth>(p);
    std::vector<int> edge;
    for (int i = 0; i < kClothN; ++i) edge.push_back(i); // held at one edge (row j = 0)
    mCloth->pin(edge);
    Collider ball;
    ball.kind = Collider::Kind::Sphere;
    ball.center = kSphereCenter;
    ball.radius = kSphereRadius;
    ball.friction = 0.3f;
    mCloth->addCollider(ball);
    Collider ground;
    ground.kind = Collider::Kind::HeightField;
    ground.rows = ground.cols = kTerrainCells + 1;
    ground.origin = glm::vec3(-0.5f * kTerrainSize, 0.0f, -0.5f * kTerrainSize);
    ground.size = glm::vec2(kTerrainSize);
    for (int j = 0; j <= kTerrainCells; ++j)
        for (int i = 0; i <= kTerrainCells; ++i)
            ground.heights.push_back(
                terrainHeight(ground.origin.x + kTerrainSize * float(i) / kTerrainCells,
                              ground.origin.z + kTerrainSize * float(j) / kTerrainCells));
    ground.friction = 0.5f;
    mCloth->addCollider(ground);
    mCloth->setWind(
        Wind{glm::vec3(std::cos(mWindAngle), 0.0f, std::sin(mWindAngle)), mWindStrength});

    mWeaveNormals = weaveNormals(256, 16);
    mClothMaterial.texture = weaveTexture(256, 16);
    mClothMaterial.normalMap = mWeaveNormals;
    mClothMaterial.ks = glm::vec3(0.15f);
    mClothMaterial.shininess = 20.0f;
    mClothId = mScene.addCloth(mCloth, mClothMaterial);

    mSunId = mScene.addLight(DirectionalLight{});
    mMoonId = mScene.addLight(DirectionalLight{});
    updateSky();

    mCamera.position = glm::vec3(2.6f, 2.3f, 3.6f);
    mCamera.target = glm::vec3(0.0f, 0.7f, -0.2f);
    mCamera.fovY = 0.8f;
}

void DemoScene::buildTerrain() {
    std::vector<float> heights;
    const glm::vec3 origin(-0.5f * kTerrainSize, 0.0f, -0.5f * kTerrainSize);
    for (int j = 0; j <= kTerrainCells; ++j)
        for (int i = 0; i <= kTerrainCells; ++i)
            heights.push_back(terrainHeight(origin.x + kTerrainSize * float(i) / kTerrainCells,
                                            origin.z + kTerrainSize * float(j) / kTerrainCells));
    Material ground;
    ground.texture = grassTexture(256, mGroundAlbedo);
    ground.ks = glm::vec3(0.03f);
    ground.shininess = 8.0f;
    mTerrainMaterial = ground;
    mTerrainId = mScene.addMesh(
        std::make_shared<Mesh>(Mesh::heightField(heights, kTerrainCells + 1, kTerrainCells + 1,
                                                 origin, glm::vec2(kTerrainSize), 12.0f)),
        ground);
}

void DemoScene::lightWith(const std::string& path) {
    // An equirectangular panorama (2:1) or a 360-degree sphere map (square), as captured;
    // radiance checked (finite, >= 0, at most kMaxEnvironmentRadiance).
    CubeMap cube = loadEnvironmentCube(path, 128);
    EnvironmentLighting env;
    env.environment = std::make_shared<Environment>(std::move(cube));
    env.domeLights = 16; // shadows from the dome (SPEC §4.5), 4 maps refreshed per frame
    env.domeMapSize = 256;
    env.domeRefresh = 4;
    env.domeBlur = 4.0f;   // the accumulated dome shadows blurred over 4 pixels
    env.background = true; // the environment is the demo's sky
    mScene.setEnvironment(env);
    // The environment replaces the sun, the moon, the analytic sky and the ambient term.
    mEnvironmentLit = true;
    mDayNight = false;
    mSky.reset();
    updateSky();
}

void DemoScene::useEnvironmentDiffuse() {
    // Diffuse light from the environment's SH9 irradiance replaces the constant ambient term.
    mTerrainMaterial.environmentDiffuse = mSphereMaterial.environmentDiffuse = 1.0f;
    mClothMaterial.environmentDiffuse = mBallMaterial.environmentDiffuse = 1.0f;
    mScene.setMaterial(mTerrainId, mTerrainMaterial);
    mScene.setMaterial(mSphereId, mSphereMaterial);
    mScene.setMaterial(mBallId, mBallMaterial);
    if (!mBtf) mScene.setMaterial(mClothId, mClothMaterial);
    mScene.setAmbient(glm::vec3(0.0f));
}

void DemoScene::setHour(float hour) {
    if (!(hour >= 0.0f && hour <= 24.0f))
        throw InvalidArgument("time of day must be in [0, 24] hours, got " + std::to_string(hour));
    mTimeOfDay = std::fmod(hour / 24.0f, 1.0f);
    updateSky();
}

void DemoScene::updateSky() {
    // The sun circles in a tilted plane; the moon is opposite. Whichever is up casts shadows.
    const float angle = glm::two_pi<float>() * (mTimeOfDay - 0.25f);
    const float height = std::sin(angle);
    const glm::vec3 toSun =
        glm::normalize(glm::vec3(std::cos(angle) * std::cos(mSunAzimuth), 0.9f * height + 0.05f,
                                 std::cos(angle) * std::sin(mSunAzimuth)));
    const float day = smoothstep(-0.05f, 0.25f, height);
    if (mEnvironmentLit) {
        DirectionalLight off;
        off.intensity = 0.0f;
        off.castShadows = false;
        mScene.setLight(mSunId, off);
        mScene.setLight(mMoonId, off);
        useEnvironmentDiffuse();
        return;
    }
    // The analytic sky lights the scene (SH9 diffuse) and shows on the dome; it is generated
    // again once the sun has moved 1 degree (a day per minute: every ~10 frames at 60 Hz).
    SkyParams sky;
    sky.sunDirection = toSun;
    sky.turbidity = kTurbidity;
    sky.sun = false; // the sun is the directional light, with sharp shadows
    sky.scale = kSkyScale;
    // the ground below the horizon continues the terrain's grass (seen beyond its edge; its
    // light from below is green, as the terrain's would be)
    sky.groundAlbedo = mGroundAlbedo;
    sky.nightRadiance = kNightSky;
    if (!mSky || glm::dot(toSun, mSkySun) < kSkyRegenCos) {
        const auto t0 = std::chrono::steady_clock::now();
        CubeMap cube = skyCube(sky, kSkyCubeSize);
        mSunLight = sunLight(sky);
        mSkyMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                     .count();
        mSkySun = toSun;
        if (!mSky) {
            mSky = std::make_shared<Environment>(std::move(cube));
            EnvironmentLighting env;
            env.environment = mSky;
            env.specularSize = 16; // nothing glossy reflects the sky itself: keep the bake cheap
            env.specularLevels = 5;
            env.background = true; // drawn behind the scene: the sky the viewer sees
            mScene.setEnvironment(env);
            useEnvironmentDiffuse();
        } else {
            mSky->setRadiance(std::move(cube));
        }
    }
    DirectionalLight sun = mSunLight; // colour and intensity from the sky model
    sun.direction = -toSun;
    sun.castShadows = mShadows && sun.intensity > 0.0f;
    DirectionalLight moon;
    moon.direction = toSun;
    moon.color = glm::vec3(0.55f, 0.65f, 1.0f);
    moon.intensity = 0.25f * (1.0f - day);
    moon.castShadows = mShadows && day <= 0.0f;
    mScene.setLight(mSunId, sun);
    mScene.setLight(mMoonId, moon);
}

void DemoScene::applySettings(Renderer& renderer) const {
    RenderSettings s = renderer.settings();
    if (s.pcfRadius != mPcf) {
        s.pcfRadius = mPcf;
        renderer.setSettings(s);
    }
}

int DemoScene::update(float realDt) {
    if (mDayNight) {
        mTimeOfDay = std::fmod(mTimeOfDay + realDt / 60.0f, 1.0f); // one day per minute
        updateSky();
    }
    if (mPaused) return 0;
    return mCloth->advance(realDt, 60.0f, 8);
}

std::string DemoScene::key(int k) {
    std::ostringstream what;
    switch (k) {
    case GLFW_KEY_1:
    case GLFW_KEY_2:
        mWindStrength = std::clamp(mWindStrength + (k == GLFW_KEY_2 ? 1.0f : -1.0f), 0.0f, 30.0f);
        mCloth->setWind(
            Wind{glm::vec3(std::cos(mWindAngle), 0.0f, std::sin(mWindAngle)), mWindStrength});
        what << "wind strength " << mWindStrength;
        break;
    case GLFW_KEY_R:
        mWindAngle += glm::radians(30.0f);
        mCloth->setWind(
            Wind{glm::vec3(std::cos(mWindAngle), 0.0f, std::sin(mWindAngle)), mWindStrength});
        what << "wind direction "
             << std::lround(glm::degrees(std::fmod(mWindAngle, glm::two_pi<float>()))) << " deg";
        break;
    case GLFW_KEY_L:
        mSunAzimuth += glm::radians(15.0f);
        updateSky();
        what << "light azimuth "
             << std::lround(glm::degrees(std::fmod(mSunAzimuth, glm::two_pi<float>()))) << " deg";
        break;
    case GLFW_KEY_T:
        mDayNight = !mDayNight;
        what << "day-night cycle " << (mDayNight ? "on" : "off");
        break;
    case GLFW_KEY_N:
        mNormalMap = !mNormalMap;
        mClothMaterial.normalMap = mNormalMap ? mWeaveNormals : nullptr;
        if (!mBtf) mScene.setMaterial(mClothId, mClothMaterial);
        what << "normal mapping " << (mNormalMap ? "on" : "off");
        break;
    case GLFW_KEY_E: {
        mReflections = !mReflections;
        Material m = mSphereMaterial;
        if (mReflections) { // a mirror-like sphere reflecting a cube captured from its centre
            m.dynamicReflection = true;
            m.reflectivity = glm::vec3(0.6f);
            m.baseColor = glm::vec3(0.15f);
        }
        mScene.setMaterial(mSphereId, m);
        what << "reflective sphere "
             << (mReflections ? "on (dynamic cube capture, Fresnel)" : "off");
        break;
    }
    case GLFW_KEY_K: {
        static const char* const names[] = {"Kajiya-Kay", "Marschner", "Sadeghi"};
        static const HairModel models[] = {HairModel::KajiyaKay, HairModel::Marschner,
                                           HairModel::Sadeghi};
        mFurModel = (mFurModel + 1) % 3;
        mFurMaterial.model = models[mFurModel];
        mScene.setHairMaterial(mFurId, mFurMaterial);
        what << "fur shading " << names[mFurModel];
        break;
    }
    case GLFW_KEY_B:
        mBtf = !mBtf;
        if (mBtf && !mBtfMaterial)
            mBtfMaterial = std::make_unique<Material>(fittedWeaveBtf(256, 16));
        mScene.setMaterial(mClothId, mBtf ? *mBtfMaterial : mClothMaterial);
        what << "BTF material " << (mBtf ? "on (fitted from a synthetic woven BTF)" : "off");
        break;
    case GLFW_KEY_S:
        mShadows = !mShadows;
        updateSky();
        what << "shadows " << (mShadows ? "on" : "off");
        break;
    case GLFW_KEY_P:
        mPcf = (mPcf + 1) % 4;
        what << "PCF " << 2 * mPcf + 1 << "x" << 2 * mPcf + 1;
        break;
    case GLFW_KEY_H: {
        mHoles = !mHoles;
        std::vector<uint8_t> mask(size_t(kClothN * kClothN), 0);
        if (mHoles)
            for (int j = 0; j < kClothN; ++j)
                for (int i = 0; i < kClothN; ++i)
                    mask[size_t(j * kClothN + i)] = std::hypot(i - 16.0f, j - 18.0f) < 4.5f ||
                                                    std::hypot(i - 8.0f, j - 9.0f) < 2.5f;
        mCloth->setHoles(mask);
        what << "holes " << (mHoles ? "on" : "off");
        break;
    }
    case GLFW_KEY_SPACE:
        mPaused = !mPaused;
        what << (mPaused ? "simulation paused" : "simulation running");
        break;
    case GLFW_KEY_C:
        mCloth->reset();
        what << "cloth reset";
        break;
    default: break;
    }
    return what.str();
}

void DemoScene::ray(double x, double y, int w, int h, glm::vec3& origin, glm::vec3& dir) const {
    const glm::mat4 inv = glm::inverse(mCamera.projection(float(w) / float(h)) * mCamera.view());
    const float nx = float(2.0 * (x + 0.5) / w - 1.0), ny = float(2.0 * (y + 0.5) / h - 1.0);
    glm::vec4 a = inv * glm::vec4(nx, ny, 0.0f, 1.0f), b = inv * glm::vec4(nx, ny, 1.0f, 1.0f);
    origin = glm::vec3(a) / a.w;
    dir = glm::normalize(glm::vec3(b) / b.w - origin);
}

bool DemoScene::grab(double x, double y, int w, int h) {
    glm::vec3 o, d;
    ray(x, y, w, h, o, d);
    const int k = mCloth->pick(o, d, 0.12f);
    if (k < 0) return false;
    const float* p = mCloth->particleData() + 4 * k;
    const glm::vec3 pos(p[0], p[1], p[2]);
    mGrabDepth =
        glm::dot(pos - mCamera.position, glm::normalize(mCamera.target - mCamera.position));
    mGrabbed = k;
    mCloth->grab({k}, {pos});
    return true;
}

void DemoScene::drag(double x, double y, int w, int h) {
    if (mGrabbed < 0) return;
    glm::vec3 o, d;
    ray(x, y, w, h, o, d);
    const glm::vec3 forward = glm::normalize(mCamera.target - mCamera.position);
    const float along = glm::dot(d, forward);
    if (along < 1e-4f) return;
    const float t = (mGrabDepth - glm::dot(o - mCamera.position, forward)) / along;
    mCloth->moveGrab({o + d * t});
}

void DemoScene::release() {
    if (mGrabbed < 0) return;
    mCloth->release();
    mGrabbed = -1;
}

float DemoScene::windDirection() const {
    return std::fmod(glm::degrees(mWindAngle) + 360.0f * 64.0f, 360.0f);
}

void DemoScene::setWind(float strength, float directionDegrees) {
    if (!(strength >= 0.0f && strength <= 30.0f) || !std::isfinite(directionDegrees))
        throw InvalidArgument("wind strength must be in [0, 30] and its direction finite");
    mWindStrength = strength;
    mWindAngle = glm::radians(std::fmod(directionDegrees, 360.0f));
    mCloth->setWind(
        Wind{glm::vec3(std::cos(mWindAngle), 0.0f, std::sin(mWindAngle)), mWindStrength});
}

float DemoScene::lightAzimuth() const {
    return std::fmod(glm::degrees(mSunAzimuth) + 360.0f * 64.0f, 360.0f);
}

void DemoScene::setLightAzimuth(float degrees) {
    if (!std::isfinite(degrees)) throw InvalidArgument("light azimuth must be finite");
    mSunAzimuth = glm::radians(std::fmod(degrees, 360.0f));
    updateSky();
}

const char* DemoScene::controls() {
    return "left-drag grabs the cloth; arrows orbit the camera; 1/2 wind weaker/stronger, R turns "
           "the wind, L orbits the light, T day-night cycle, N normal mapping, B BTF material, E "
           "reflective sphere, K fur shading model, S "
           "shadows, P PCF size, H holes, C resets the cloth, Space pauses, Esc/Q quits";
}

std::string DemoScene::status() const {
    std::ostringstream s;
    s << "wind " << mWindStrength << " @ "
      << std::lround(glm::degrees(std::fmod(mWindAngle, glm::two_pi<float>()))) << " deg, time "
      << std::lround(24.0f * mTimeOfDay) << "h" << (mDayNight ? " (cycling)" : "") << ", PCF "
      << 2 * mPcf + 1
      << (mBtf         ? ", BTF"
          : mNormalMap ? ", normal map"
                       : "")
      << (mHoles ? ", holes" : "") << (mShadows ? "" : ", no shadows")
      << (mPaused ? ", paused" : "");
    if (mSky) s << ", analytic sky " << std::fixed << std::setprecision(2) << mSkyMs << " ms";
    return s.str();
}

} // namespace weft::app
