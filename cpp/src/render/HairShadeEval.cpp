#include <weft/HairShadeEval.h>

#include <cmath>
#include <cstring>
#include <string>

#include <weft/Error.h>

#include "render/HairShadingGpu.h"
#include "vk/StorageCompute.h"

namespace weft {

namespace {

struct EvalInput {
    glm::vec4 t, l, v;
    uint32_t strand[4];
};
static_assert(sizeof(EvalInput) == 64, "must match glsl/hair/shade_eval.comp");

constexpr uint32_t kGroupSize = 64;

glm::vec3 unit(const glm::vec3& d, const char* what, size_t i) {
    const float len = glm::length(d);
    if (!std::isfinite(len) || len < 1e-20f)
        throw InvalidArgument(std::string("hair shading: ") + what + "[" + std::to_string(i) +
                              "] must be finite and non-zero");
    return d / len;
}

} // namespace

std::vector<glm::vec3> evaluateHairShading(const HairMaterial& material,
                                           const std::vector<glm::vec3>& t,
                                           const std::vector<glm::vec3>& l,
                                           const std::vector<glm::vec3>& v,
                                           const std::vector<uint32_t>& strandIds) {
    const hair::HairShadingGpu params = hair::packHairShading(material);
    const size_t n = t.size();
    if (l.size() != n || v.size() != n || strandIds.size() != n)
        throw InvalidArgument("hair shading: t, l, v and strand ids must have the same length");
    if (n == 0) return {};
    if (n > (size_t(1) << 26)) throw InvalidArgument("hair shading: at most 2^26 samples per call");
    std::vector<EvalInput> inputs(n);
    for (size_t i = 0; i < n; ++i) {
        inputs[i].t = glm::vec4(unit(t[i], "t", i), 0.0f);
        inputs[i].l = glm::vec4(unit(l[i], "l", i), 0.0f);
        inputs[i].v = glm::vec4(unit(v[i], "v", i), 0.0f);
        inputs[i].strand[0] = strandIds[i];
    }

    auto ctx = vk::Context::shared();
    const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
    vk::Buffer paramBuf(ctx.get(), sizeof params, storage, vk::MemoryUsage::Upload);
    vk::Buffer inBuf(ctx.get(), n * sizeof(EvalInput), storage, vk::MemoryUsage::Upload);
    vk::Buffer outBuf(ctx.get(), n * sizeof(glm::vec4), storage, vk::MemoryUsage::Readback);
    paramBuf.write(&params, sizeof params);
    inBuf.write(inputs.data(), n * sizeof(EvalInput));

    const vk::StorageCompute compute = vk::createStorageCompute(
        *ctx, "hair/shade_eval.comp", {{&paramBuf}, {&inBuf}, {&outBuf}}, sizeof(uint32_t));
    const uint32_t count = uint32_t(n);
    vk::runStorageCompute(*ctx, compute, [&](VkCommandBuffer cmd) {
        vkCmdPushConstants(cmd, compute.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(count),
                           &count);
        vkCmdDispatch(cmd, (count + kGroupSize - 1) / kGroupSize, 1, 1);
    });

    std::vector<glm::vec3> out(n);
    const glm::vec4* result = static_cast<const glm::vec4*>(outBuf.mapped());
    for (size_t i = 0; i < n; ++i) out[i] = glm::vec3(result[i]);
    return out;
}

} // namespace weft
