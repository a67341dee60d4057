#include "render/FrameData.h"

#include <cmath>
#include <string>

namespace weft::render {

namespace {

glm::vec4 attenuationOf(const Attenuation& a) {
    return glm::vec4(a.constant, a.linear, a.quadratic, a.radius);
}

// Slot of a cookie texture in this frame (added on first use), or -1 without one.
int cookieSlot(const TexturePtr& cookie, std::vector<TexturePtr>& cookies) {
    if (!cookie) return -1;
    for (size_t i = 0; i < cookies.size(); ++i)
        if (cookies[i]->id() == cookie->id()) return int(i);
    if (cookies.size() >= size_t(kMaxCookies))
        throw InvalidArgument("a scene may use at most " + std::to_string(kMaxCookies) +
                              " different spot-light cookie textures");
    cookies.push_back(cookie);
    return int(cookies.size() - 1);
}

struct LightBuilder {
    const RenderSettings& settings;
    glm::vec3 lo, hi;
    bool anyCaster;
    FrameData& f;

    // Adds shadow views for light `index`; returns its first layer or -1.
    int addViews(int index, const ShadowFrustum* views, int count) {
        if (!anyCaster || int(f.shadowViews.size()) + count > kMaxShadowLayers) return -1;
        const int first = int(f.shadowViews.size());
        ShadowInfo& info = f.shadowInfos[size_t(index)];
        info.active = true;
        info.layer = first;
        info.size = settings.shadowMapSize;
        info.viewProj = views[0].viewProj;
        info.perspective = views[0].perspective;
        info.zNear = views[0].zNear;
        info.zFar = views[0].zFar;
        info.normalOffsetWorld = settings.normalOffset * views[0].texelWorld;
        info.settings = settings;
        for (int i = 0; i < count; ++i) {
            f.shadowViews.push_back({index, first + i, views[i]});
            info.views.push_back(views[i].viewProj);
            f.shadowLayers.push_back(
                {views[i].viewProj, glm::vec4(info.normalOffsetWorld, views[i].perspective ? 1 : 0,
                                              views[i].zNear, views[i].zFar)});
        }
        return first;
    }

    GpuLight operator()(int index, const DirectionalLight& l) {
        int layer = -1;
        if (l.castShadows) {
            const ShadowFrustum view =
                fitDirectionalShadow(l.toLight(), lo, hi, settings.shadowMapSize);
            layer = addViews(index, &view, 1);
        }
        GpuLight g{};
        g.position = glm::vec4(0, 0, 0, kLightDirectional);
        g.direction = glm::vec4(l.toLight(), -1);
        g.radiance = glm::vec4(l.radiance(), float(layer));
        g.cone = glm::vec4(0.0f, 0.0f, 0.0f, std::tan(l.angularRadius));
        return g;
    }

    GpuLight operator()(int index, const PointLight& l) {
        int layer = -1;
        if (l.castShadows) {
            ShadowFrustum views[6];
            pointShadowFaces(l.position, l.shadowNear, lo, hi, settings.shadowMapSize, views);
            layer = addViews(index, views, 6);
        }
        GpuLight g{};
        g.position = glm::vec4(l.position, kLightPoint);
        g.direction = glm::vec4(0, 0, 0, -1);
        g.radiance = glm::vec4(l.radiance(), float(layer));
        g.attenuation = attenuationOf(l.attenuation);
        return g;
    }

