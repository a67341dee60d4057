#pragma once
// The scene environment on the GPU (SPEC §4.4): a cube image holding the GGX-prefiltered chain
// (specular) and the SH9 irradiance coefficients (diffuse, in the frame uniforms). Baked and
// uploaded again only when the environment's content or the chain parameters change.
#include <array>
#include <cstdint>
#include <memory>

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

private:
    // What the uploaded chain was baked from (weak: a new environment at a freed address differs).
    struct Key {
        std::weak_ptr<Environment> environment;
        uint64_t version = 0;
        int size = 0, levels = 0, samples = 0;
        bool same(const Key& o) const {
            return environment.lock() == o.environment.lock() && version == o.version &&
                   size == o.size && levels == o.levels && samples == o.samples;
        }
    };
    void upload(const CubeMap& chain);

    vk::Context& mCtx;
    vk::Image mBlack, mCube;
    Key mKey;
    std::array<glm::vec4, 9> mSh{}; // A_l L_lm / pi
};

} // namespace weft::render
