#include "render/DomeShadows.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include <weft/Environment.h>

#include "render/FrameData.h"
#include "render/RenderTargets.h"

namespace weft::render {

std::vector<int> DomeShadows::prepare(const Scene& scene, const RenderSettings& settings,
                                      const std::vector<uint64_t>& casterKey, uint64_t frame) {
    const EnvironmentLighting& env = scene.environment();
    // casterKey is empty exactly when nothing casts a shadow
    mAmbient = ambientReadsAsSky(scene, settings) && !casterKey.empty();
    if (!mAmbient && (!env.environment || env.domeLights == 0)) {
        mLights.clear();
        mMaps = vk::Image();
        mFrustumKey.clear();
        return {};
    }
    glm::vec3 lo, hi;
    scene.bounds(lo, hi, true);
    // Cached by the environment's content version: unchanged radiance integrates nothing. The
    // ambient's sky is one uniform environment for every renderer.
    static const std::shared_ptr<Environment> uniformSky = [] {
        CubeMap sky(16);
        std::fill(sky.data(), sky.data() + sky.floatCount(), 1.0f);
        return std::make_shared<Environment>(std::move(sky));
    }();
    const ShadowDome dome = mAmbient ? uniformSky->shadowDome(int(settings.ambientOcclusion))
                                     : env.environment->shadowDome(env.domeLights);
    mBlur = mAmbient ? settings.ambientOcclusionBlur : env.domeBlur;
    mBlurTolerance = env.domeBlurDepthTolerance;
    const unsigned size = unsigned(env.domeMapSize);
    std::vector<GpuDomeLight> lights;
    std::vector<uint64_t> frustumKey;
    for (const DomeLight& l : dome.lights()) {
        const ShadowFrustum f = fitDirectionalShadow(l.direction, lo, hi, size);
        GpuDomeLight g;
        g.viewProj = f.viewProj;
        g.direction = glm::vec4(l.direction, settings.normalOffset * f.texelWorld);
        // the light's soft-shadow filter (environment.glsl) spreads over tan of its angular
        // radius per unit of receiver-blocker distance; capped at 60 degrees
        g.intensity =
            glm::vec4(l.intensity / 3.14159265f, std::tan(std::min(l.angularRadius, 1.0471976f)));
        lights.push_back(g);
        const size_t at = frustumKey.size();
        frustumKey.resize(at + sizeof(glm::mat4) / 8);
        std::memcpy(frustumKey.data() + at, &f.viewProj, sizeof(glm::mat4));
    }
    mLights = std::move(lights);
    const uint32_t n = uint32_t(mLights.size());
    std::vector<int> render;
    if (!mMaps || mMaps.desc().layers != n || mMaps.desc().width != size ||
        frustumKey != mFrustumKey || !settings.reuseShadowMaps) {
        if (!mMaps || mMaps.desc().layers != n || mMaps.desc().width != size) {
            vk::ImageDesc d;
            d.width = d.height = size;
            d.layers = n;
            d.format = kDepthFormat;
            d.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
            mMaps = vk::Image(&mCtx, d);
        }
        for (uint32_t i = 0; i < n; ++i) render.push_back(int(i));
        mCurrent.assign(n, 1);
    } else {
        if (casterKey != mCasterKey) mCurrent.assign(n, 0); // every map is stale now
        const int perFrame = env.domeRefresh > 0 && !mAmbient ? env.domeRefresh : int(n);
        int rendered = 0;
        // Round robin over the stale maps, starting where the frame index points.
        for (uint32_t k = 0; k < n && rendered < perFrame; ++k) {
            const uint32_t i = uint32_t((frame * uint64_t(perFrame) + k) % n);
            if (mCurrent[i]) continue;
            render.push_back(int(i));
            mCurrent[i] = 1;
            ++rendered;
        }
    }
    mFrustumKey = std::move(frustumKey);
    mCasterKey = casterKey;
    return render;
}

} // namespace weft::render
