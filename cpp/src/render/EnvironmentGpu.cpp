#include "render/EnvironmentGpu.h"

#include <algorithm>
#include <chrono>
#include <vector>

#include <glm/gtc/packing.hpp>

#include <weft/IblConvert.h>

#include "render/FrameGraph.h"

namespace weft::render {

namespace {

// Half floats: filterable on every device (32-bit float filtering is optional in Vulkan).
constexpr VkFormat kEnvironmentFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

vk::ImageDesc cubeDesc(uint32_t size, uint32_t levels) {
    vk::ImageDesc d;
    d.width = d.height = size;
    d.layers = 6;
    d.mipLevels = levels;
    d.format = kEnvironmentFormat;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
    d.cube = true;
    return d;
}

// A 2D image with `levels` mips (level l: max(1, size >> l)).
vk::ImageDesc imageDesc(uint32_t size, uint32_t levels) {
    vk::ImageDesc d = cubeDesc(size, levels);
    d.layers = 1;
    d.cube = false;
    return d;
}

// RGB floats -> RGBA half floats (alpha 1), appended.
void appendHalves(const float* rgb, size_t texels, std::vector<uint16_t>& out) {
    for (size_t t = 0; t < texels; ++t) {
        for (int c = 0; c < 3; ++c) out.push_back(glm::packHalf1x16(rgb[t * 3 + size_t(c)]));
        out.push_back(glm::packHalf1x16(1.0f));
    }
}

void toShaderRead(vk::Context& ctx, VkCommandBuffer cmd, vk::Image& image) {
    const UseState s = useState(Use::Sampled, false);
    vk::transition(ctx, cmd, image, s.layout, s.stage, s.access);
}

// A 1x1 image (every layer) cleared to black, ready to be sampled: bound where nothing is.
vk::Image blackImage(vk::Context& ctx, const vk::ImageDesc& desc) {
    vk::Image image(&ctx, desc);
    ctx.immediate([&](VkCommandBuffer cmd) {
        vk::transition(ctx, cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_2_CLEAR_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        const VkClearColorValue black{};
        const VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, desc.layers};
        vkCmdClearColorImage(cmd, image.get(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, &black, 1,
                             &range);
        toShaderRead(ctx, cmd, image);
    });
    return image;
}

} // namespace

EnvironmentGpu::EnvironmentGpu(vk::Context& ctx)
    : mCtx(ctx), mBlack(blackImage(ctx, cubeDesc(1, 1))),
      mBlack2d(blackImage(ctx, imageDesc(1, 1))) {}

bool EnvironmentGpu::prepare(const EnvironmentLighting& env, double& bakeMs) {
    bakeMs = 0.0;
    if (!env.environment) return false;
    const auto t0 = std::chrono::steady_clock::now();
    bool uploaded = false;
    // The background's sharp source: the radiance and its mips, only while it is shown.
    const Key radianceKey{env.environment, env.environment->version()};
    if (env.background && !(mRadiance && radianceKey.same(mRadianceKey))) {
        CubeMap radiance = env.environment->radiance();
        radiance.buildMips();
        uploadCube(mRadiance, radiance);
        mRadianceKey = radianceKey;
        uploaded = true;
    }
    const bool sphere = env.lookup == EnvironmentLighting::Lookup::SphereMap;
    const Key key{env.environment,    env.environment->version(), env.specularSize,
                  env.specularLevels, env.specularSamples,        sphere ? env.sphereMapSize : 0};
    if (mCube && key.same(mKey)) {
        if (uploaded)
            bakeMs =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                    .count();
        return uploaded;
    }
    // Environment caches both by content version, so a chain another user already asked for
    // (or a renderer before this one) is not filtered again.
    const Sh9 sh = env.environment->irradianceSh();
    const float a[9] = {1.0f,  2.0f / 3.0f, 2.0f / 3.0f, 2.0f / 3.0f, 0.25f,
                        0.25f, 0.25f,       0.25f,       0.25f}; // A_l / pi
    for (int k = 0; k < 9; ++k) mSh[size_t(k)] = glm::vec4(a[k] * sh.coeffs[size_t(k)], 0.0f);
    const CubeMap chain =
        env.environment->specularChain(env.specularSize, env.specularLevels, env.specularSamples);
    uploadCube(mCube, chain);
    if (sphere) {
        uploadSphereMaps(*env.environment, chain, env.sphereMapSize);
    } else {
        mSphereIrradiance = vk::Image();
        mSphereGlossy = vk::Image();
    }
    mKey = key;
    bakeMs =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return true;
}

void EnvironmentGpu::uploadCube(vk::Image& image, const CubeMap& chain) {
    const uint32_t size = uint32_t(chain.size()), levels = uint32_t(chain.levels());
    std::vector<uint16_t> halves;
    std::vector<VkBufferImageCopy> regions;
    for (uint32_t l = 0; l < levels; ++l) {
        const uint32_t s = uint32_t(chain.levelSize(int(l)));
        VkBufferImageCopy r{};
        r.bufferOffset = halves.size() * sizeof(uint16_t);
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, l, 0, 6};
        r.imageExtent = {s, s, 1};
        regions.push_back(r);
        appendHalves(chain.data(int(l)), size_t(6) * s * s, halves);
    }
    // A new image: a frame in flight may still sample the old one, which is retired after it.
    image = vk::Image(&mCtx, cubeDesc(size, levels));
    uploadImage(image, halves, regions);
}

void EnvironmentGpu::uploadImage(vk::Image& image, const std::vector<uint16_t>& halves,
                                 const std::vector<VkBufferImageCopy>& regions) {
    vk::Buffer staging(&mCtx, halves.size() * sizeof(uint16_t), VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                       vk::MemoryUsage::Upload);
    staging.write(halves.data(), halves.size() * sizeof(uint16_t));
    mCtx.immediate([&](VkCommandBuffer cmd) {
        vk::transition(mCtx, cmd, image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        vkCmdCopyBufferToImage(cmd, staging.get(), image.get(),
                               VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, uint32_t(regions.size()),
                               regions.data());
        toShaderRead(mCtx, cmd, image);
    });
}

// The seed's eye-space sphere maps (SPEC §4.4): the environment is read as eye space (identity
// world -> sphere, wrap 1), the irradiance (E / pi, as the SH9 uniforms hold it) at up to 64^2
// -- it is smooth -- and every level of the GGX chain at size >> level.
void EnvironmentGpu::uploadSphereMaps(Environment& env, const CubeMap& chain, int size) {
    const glm::mat4 eye(1.0f);
    const int irradianceSize = std::min(size, 64);
    std::vector<float> irradiance =
        cubeToSphere(env.irradianceMap(std::max(8, irradianceSize / 2)), irradianceSize, eye, 1.0f);
    for (float& v : irradiance) v /= 3.14159265f;
    std::vector<uint16_t> halves;
    VkBufferImageCopy r{};
    r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    r.imageExtent = {uint32_t(irradianceSize), uint32_t(irradianceSize), 1};
    appendHalves(irradiance.data(), irradiance.size() / 3, halves);
    mSphereIrradiance = vk::Image(&mCtx, imageDesc(uint32_t(irradianceSize), 1));
    uploadImage(mSphereIrradiance, halves, {r});

    const int levels = chain.levels();
    halves.clear();
    std::vector<VkBufferImageCopy> regions;
    for (int l = 0; l < levels; ++l) {
        const int s = std::max(1, size >> l);
        r.bufferOffset = halves.size() * sizeof(uint16_t);
        r.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, uint32_t(l), 0, 1};
        r.imageExtent = {uint32_t(s), uint32_t(s), 1};
        regions.push_back(r);
        const std::vector<float> level = cubeToSphere(chain, s, eye, 1.0f, l);
        appendHalves(level.data(), size_t(s) * s, halves);
    }
    mSphereGlossy = vk::Image(&mCtx, imageDesc(uint32_t(size), uint32_t(levels)));
    uploadImage(mSphereGlossy, halves, regions);
}

void EnvironmentGpu::fillFrame(const EnvironmentLighting& env, GpuFrame& frame) const {
    if (!env.environment || !mCube) {
        frame.environment = glm::vec4(0.0f);
        return;
    }
    frame.environment = glm::vec4(env.intensity, float(mCube.desc().mipLevels - 1), 0.0f, 0.0f);
    // The background: the sharp radiance (level < 0) or the chain at the blur's roughness.
    if (env.background && env.lookup == EnvironmentLighting::Lookup::Cube)
        frame.sky = glm::vec4(1.0f,
                              env.backgroundBlur > 0.0f
                                  ? env.backgroundBlur * float(mCube.desc().mipLevels - 1)
                                  : -1.0f,
                              0.0f, 0.0f);
    if (mSphereGlossy) {
        frame.options.x = 1.0f;
        frame.options.y = float(mSphereGlossy.desc().mipLevels - 1);
    }
    for (int k = 0; k < 9; ++k) frame.environmentSh[k] = mSh[size_t(k)];
}

VkImageView EnvironmentGpu::view(const EnvironmentLighting& env) const {
    return env.environment && mCube ? mCube.view() : mBlack.view();
}

} // namespace weft::render
