// HairPasses' deep opacity maps (SPEC §5.3): the view fitted around the shadow-casting hair for
// each shadow-casting directional light, what the maps hold (their reuse), and a map read back
// for tests. The passes that draw them are in HairPasses.cpp.
#include <cstring>
#include <string>

#include "render/HairPasses.h"

namespace weft::render {

// An orthographic view per shadow-casting directional light around the shadow-casting hair,
// in the basis of reference/hair_shadow.py's LightGrid (rows right, up, forward).
void HairPasses::fitDoms(const Scene& scene, const RenderSettings& settings) {
    mDoms.clear();
    mLastDoms.assign(scene.lights().size(), HairDomInfo{});
    if (!settings.hairDeepOpacity) return;
    std::vector<glm::vec3> corners;
    for (const HairInstance& h : scene.hairs()) {
        if (!h.castShadows) continue;
        for (int i = 0; i < 8; ++i) {
            const glm::vec3 c((i & 1) ? h.hi.x : h.lo.x, (i & 2) ? h.hi.y : h.lo.y,
                              (i & 4) ? h.hi.z : h.lo.z);
            corners.push_back(glm::vec3(h.transform * glm::vec4(c, 1.0f)));
        }
    }
    if (corners.empty()) return;
    glm::vec3 casterLo, casterHi; // every caster: meshes between the light and the hair shadow it
    scene.bounds(casterLo, casterHi, true);
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& c : corners) {
        lo = glm::min(lo, c);
        hi = glm::max(hi, c);
    }
    const glm::vec3 center = 0.5f * (lo + hi);
    for (size_t i = 0; i < scene.lights().size() && mDoms.size() < size_t(kMaxHairDoms); ++i) {
        const auto* light = std::get_if<DirectionalLight>(&scene.lights()[i]);
        if (!light || !light->castShadows) continue;
        const glm::vec3 f = -glm::normalize(light->toLight());
        const glm::vec3 helper = std::abs(f.y) > 0.9f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
        const glm::vec3 r = glm::normalize(glm::cross(helper, f));
        const glm::vec3 u = glm::cross(f, r);
        float half = 0.0f, zMin = 1e30f, zMax = -1e30f;
        for (const glm::vec3& c : corners) {
            const glm::vec3 q = c - center;
            half = std::max({half, std::abs(glm::dot(q, r)), std::abs(glm::dot(q, u))});
            zMin = std::min(zMin, glm::dot(q, f));
            zMax = std::max(zMax, glm::dot(q, f));
        }
        const float depth = std::max(zMax - zMin, 1e-4f);
        const float extent = 2.0f * half * 1.02f + 1e-4f;
        const float zNear = zMin - 0.01f * depth - 1e-4f, zFar = zMax + 0.01f * depth + 1e-4f;
        float d = settings.hairDomLayerSize;
        if (d <= 0.0f) d = depth / (settings.hairDomLogSpacing ? 7.0f : 3.0f);
        Dom dom;
        dom.light = int(i);
        HairDomInfo& info = dom.info;
        info.direction = f;
        info.center = center;
        info.extent = extent;
        info.zNear = zNear;
        info.zFar = zFar;
        info.layerSize = d;
        info.logSpacing = settings.hairDomLogSpacing;
        info.size = settings.hairDomSize;
        // Rows: x = 2 r.(p - c) / extent, y = 2 u.(p - c) / extent, z = (f.(p - c) - near) / range.
        glm::mat4 m(0.0f);
        auto row = [&](int k, const glm::vec3& axis, float scale, float offset) {
            for (int j = 0; j < 3; ++j) m[j][k] = axis[j] * scale;
            m[3][k] = -glm::dot(axis, center) * scale + offset;
        };
        row(0, r, 2.0f / extent, 0.0f);
        row(1, u, 2.0f / extent, 0.0f);
        row(2, f, 1.0f / (zFar - zNear), -zNear / (zFar - zNear));
        m[3][3] = 1.0f;
        dom.viewProj = m;
        float meshNear = zNear;
        for (int k = 0; k < 8; ++k) {
            const glm::vec3 c((k & 1) ? casterHi.x : casterLo.x, (k & 2) ? casterHi.y : casterLo.y,
                              (k & 4) ? casterHi.z : casterLo.z);
            meshNear = std::min(meshNear, glm::dot(c - center, f) - 1e-3f);
        }
        row(2, f, 1.0f / (zFar - meshNear), -meshNear / (zFar - meshNear));
        dom.meshViewProj = m;
        dom.layerNdc = d / (zFar - zNear);
        mDoms.push_back(dom);
    }
}

std::vector<uint64_t> HairPasses::domKey() const {
    std::vector<uint64_t> key;
    auto add = [&key](const float* v, size_t n) {
        for (size_t i = 0; i < n; ++i) {
            uint32_t bits;
            std::memcpy(&bits, &v[i], sizeof(bits));
            key.push_back(bits);
        }
    };
    for (const Dom& d : mDoms) {
        key.push_back(uint64_t(d.light));
        key.push_back(d.info.size);
        add(&d.viewProj[0][0], 16);
        add(&d.layerNdc, 1);
    }
    for (const HairDraw& d : mDraws) {
        if (!d.castShadows) continue;
        key.push_back(reinterpret_cast<uintptr_t>(d.gpu->vertices.get())); // immutable strands
        add(&d.model[0][0], 16);
    }
    return key;
}

HairDomInfo HairPasses::domInfo(int lightIndex) {
    if (lightIndex < 0 || size_t(lightIndex) >= mLastDoms.size() ||
        mLastDoms[size_t(lightIndex)].size == 0)
        throw InvalidArgument("light " + std::to_string(lightIndex) +
                              " had no deep opacity map in the last frame");
    HairDomInfo info = mLastDoms[size_t(lightIndex)];
    int slot = 0;
    while (mDoms[size_t(slot)].light != lightIndex) ++slot;
    const uint32_t size = mDomOpacity.desc().width;
    vk::Buffer buffer(&mCtx, VkDeviceSize(size) * size * 16, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                      vk::MemoryUsage::Readback);
    mCtx.immediate([&](VkCommandBuffer cmd) {
        const UseState s = useState(Use::TransferRead, false);
        vk::transition(mCtx, cmd, mDomOpacity, s.layout, s.stage, s.access);
        VkBufferImageCopy region{};
        region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, uint32_t(slot), 1};
        region.imageExtent = {size, size, 1};
        vkCmdCopyImageToBuffer(cmd, mDomOpacity.get(), s.layout, buffer.get(), 1, &region);
    });
    info.texels.resize(size_t(size) * size * 4);
    std::memcpy(info.texels.data(), buffer.mapped(), info.texels.size() * sizeof(float));
    return info;
}

} // namespace weft::render
