#include "render/FrameData.h"

namespace weft::render {

FrameData buildFrameData(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         float aspect, GpuCache& cache) {
    FrameData f;
    for (const MeshInstance& inst : scene.instances()) {
        GpuInstance g;
        g.model = inst.transform;
        g.normalMatrix = glm::transpose(glm::inverse(inst.transform));
        g.ka = glm::vec4(inst.material.ka, 0);
        g.kd = glm::vec4(inst.material.kd, 0);
        g.ks = glm::vec4(inst.material.ks, inst.material.shininess);
        g.baseColor = glm::vec4(inst.material.baseColor, 1);
        f.draws.push_back({&cache.mesh(inst.mesh), cache.texture(inst.material.texture),
                           uint32_t(f.instances.size()), inst.castShadows, inst.transform});
        f.instances.push_back(g);
    }

    glm::vec3 lo, hi;
    scene.bounds(lo, hi);
    f.shadowInfos.assign(scene.lights().size(), ShadowInfo{});
    for (size_t i = 0; i < scene.lights().size(); ++i) {
        const DirectionalLight& l = scene.lights()[i];
        int layer = -1;
        if (l.castShadows && !f.draws.empty() && int(f.shadowLights.size()) < kMaxShadowLights) {
            layer = int(f.shadowLights.size());
            const ShadowFrustum frustum =
                fitDirectionalShadow(l.toLight(), lo, hi, settings.shadowMapSize);
            f.shadowLights.push_back({int(i), layer, frustum});
            ShadowInfo& info = f.shadowInfos[i];
            info.active = true;
            info.layer = layer;
            info.size = settings.shadowMapSize;
            info.viewProj = frustum.viewProj;
            info.normalOffsetWorld = settings.normalOffset * frustum.texelWorld;
            info.settings = settings;
        }
        f.lights.push_back({glm::vec4(l.toLight(), 0), glm::vec4(l.radiance(), float(layer))});
    }

    GpuFrame& g = f.frame;
    g.viewProj = camera.projection(aspect) * camera.view();
    g.cameraPos = glm::vec4(camera.position, 1);
    g.ambient = glm::vec4(scene.ambient(), 0);
    g.background = glm::vec4(scene.background(), 1);
    for (const ShadowLight& s : f.shadowLights) {
        g.lightViewProj[s.layer] = s.frustum.viewProj;
        g.normalOffset[s.layer].x = f.shadowInfos[size_t(s.lightIndex)].normalOffsetWorld;
    }
    g.bias = glm::vec4(settings.biasConstant, settings.biasSlope, settings.biasMax, 0);
    // The debug shadow channel reports the first shadow map (layer 0) when there is one.
    g.counts = glm::ivec4(int(f.lights.size()), settings.pcfRadius, int(settings.shadowMapSize),
                          f.shadowLights.empty() ? -1 : 0);
    return f;
}

} // namespace weft::render
