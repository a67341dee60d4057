// Signed distances of the collider shapes (SPEC §2.2), used to project particles out of them.
#include <algorithm>
#include <cmath>
#include <string>

#include <weft/Cloth.h>

#include "core/Validate.h"

namespace weft {

void Collider::validate() const {
    requireFinite(center, "collider center");
    requireFinite(friction, "collider friction");
    if (friction < 0.0f || friction > 1.0f)
        throw InvalidArgument("collider friction must be in [0, 1]");
    switch (kind) {
    case Kind::Sphere: requirePositive(radius, "sphere radius"); break;
    case Kind::Plane:
        requireFinite(normal, "plane normal");
        if (glm::length(normal) < 1e-6f) throw InvalidArgument("plane normal must not be zero");
        break;
    case Kind::Box:
        requireFinite(halfExtents, "box half_extents");
        if (halfExtents.x <= 0 || halfExtents.y <= 0 || halfExtents.z <= 0)
            throw InvalidArgument("box half_extents must be positive");
        for (int c = 0; c < 3; ++c) requireFinite(rotation[c], "box rotation");
        {
            const glm::mat3 e = glm::transpose(rotation) * rotation - glm::mat3(1.0f);
            float worst = 0.0f;
            for (int c = 0; c < 3; ++c)
                for (int r = 0; r < 3; ++r) worst = std::max(worst, std::abs(e[c][r]));
            if (worst > 1e-3f || glm::determinant(rotation) < 0.0f)
                throw InvalidArgument(
                    "box rotation must be a rotation matrix (orthonormal, det +1)");
        }
        break;
    case Kind::Capsule:
        requireFinite(end, "capsule end");
        requirePositive(radius, "capsule radius");
        break;
    case Kind::HeightField:
        requireFinite(origin, "height field origin");
        requirePositive(size.x, "height field size_x");
        requirePositive(size.y, "height field size_z");
        if (rows < 2 || cols < 2 || heights.size() != size_t(rows) * size_t(cols))
            throw InvalidArgument("height field needs rows, cols >= 2 and rows * cols heights");
        for (float h : heights) requireFinite(h, "height field height");
        break;
    }
}

namespace {

float heightAt(const Collider& c, float x, float z, glm::vec3& normal) {
    // Bilinear surface over the grid, clamped at the borders.
    const float gx = std::clamp((x - c.origin.x) / c.size.x, 0.0f, 1.0f) * float(c.cols - 1);
    const float gz = std::clamp((z - c.origin.z) / c.size.y, 0.0f, 1.0f) * float(c.rows - 1);
    const int x0 = std::min(int(gx), c.cols - 2), z0 = std::min(int(gz), c.rows - 2);
    const float fx = gx - float(x0), fz = gz - float(z0);
    auto h = [&](int i, int j) { return c.heights[size_t(j) * size_t(c.cols) + size_t(i)]; };
    const float h00 = h(x0, z0), h10 = h(x0 + 1, z0), h01 = h(x0, z0 + 1), h11 = h(x0 + 1, z0 + 1);
    const float height = (1 - fz) * ((1 - fx) * h00 + fx * h10) + fz * ((1 - fx) * h01 + fx * h11);
    const float dhdx = ((1 - fz) * (h10 - h00) + fz * (h11 - h01)) * float(c.cols - 1) / c.size.x;
    const float dhdz = ((1 - fx) * (h01 - h00) + fx * (h11 - h10)) * float(c.rows - 1) / c.size.y;
    normal = glm::normalize(glm::vec3(-dhdx, 1.0f, -dhdz));
    return c.origin.y + height;
}

} // namespace

float Collider::distance(const glm::vec3& p, glm::vec3& n) const {
    switch (kind) {
    case Kind::Sphere: {
        const glm::vec3 d = p - center;
        const float len = glm::length(d);
        n = len > 1e-12f ? d / len : glm::vec3(0, 1, 0);
        return len - radius;
    }
    case Kind::Plane: n = glm::normalize(normal); return glm::dot(p - center, n);
    case Kind::Box: {
        const glm::vec3 local = glm::transpose(rotation) * (p - center);
        const glm::vec3 q = glm::abs(local) - halfExtents;
        const float outside = glm::length(glm::max(q, glm::vec3(0.0f)));
        const float inside = std::min(std::max(q.x, std::max(q.y, q.z)), 0.0f);
        glm::vec3 ln;
        if (outside > 0.0f) {
            ln = glm::max(q, glm::vec3(0.0f)) * glm::sign(local) / outside;
        } else { // nearest face
            const int axis = q.x > q.y ? (q.x > q.z ? 0 : 2) : (q.y > q.z ? 1 : 2);
            ln = glm::vec3(0.0f);
            ln[axis] = local[axis] >= 0.0f ? 1.0f : -1.0f;
        }
        n = rotation * ln;
        return outside + inside;
    }
    case Kind::Capsule: {
        const glm::vec3 ab = end - center;
        const float len2 = glm::dot(ab, ab);
        const float t = len2 > 0 ? std::clamp(glm::dot(p - center, ab) / len2, 0.0f, 1.0f) : 0.0f;
        const glm::vec3 d = p - (center + t * ab);
        const float len = glm::length(d);
        n = len > 1e-12f ? d / len : glm::vec3(0, 1, 0);
        return len - radius;
    }
    case Kind::HeightField: {
        // Vertical distance scaled by the slope: a first-order distance to the surface.
        glm::vec3 surfaceNormal;
        const float h = heightAt(*this, p.x, p.z, surfaceNormal);
        n = surfaceNormal;
        return (p.y - h) * surfaceNormal.y;
    }
    }
    n = glm::vec3(0, 1, 0);
    return 1e30f;
}

} // namespace weft
