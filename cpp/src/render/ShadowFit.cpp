#include "render/ShadowFit.h"

#include <algorithm>
#include <cmath>

#include <glm/gtc/constants.hpp>
#include <glm/gtc/matrix_transform.hpp>

namespace weft::render {

ShadowFrustum fitDirectionalShadow(const glm::vec3& toLight, const glm::vec3& lo,
                                   const glm::vec3& hi, unsigned size) {
    const glm::vec3 center = 0.5f * (lo + hi);
    const float radius = std::max(0.5f * glm::length(hi - lo), 1e-3f);
    const glm::vec3 l = glm::normalize(toLight);
    const glm::vec3 up = std::abs(l.y) > 0.99f ? glm::vec3(0, 0, 1) : glm::vec3(0, 1, 0);
    const glm::mat4 view = glm::lookAtRH(center + l * (2.0f * radius), center, up);

    glm::vec3 mn(1e30f), mx(-1e30f);
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
        const glm::vec3 p = glm::vec3(view * glm::vec4(corner, 1.0f));
        mn = glm::min(mn, p);
        mx = glm::max(mx, p);
    }
    // A margin keeps geometry on the boundary inside the map and off the far plane.
    const float pad = 0.01f * std::max({mx.x - mn.x, mx.y - mn.y, 1e-3f});
    mn -= glm::vec3(pad);
    mx += glm::vec3(pad);
    const glm::mat4 proj = glm::orthoRH_ZO(mn.x, mx.x, mn.y, mx.y, -mx.z, -mn.z);
    ShadowFrustum f;
    f.viewProj = vulkanClipFlip() * proj * view;
    f.texelWorld = std::max(mx.x - mn.x, mx.y - mn.y) / float(size);
    return f;
}

ShadowFrustum fitPerspectiveShadow(const glm::vec3& position, const glm::vec3& axis,
                                   const glm::vec3& up, float fovY, float zNear,
                                   const glm::vec3& lo, const glm::vec3& hi, unsigned size) {
    float farthest = 0.0f;
    for (int i = 0; i < 8; ++i) {
        const glm::vec3 corner((i & 1) ? hi.x : lo.x, (i & 2) ? hi.y : lo.y, (i & 4) ? hi.z : lo.z);
        farthest = std::max(farthest, glm::length(corner - position));
    }
    ShadowFrustum f;
    f.perspective = true;
    f.zNear = zNear;
    f.zFar = std::max(farthest * 1.01f, zNear * 2.0f);
    const glm::mat4 view = glm::lookAtRH(position, position + glm::normalize(axis), up);
    f.viewProj = vulkanClipFlip() * glm::perspectiveRH_ZO(fovY, 1.0f, f.zNear, f.zFar) * view;
    f.texelWorld = 2.0f * std::tan(0.5f * fovY) / float(size);
    return f;
}

void pointShadowFaces(const glm::vec3& position, float zNear, const glm::vec3& lo,
                      const glm::vec3& hi, unsigned size, ShadowFrustum faces[6]) {
    static const glm::vec3 axes[6] = {{1, 0, 0},  {-1, 0, 0}, {0, 1, 0},
                                      {0, -1, 0}, {0, 0, 1},  {0, 0, -1}};
    static const glm::vec3 ups[6] = {{0, 1, 0}, {0, 1, 0}, {0, 0, -1},
                                     {0, 0, 1}, {0, 1, 0}, {0, 1, 0}};
    for (int i = 0; i < 6; ++i)
        faces[i] = fitPerspectiveShadow(position, axes[i], ups[i], glm::half_pi<float>(), zNear, lo,
                                        hi, size);
}

} // namespace weft::render