    GpuLight operator()(int index, const SpotLight& l) {
        const glm::vec3 axis = glm::normalize(l.direction);
        int layer = -1;
        if (l.castShadows) {
            glm::vec3 right, up;
            spotBasis(axis, right, up);
            const ShadowFrustum view =
                fitPerspectiveShadow(l.position, axis, up, 2.0f * l.outerAngle, l.shadowNear, lo,
                                     hi, settings.shadowMapSize);
            layer = addViews(index, &view, 1);
        }
        GpuLight g{};
        g.position = glm::vec4(l.position, kLightSpot);
        g.direction = glm::vec4(axis, float(cookieSlot(l.cookie, f.cookies)));
        g.radiance = glm::vec4(l.radiance(), float(layer));
        g.attenuation = attenuationOf(l.attenuation);
        g.cone =
            glm::vec4(std::cos(l.innerAngle), std::cos(l.outerAngle), std::tan(l.outerAngle), 0);
        return g;
    }
};

// The light's group (gpu_types.h), as lightGroup in shading.glsl.
int lightGroup(const GpuLight& l) {
    return gpu::lightGroupOf(int(l.position.w), l.radiance.w >= 0.0f, l.cone.w > 0.0f);
}

// Sorts the lights by group (stable: scene order within a group), fills Frame::lightStart and
// the light features, and maps scene light indices to their places. A light without shadows
// that brings no light (the demo's moon by day) is left out (index -1).
void sortLightsByGroup(FrameData& f) {
    std::vector<GpuLight> byGroup;
    byGroup.reserve(f.lights.size());
    f.gpuLightIndex.assign(f.lights.size(), -1);
    for (int g = 0; g < gpu::LIGHT_GROUPS; ++g) {
        f.frame.lightStart[g / 4][g % 4] = int(byGroup.size());
        for (size_t i = 0; i < f.lights.size(); ++i) {
            const GpuLight& l = f.lights[i];
            if (l.radiance.w < 0.0f && glm::vec3(l.radiance) == glm::vec3(0.0f)) continue;
            if (lightGroup(l) == g) {
                f.gpuLightIndex[i] = int(byGroup.size());
                byGroup.push_back(l);
                f.lightFeatures |= gpu::FEATURE_LIGHT_GROUP << g;
                if (g >= gpu::LIGHT_GROUP_SPOT && l.direction.w >= 0.0f)
                    f.lightFeatures |= gpu::FEATURE_COOKIES;
            }
        }
    }
    f.frame.lightStart[1][3] = int(byGroup.size());
    f.lights = std::move(byGroup);
}

} // namespace

bool ambientReadsAsSky(const Scene& scene, const RenderSettings& settings) {
    const glm::vec3 ambient = scene.ambient();
    return settings.ambientOcclusion > 0 && !scene.environment().environment &&
           glm::max(ambient.x, glm::max(ambient.y, ambient.z)) > 0.0f;
}

FrameData buildFrameData(const Scene& scene, const Camera& camera, const RenderSettings& settings,
                         float aspect, GpuCache& cache) {
    FrameData f;
    bool anyCaster = false;
    for (const MeshInstance& inst : scene.instances()) {
        GpuInstance g;
        g.model = inst.transform;
        g.normalMatrix = glm::transpose(glm::inverse(inst.transform));
        g.ka = glm::vec4(inst.material.ka, inst.material.alphaCutoff);
        const Material& m = inst.material;
        const bool mirrored = glm::determinant(glm::mat3(inst.transform)) < 0.0f;
        const uint32_t flags =
            (m.normalMap ? gpu::MAP_NORMAL : 0u) | (m.ambientMap ? gpu::MAP_AMBIENT : 0u) |
            (m.specularVertexNormal ? gpu::SPECULAR_VERTEX_NORMAL : 0u) |
            (m.glossInAlpha ? gpu::GLOSS_IN_ALPHA : 0u) | (m.phantom ? gpu::PHANTOM : 0u) |
            (m.ambientMapIsRadiance ? gpu::AMBIENT_RADIANCE : 0u) |
            (m.twoSided ? gpu::TWO_SIDED : 0u) | (mirrored ? gpu::MIRRORED : 0u) |
            (m.dynamicReflection ? gpu::DYNAMIC_REFLECTION : 0u) |
            (m.texture ? gpu::MAP_BASE : 0u) | (m.specularMap ? gpu::MAP_SPECULAR : 0u) |
            (m.alphaCutoff > 0.0f ? gpu::ALPHA_TEST : 0u) |
            (m.specularModel == SpecularModel::Ggx ? gpu::SPECULAR_GGX : 0u);
        g.flags = glm::uvec4(flags, 0u, 0u, 0u);
        g.kd = glm::vec4(inst.material.kd, 0.0f);
        g.ks = glm::vec4(inst.material.ks, inst.material.shininess);
        g.baseColor = glm::vec4(inst.material.baseColor, 0.0f);
        g.environment = glm::vec4(inst.material.reflectivity, inst.material.environmentDiffuse);
        g.maps = glm::vec4(m.shininessMax > 0.0f ? std::log2(m.shininessMax / m.shininess) : 0.0f,
                           m.normalScale, 0.0f, 0.0f);
        const MeshGpu* mesh = nullptr;
        if (inst.deformable) {
            const uint64_t before = f.uploadBytes;
            mesh = &cache.deformable(inst.deformable, f.uploadBytes);
            f.meshUploads += f.uploadBytes != before ? 1 : 0;
        } else {
            mesh = &cache.mesh(inst.mesh);
        }
        f.draws.push_back({mesh, cache.materialSet(inst.material), uint32_t(f.instances.size()),
                           inst.castShadows, inst.transform, inst.material.alphaCutoff, mirrored,
                           inst.material.twoSided, inst.material.phantom});
        f.instances.push_back(g);
        anyCaster |= inst.castShadows;
    }
    for (const HairInstance& h : scene.hairs()) anyCaster |= h.castShadows; // drawn by HairPasses

    LightBuilder builder{settings, {}, {}, anyCaster, f};
    scene.bounds(builder.lo, builder.hi, true); // shadow maps enclose the casters only
    f.shadowInfos.assign(scene.lights().size(), ShadowInfo{});
    int debugLight = -1;
    for (size_t i = 0; i < scene.lights().size(); ++i) {
        f.lights.push_back(
            std::visit([&](const auto& l) { return builder(int(i), l); }, scene.lights()[i]));
        if (debugLight < 0 && f.shadowInfos[i].active) debugLight = int(i);
    }
    sortLightsByGroup(f);

    GpuFrame& g = f.frame;
    g.viewProj = camera.projection(aspect) * camera.view();
    g.inverseViewProj = glm::inverse(g.viewProj);
    g.cameraPos = glm::vec4(camera.position, 1);
    g.view = camera.view();
    g.ambient = glm::vec4(scene.ambient(), ambientReadsAsSky(scene, settings) ? 1.0f : 0.0f);
    g.background = glm::vec4(scene.background(), 1);
    g.bias = glm::vec4(settings.biasConstant, settings.biasSlope, settings.biasMax, 0);
    // The debug shadow channel reports the first light with a shadow map.
    g.counts = glm::ivec4(int(f.lights.size()), settings.pcfRadius, int(settings.shadowMapSize),
                          debugLight < 0 ? -1 : f.gpuLightIndex[size_t(debugLight)]);
    return f;
}

// The gpu::FEATURE_* bits a frame's uniform and instances can turn on (frame.glsl): exactly the
// runtime tests of the forward shader, so a pipeline without the others draws the same.
uint32_t frameFeatures(const FrameData& data) {
    bool reflection = false;
    for (const GpuInstance& i : data.instances)
        reflection = reflection || (i.flags.x & gpu::DYNAMIC_REFLECTION) != 0u;
    return (data.frame.environment.x > 0.0f || reflection ? gpu::FEATURE_ENVIRONMENT : 0u) |
           (data.frame.ambient.w > 0.5f ? gpu::FEATURE_AMBIENT_SKY : 0u) |
           (data.frame.sky.z > 0.5f ? gpu::FEATURE_BOUNCE : 0u) |
           (data.frame.environment.z > 0.0f || data.frame.sky.w > 0.5f ? gpu::FEATURE_DOME : 0u) |
           (data.frame.options.x > 0.5f ? gpu::FEATURE_SPHERE_MAP : 0u) | data.lightFeatures;
}

uint32_t materialFeatures(const FrameData& data, uint32_t instance) {
    const GpuInstance& i = data.instances[instance];
    const bool reflective = glm::any(glm::greaterThan(glm::vec3(i.environment), glm::vec3(0.0f)));
    return i.flags.x | (i.flags.y != 0u ? gpu::BOUNCE_CAPTURE : 0u) |
           (reflective ? gpu::REFLECTIVE : 0u);
}

} // namespace weft::render
