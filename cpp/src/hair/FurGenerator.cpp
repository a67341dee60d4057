// Fur grown from a triangle mesh: 002 listing 1 on the CPU, with per-strand length and
// direction jitter, texture colour and density control.
#include <weft/HairGenerator.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/gtc/constants.hpp>

#include <weft/Error.h>

#include "core/Srgb.h"
#include "core/ThreadPool.h"
#include "hair/HairRandom.h"

namespace weft {

namespace {

// Bilinear, repeat, texel centres at (i + 0.5) / size, v = 0 at the top row; linear RGB.
glm::vec3 sampleTexture(const ImageU8& img, glm::vec2 uv) {
    const float x = uv.x * float(img.width) - 0.5f, y = uv.y * float(img.height) - 0.5f;
    const float fx = std::floor(x), fy = std::floor(y);
    const float tx = x - fx, ty = y - fy;
    glm::vec3 out(0.0f);
    for (int dy = 0; dy < 2; ++dy)
        for (int dx = 0; dx < 2; ++dx) {
            int ix = (int(fx) + dx) % img.width, iy = (int(fy) + dy) % img.height;
            if (ix < 0) ix += img.width;
            if (iy < 0) iy += img.height;
            const uint8_t* p = img.at(ix, iy);
            glm::vec3 c;
            for (int k = 0; k < 3; ++k)
                c[k] = srgbToLinear(float(p[img.channels >= 3 ? k : 0]) / 255.0f);
            out += c * ((dx ? tx : 1.0f - tx) * (dy ? ty : 1.0f - ty));
        }
    return out;
}

// Calls grow(local, b) for the level^2 sub-triangles of a triangle, b = barycentric weights of
// vertices 1 and 2 at the sub-triangle's centroid: first the level(level+1)/2 upright ones row
// by row, then the level(level-1)/2 inverted ones.
template <typename Grow> void forEachSubTriangle(int level, Grow&& grow) {
    int local = 0;
    for (int inverted = 0; inverted < 2; ++inverted) {
        const float third = inverted ? 2.0f / 3.0f : 1.0f / 3.0f;
        const int rows = level - inverted;
        for (int j = 0; j < rows; ++j)
            for (int i = 0; i < rows - j; ++i)
                grow(local++, glm::vec2(float(i) + third, float(j) + third) / float(level));
    }
}

} // namespace

void FurParams::validate() const {
    if (level < 1 || level > 1024) throw InvalidArgument("fur: level must be in [1, 1024]");
    if (!(std::isfinite(density) && density >= 0.0f))
        throw InvalidArgument("fur: density must be finite and >= 0");
    if (segments < 1 || segments > 65535)
        throw InvalidArgument("fur: segments must be in [1, 65535]");
    if (!(std::isfinite(length) && length > 0.0f)) throw InvalidArgument("fur: length must be > 0");
    if (!(lengthJitter >= 0.0f && lengthJitter < 1.0f))
        throw InvalidArgument("fur: length jitter must be in [0, 1)");
    if (!(directionJitter >= 0.0f && directionJitter <= glm::pi<float>()))
        throw InvalidArgument("fur: direction jitter must be in [0, pi]");
    for (int i = 0; i < 3; ++i)
        if (!std::isfinite(down[i])) throw InvalidArgument("fur: down must be finite");
}

HairStrands generateFur(const Mesh& mesh, const FurParams& params, const ImageU8* texture) {
    mesh.validate();
    params.validate();
    if (texture &&
        (texture->width < 1 || texture->height < 1 || texture->channels < 1 ||
         texture->pixels.size() != size_t(texture->width) * texture->height * texture->channels))
        throw InvalidArgument("fur: invalid colour texture");
    const size_t triangles = mesh.triangleCount();
    std::vector<uint64_t> first(triangles + 1, 0);
    std::vector<int> levels(triangles, params.level);
    for (size_t t = 0; t < triangles; ++t) {
        if (params.density > 0.0f) {
            const glm::vec3& a = mesh.positions[mesh.indices[3 * t]];
            const glm::vec3& b = mesh.positions[mesh.indices[3 * t + 1]];
            const glm::vec3& c = mesh.positions[mesh.indices[3 * t + 2]];
            const double area = 0.5 * double(glm::length(glm::cross(b - a, c - a)));
            levels[t] =
                int(std::clamp(std::lround(std::sqrt(area * double(params.density))), 1l, 1024l));
        }
        first[t + 1] = first[t] + uint64_t(levels[t]) * uint64_t(levels[t]);
    }
    const uint64_t strands = first[triangles], perStrand = uint64_t(params.segments) + 1;
    if (strands * perStrand > UINT32_MAX)
        throw InvalidArgument("fur: " + std::to_string(strands * perStrand) +
                              " points, more than a .hair file holds (2^32 - 1)");

    HairStrands h;
    h.defaultSegments = uint32_t(params.segments);
    h.info = "weft generated fur";
    h.points.resize(size_t(strands * perStrand));
    if (texture) h.colors.resize(h.points.size());
    const float segmentLength = params.length / float(params.segments);

    PoolShare(params.threads)
        .parallelFor(
            int(triangles),
            [&](int begin, int end) {
                for (int t = begin; t < end; ++t) {
                    const uint32_t i0 = mesh.indices[3 * size_t(t)],
                                   i1 = mesh.indices[3 * size_t(t) + 1],
                                   i2 = mesh.indices[3 * size_t(t) + 2];
                    const glm::vec3 face = glm::cross(mesh.positions[i1] - mesh.positions[i0],
                                                      mesh.positions[i2] - mesh.positions[i0]);
                    const int level = levels[size_t(t)];
                    forEachSubTriangle(level, [&](int local, const glm::vec2& b) {
                        const uint64_t strand = first[size_t(t)] + uint64_t(local);
                        const uint32_t id = uint32_t(strand);
                        const float b0 = 1.0f - b.x - b.y;
                        const glm::vec3 root = b0 * mesh.positions[i0] + b.x * mesh.positions[i1] +
                                               b.y * mesh.positions[i2];
                        glm::vec3 n =
                            b0 * mesh.normals[i0] + b.x * mesh.normals[i1] + b.y * mesh.normals[i2];
                        if (glm::dot(n, n) < 1e-12f) n = face;
                        n = glm::dot(n, n) < 1e-30f ? glm::vec3(0.0f, 1.0f, 0.0f)
                                                    : glm::normalize(n);
                        glm::vec3 dir = n;
                        if (params.directionJitter > 0.0f) {
                            glm::vec3 e1, e2;
                            hair::orthonormalBasis(n, e1, e2);
                            const float tilt =
                                params.directionJitter * hair::random01(params.seed, id, 0);
                            const float spin =
                                glm::two_pi<float>() * hair::random01(params.seed, id, 1);
                            dir = std::cos(tilt) * n +
                                  std::sin(tilt) * (std::cos(spin) * e1 + std::sin(spin) * e2);
                        }
                        const float len =
                            segmentLength *
                            (1.0f + params.lengthJitter *
                                        (2.0f * hair::random01(params.seed, id, 2) - 1.0f));
                        glm::vec3* out = h.points.data() + strand * perStrand;
                        out[0] = root;
                        for (int k = 0; k < params.segments; ++k) { // 002 listing 1, lines 25-34
                            out[k + 1] = out[k] + dir * len;
                            dir += params.down * len;
                        }
                        if (texture) {
                            const glm::vec2 uv =
                                b0 * mesh.uvs[i0] + b.x * mesh.uvs[i1] + b.y * mesh.uvs[i2];
                            std::fill_n(h.colors.data() + strand * perStrand, perStrand,
                                        sampleTexture(*texture, uv));
                        }
                    });
                }
            },
            16);
    return h;
}

} // namespace weft
