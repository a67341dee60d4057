#include "render/BounceProbes.h"

#include <cmath>
#include <cstring>

#include "render/ReflectionProbe.h"
#include "render/RenderTargets.h"

namespace weft::render {

bool BounceProbes::prepare(const Scene& scene, FrameData& data, const RenderSettings& settings) {
    mPositions.clear();
    mHalves.clear();
    data.frame.sky.z = 0.0f;
    for (glm::vec4& s : data.frame.bounceSpheres) s = glm::vec4(0.0f);
    for (glm::vec4& h : data.frame.bounceHalves) h = glm::vec4(0.0f);
    std::vector<uint32_t> casters;
    bool receivers = false;
    for (const Draw& d : data.draws) {
        if (d.phantom || d.mesh->indexCount == 0) continue;
        if (!d.castShadows)
            receivers = true;
        else if (casters.size() < kMaxProbes)
            casters.push_back(d.instance);
    }
    if (!settings.bounce || !receivers || casters.empty()) {
        mKey.clear();
        return false;
    }
    for (uint32_t i = 0; i < casters.size(); ++i) {
        glm::vec3 lo, hi;
        scene.instanceBounds(casters[i], lo, hi);
        const glm::vec3 centre = 0.5f * (lo + hi), half = 0.5f * (hi - lo);
        mPositions.push_back(centre);
        mHalves.push_back(half);
        data.instances[casters[i]].flags.y = i + 1;
        // the proxy whose light the others receive is the ellipsoid of the bounds (the half
        // extents, caster_bounce.glsl); its radius, the RMS of the half extents (a sphere's
        // exactly), places the lit pole bounce_radiance.frag tests the lights' shadows at
        data.frame.bounceSpheres[i] = glm::vec4(centre, std::sqrt(glm::dot(half, half) / 3.0f));
        data.frame.bounceHalves[i] = glm::vec4(half, 0.0f);
        data.frame.bounceInstances[i / 4][i % 4] = int(casters[i]);
    }
    data.frame.sky.z = 1.0f;

    const uint32_t layers = 6 * kMaxProbes;
    if (!mFaces) { // sized for kMaxProbes once: a few hundred kB
        vk::ImageDesc d;
        d.width = d.height = kFaceSize;
        d.layers = layers;
        d.format = kHdrFormat; // the forward pipelines draw into it as they draw the frame
        d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        mFaces = vk::Image(&mCtx, d);
        // one layer per face, kept for bounce_geometry.frag: where the receivers are
        vk::ImageDesc z;
        z.width = z.height = kFaceSize;
        z.layers = layers;
        z.format = kDepthFormat;
        z.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        mDepth = vk::Image(&mCtx, z);
        vk::ImageDesc s;
        s.width = kShColumns;
        s.height = kMaxProbes * kPoints;
        s.format = kShFormat;
        s.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
        mSh = vk::Image(&mCtx, s);
        mShFirst = vk::Image(&mCtx, s);
        s.width = 6 * kFaceSize * kFaceSize;
        mGeometry = vk::Image(&mCtx, s);
        s.width = kRadianceColumns;
        s.height = kMaxProbes;
        mRadiance = vk::Image(&mCtx, s);
        mRadianceFirst = vk::Image(&mCtx, s);
        mKey.clear();
    }
    std::vector<uint64_t> key = captureKey(scene, data);
    for (uint32_t i = 0; i < count(); ++i) {
        uint64_t bits[3] = {0, 0, 0};
        std::memcpy(bits, &mPositions[i], sizeof(glm::vec3));
        std::memcpy(reinterpret_cast<char*>(bits) + sizeof(glm::vec3), &mHalves[i],
                    sizeof(glm::vec3));
        key.insert(key.end(), bits, bits + 3);
    }
    if (key == mKey) return false;
    mKey = std::move(key);
    return true;
}

} // namespace weft::render
