#include "render/ReflectionProbe.h"

#include "render/RenderTargets.h"

namespace weft::render {

glm::mat4 probeFaceViewProj(int face, const glm::vec3& position, float zNear, float zFar) {
    // (major axis, u axis, v axis) per face: a direction ma + u su + v sv hits texel (u, v).
    static const glm::vec3 axes[6][3] = {
        {{1, 0, 0}, {0, 0, -1}, {0, -1, 0}}, {{-1, 0, 0}, {0, 0, 1}, {0, -1, 0}},
        {{0, 1, 0}, {1, 0, 0}, {0, 0, 1}},   {{0, -1, 0}, {1, 0, 0}, {0, 0, -1}},
        {{0, 0, 1}, {1, 0, 0}, {0, -1, 0}},  {{0, 0, -1}, {-1, 0, 0}, {0, -1, 0}}};
    const glm::vec3 &ma = axes[face][0], &su = axes[face][1], &sv = axes[face][2];
    // clip = (r.su, r.sv, a (r.ma) + b, r.ma) with r = q - position: NDC x = u, y = v, and
    // depth a + b / w running from 0 at zNear to 1 at zFar.
    const float a = zFar / (zFar - zNear), b = -zFar * zNear / (zFar - zNear);
    glm::mat4 m(0.0f); // column-major: m[column][row]
    for (int k = 0; k < 3; ++k) {
        m[k][0] = su[k];
        m[k][1] = sv[k];
        m[k][2] = a * ma[k];
        m[k][3] = ma[k];
    }
    m[3][0] = -glm::dot(su, position);
    m[3][1] = -glm::dot(sv, position);
    m[3][2] = -a * glm::dot(ma, position) + b;
    m[3][3] = -glm::dot(ma, position);
    return m;
}

std::vector<uint64_t> captureKey(const Scene& scene, const FrameData& data) {
    std::vector<uint64_t> key = {uint64_t(reinterpret_cast<uintptr_t>(&scene)), scene.version()};
    for (const Draw& d : data.draws) key.push_back(d.mesh->contentId);
    const EnvironmentLighting& env = scene.environment();
    key.push_back(env.environment ? env.environment->version() : 0);
    return key;
}

// The depth attachment the probe's faces are drawn with, one face at a time: size x size.
static vk::Image captureDepth(vk::Context& ctx, uint32_t size) {
    vk::ImageDesc z;
    z.width = z.height = size;
    z.format = kDepthFormat;
    z.usage = VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    return vk::Image(&ctx, z);
}

bool ReflectionProbe::prepare(const Scene& scene, const FrameData& data, uint32_t size) {
    mInstance = -1;
    for (size_t i = 0; i < scene.instances().size(); ++i)
        if (scene.instances()[i].material.dynamicReflection) {
            mInstance = int(i);
            break;
        }
    if (mInstance < 0) {
        mCube = vk::Image();
        mDepth = vk::Image();
        mKey.clear();
        return false;
    }
    mPosition = glm::vec3(scene.instances()[size_t(mInstance)].transform[3]);
    std::vector<uint64_t> key = captureKey(scene, data);
    key.push_back(uint64_t(mInstance));
    key.push_back(size);
    if (!mCube || mCube.desc().width != size) {
        vk::ImageDesc d;
        d.width = d.height = size;
        d.layers = 6;
        d.cube = true;
        d.format = kHdrFormat; // the forward pipelines draw into it as they draw the frame
        d.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                  VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
        mCube = vk::Image(&mCtx, d);
        mDepth = captureDepth(mCtx, size);
        mKey.clear();
    }
    if (key == mKey) return false;
    mKey = std::move(key);
    return true;
}

} // namespace weft::render
