#pragma once
// Dynamic reflection capture (SPEC §1.3, 000 §2.5.4): the scene rendered into the 6 faces of a
// cube from the position of the first instance whose material has `dynamicReflection`, used as
// that material's reflection. Re-captured only when something the faces show may have changed
// (the capture key: scene version, mesh contents, environment version, position, size).
#include <cstdint>
#include <vector>

#include <weft/Scene.h>

#include "render/FrameData.h"
#include "vk/Resources.h"

namespace weft::render {

/// World -> clip of cube face `face` seen from `position`, in CubeMap.h's face order and
/// orientation (face texel (i, j) looks along that face's (u, v) direction), depth 0..1 over
/// [zNear, zFar]. Its determinant is negative: faces are mirror images of a camera's view.
glm::mat4 probeFaceViewProj(int face, const glm::vec3& position, float zNear, float zFar);

/// What a capture of the scene shows, as a key (equal keys: the capture can be kept): the scene
/// (its version counts every edit), the meshes' contents (cloth moves without editing the
/// scene) and the environment's radiance.
std::vector<uint64_t> captureKey(const Scene& scene, const FrameData& data);

class ReflectionProbe {
public:
    explicit ReflectionProbe(vk::Context& ctx) : mCtx(ctx) {}

    /// Finds this frame's probe (instance index, or -1 without one) and returns whether the faces
    /// must be captured again; the cube is (re)created at `size`.
    bool prepare(const Scene& scene, const FrameData& data, uint32_t size);
    /// The next prepare() captures again (the renderer's settings changed).
    void invalidate() { mKey.clear(); }
    int instance() const { return mInstance; }
    const glm::vec3& position() const { return mPosition; }
    vk::Image& cube() { return mCube; }
    vk::Image& depth() { return mDepth; }

private:
    vk::Context& mCtx;
    vk::Image mCube, mDepth;
    int mInstance = -1;
    glm::vec3 mPosition{0.0f};
    std::vector<uint64_t> mKey;
};

} // namespace weft::render
