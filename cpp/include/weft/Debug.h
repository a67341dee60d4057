#pragma once
// What a Renderer drew in its last frame, read back for tests and tools: shadow maps and the
// light transforms to redo a shadow test, the dynamic reflection capture and the hair's deep
// opacity maps. Not needed to render; each call reads GPU memory back (slow).
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include <weft/Renderer.h>

namespace weft {

/// Everything needed to redo the shadow test of light `lightIndex` outside the renderer.
/// Directional lights have one orthographic view, spot lights one perspective view, point
/// lights six perspective views (+X, -X, +Y, -Y, +Z, -Z; a receiver uses the view of its
/// direction from the light's largest component).
struct ShadowInfo {
    bool active = false;          // the light cast shadows in the last frame
    int layer = -1;               // first shadow-map layer
    uint32_t size = 0;            // texels per side
    glm::mat4 viewProj{1.0f};     // world -> light clip space (x, y in [-1,1], depth [0,1])
    std::vector<glm::mat4> views; // viewProj of every view (1 or 6)
    bool perspective = false;     // depth compared as distance: near * far / (far - d (far - near))
    float zNear = 0.0f, zFar = 1.0f;
    /// Receiver offset along the normal: world units (orthographic) or world units per metre of
    /// distance to the light (perspective).
    float normalOffsetWorld = 0.f;
    RenderSettings settings;
};

/// A deep opacity map (SPEC §5.3) of the last frame, for tests and tools. The light's view is
/// orthographic: pixel (x, y) covers local (x, y) in [-extent/2, extent/2]^2 around `center` in
/// the basis of python/weft/reference/hair_shadow.py's LightGrid for `direction` (the way the
/// light travels); local depth z maps to stored depth (z - zNear) / (zFar - zNear).
struct HairDomInfo {
    glm::vec3 direction{0.0f}, center{0.0f};
    float extent = 0.0f;
    float zNear = 0.0f, zFar = 1.0f;
    float layerSize = 0.0f; // d, world units
    bool logSpacing = false;
    uint32_t size = 0;
    /// size * size * 4 floats, rows as the light pixel y: opacity of layers 0, 1, 2 (each
    /// including the layers before) and z0 as stored depth (1 where no hair).
    std::vector<float> texels;
};

namespace debug {

/// The shadow state of light `lightIndex` in the last frame. Throws InvalidArgument for an
/// index that was not a light of the last rendered scene.
ShadowInfo shadowInfo(const Renderer& renderer, int lightIndex);
/// The last frame's shadow map of `lightIndex` (depth in [0,1], rows top to bottom);
/// `view` selects one of a point light's six views.
std::vector<float> shadowMap(Renderer& renderer, int lightIndex, uint32_t* size = nullptr,
                             int view = 0);
/// The last frame's dynamic reflection capture: 6 faces x size^2 x RGBA linear floats in
/// CubeMap.h's face order and orientation. Throws InvalidArgument without one.
std::vector<float> reflectionProbe(Renderer& renderer, uint32_t* size = nullptr);
/// The last frame's deep opacity map of directional light `lightIndex`.
HairDomInfo hairDeepOpacity(const Renderer& renderer, int lightIndex);

} // namespace debug
} // namespace weft
