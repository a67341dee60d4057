#pragma once
// The scene environment on the GPU (SPEC §4.4): a cube image holding the GGX-prefiltered chain
// (specular) and the SH9 irradiance coefficients (diffuse, in the frame uniforms); for the seed's
// eye-space path, sphere maps of the irradiance and of the chain instead. Baked and uploaded
// again only when the environment's content or the bake parameters change.
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#include <weft/Scene.h>

#include "render/GpuTypes.h"
#include "vk/Resources.h"

namespace weft::render {

class EnvironmentGpu {
public:
    explicit EnvironmentGpu(vk::Context& ctx);

    /// Makes the GPU copy match `env` (no environment: nothing happens, the black 1x1 cube is
    /// bound). Returns true when it baked and uploaded; `bakeMs` receives the time that took.
    bool prepare(const EnvironmentLighting& env, double& bakeMs);
    /// Fills the frame's environment uniforms (zero intensity without an environment).
    void fillFrame(const EnvironmentLighting& env, GpuFrame& frame) const;
    /// The cube view to bind: the chain, or black without an environment.
    VkImageView view(const EnvironmentLighting& env) const;
    VkImageView black() const { return mBlack.view(); }
    /// The eye-space sphere maps (irradiance E / pi, glossy chain), or a black 2D image.
    VkImageView sphereIrradiance() const {
        return mSphereIrradiance ? mSphereIrradiance.view() : mBlack2d.view();
    }
    VkImageView sphereGlossy() const {
        return mSphereGlossy ? mSphereGlossy.view() : mBlack2d.view();
    }
    /// The radiance itself with its mips (uploaded while the environment is the background), or
    /// the black cube.
    VkImageView radianceView() const { return mRadiance ? mRadiance.view() : mBlack.view(); }

private:
    // What the uploaded chain was baked from (weak: a new environment at a freed address differs).
    struct Key {
        std::weak_ptr<Environment> environment;
        uint64_t version = 0;
        int size = 0, levels = 0, samples = 0, sphereSize = 0; // sphereSize 0: cube lookups
        bool same(const Key& o) const {
            return environment.lock() == o.environment.lock() && version == o.version &&
                   size == o.size && levels == o.levels && samples == o.samples &&
                   sphereSize == o.sphereSize;
        }
    };
    void uploadCube(vk::Image& image, const CubeMap& cube);
    void uploadSphereMaps(Environment& env, const CubeMap& chain, int size);
    void uploadImage(vk::Image& image, const std::vector<uint16_t>& halves,
                     const std::vector<VkBufferImageCopy>& regions);

    vk::Context& mCtx;
    vk::Image mBlack, mBlack2d, mCube, mSphereIrradiance, mSphereGlossy, mRadiance;
    Key mKey;
    Key mRadianceKey;               // what mRadiance holds (size, levels, samples unused)
    std::array<glm::vec4, 9> mSh{}; // A_l L_lm / pi
};

} // namespace weft::render
