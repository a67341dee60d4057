#pragma once
// The environment's dome of shadow lights on the GPU (SPEC §4.5, eq. 2.21-2.23): N directional
// lights from Environment::shadowDome, each with an orthographic shadow map in a layer of its own
// depth array. Maps are rendered all at once when the dome or its frusta change, not at all while
// the casters stay (reuse), and `domeRefresh` per frame round robin while casters move (the
// others keep their stale maps). A scene without an environment gets the same dome over a
// uniform sky of radiance 1 when it has a constant ambient and RenderSettings::ambientOcclusion
// asks for it: the dome then occludes the ambient (ambient occlusion).
#include <cstdint>
#include <vector>

#include <weft/Renderer.h>

#include "render/GpuTypes.h"
#include "render/ShadowFit.h"
#include "vk/Resources.h"

namespace weft::render {

class DomeShadows {
public:
    explicit DomeShadows(vk::Context& ctx) : mCtx(ctx) {}

    /// Sets up this frame's dome (none: clears everything). `casterKey` identifies what the casters
    /// look like (the shadow reuse key without light views). Returns the layers to render.
    std::vector<int> prepare(const Scene& scene, const RenderSettings& settings,
                             const std::vector<uint64_t>& casterKey, uint64_t frame);
    bool active() const { return !mLights.empty(); }
    /// The dome stands for the constant ambient (a uniform sky of radiance 1), not an environment.
    bool occludesAmbient() const { return mAmbient; }
    /// The blur of the dome's shadows in pixels (0: none) and its relative depth tolerance.
    float blurRadius() const { return mBlur; }
    float blurDepthTolerance() const { return mBlurTolerance; }
    const std::vector<GpuDomeLight>& lights() const { return mLights; }
    vk::Image& maps() { return mMaps; }
    uint32_t mapSize() const { return mMaps ? mMaps.desc().width : 0; }

private:
    vk::Context& mCtx;
    vk::Image mMaps;
    std::vector<GpuDomeLight> mLights;
    std::vector<uint64_t> mFrustumKey, mCasterKey;
    std::vector<uint8_t> mCurrent; // per layer: rendered for the current casters
    bool mAmbient = false;
    float mBlur = 0.0f, mBlurTolerance = 0.05f;
};

} // namespace weft::render
