// CubeMap: face convention, texel solid angles, mip chain and seamless sampling.
#include <weft/CubeMap.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <weft/Error.h>

namespace weft {

namespace {

// Integral of the solid angle over [0, x] x [0, y] of a face at distance 1 (signed).
double areaElement(double x, double y) { return std::atan2(x * y, std::sqrt(x * x + y * y + 1.0)); }

int faceIndexFromCoord(float c, int size) {
    return std::clamp(int(std::floor((c + 1.0f) * 0.5f * float(size))), 0, size - 1);
}

} // namespace

CubeCoord cubeCoord(const glm::vec3& d) {
    const float ax = std::fabs(d.x), ay = std::fabs(d.y), az = std::fabs(d.z);
    if (!(std::isfinite(ax) && std::isfinite(ay) && std::isfinite(az)) || ax + ay + az == 0.0f)
        throw InvalidArgument("cube map direction must be finite and non-zero");
    CubeCoord c;
    float sc, tc, ma;
    if (ax >= ay && ax >= az) {
        c.face = d.x > 0.0f ? 0 : 1;
        sc = d.x > 0.0f ? -d.z : d.z;
        tc = -d.y;
        ma = ax;
    } else if (ay >= az) {
        c.face = d.y > 0.0f ? 2 : 3;
        sc = d.x;
        tc = d.y > 0.0f ? d.z : -d.z;
        ma = ay;
    } else {
        c.face = d.z > 0.0f ? 4 : 5;
        sc = d.z > 0.0f ? d.x : -d.x;
        tc = -d.y;
        ma = az;
    }
    c.u = std::clamp(sc / ma, -1.0f, 1.0f);
    c.v = std::clamp(tc / ma, -1.0f, 1.0f);
    return c;
}

glm::vec3 cubeDirection(int face, float u, float v) {
    glm::vec3 d;
    switch (face) {
    case 0: d = {1.0f, -v, -u}; break;
    case 1: d = {-1.0f, -v, u}; break;
    case 2: d = {u, 1.0f, v}; break;
    case 3: d = {u, -1.0f, -v}; break;
    case 4: d = {u, -v, 1.0f}; break;
    case 5: d = {-u, -v, -1.0f}; break;
    default:
        throw InvalidArgument("cube face index must be in [0, 5], got " + std::to_string(face));
    }
    return glm::normalize(d);
}

glm::vec3 cubeTexelDirection(int face, int i, int j, int size) {
    const float u = 2.0f * (float(i) + 0.5f) / float(size) - 1.0f;
    const float v = 2.0f * (float(j) + 0.5f) / float(size) - 1.0f;
    return cubeDirection(face, u, v);
}

int cubeTexelIndexWrapped(int face, int i, int j, int size) {
    if (i < 0 || i >= size || j < 0 || j >= size) {
        // Step just across the edge at the same position along it: the neighbouring face's edge
        // texels line up with this face's, so that is the texel next to (i, j).
        auto across = [size](int k) {
            const float eps = 1e-3f / float(size);
            if (k < 0) return -1.0f - eps;
            if (k >= size) return 1.0f + eps;
            return 2.0f * (float(k) + 0.5f) / float(size) - 1.0f;
        };
        const CubeCoord c = cubeCoord(cubeDirection(face, across(i), across(j)));
        face = c.face;
        i = faceIndexFromCoord(c.u, size);
        j = faceIndexFromCoord(c.v, size);
    }
    return (face * size + j) * size + i;
}

double cubeTexelSolidAngle(int i, int j, int size) {
    const double x0 = 2.0 * i / size - 1.0, x1 = 2.0 * (i + 1) / size - 1.0;
    const double y0 = 2.0 * j / size - 1.0, y1 = 2.0 * (j + 1) / size - 1.0;
    return areaElement(x0, y0) - areaElement(x0, y1) - areaElement(x1, y0) + areaElement(x1, y1);
}

CubeMap::CubeMap(int size) {
    if (size < 1 || size > 8192)
        throw InvalidArgument("cube map size must be in [1, 8192], got " + std::to_string(size));
    mSize = size;
    mLevels.assign(1, std::vector<float>(size_t(6) * size * size * 3, 0.0f));
}

int CubeMap::levelSize(int level) const { return std::max(1, mSize >> level); }

float* CubeMap::texel(int face, int i, int j, int level) {
    const int s = levelSize(level);
    return mLevels[size_t(level)].data() + ((size_t(face) * s + j) * s + i) * 3;
}

const float* CubeMap::texel(int face, int i, int j, int level) const {
    const int s = levelSize(level);
    return mLevels[size_t(level)].data() + ((size_t(face) * s + j) * s + i) * 3;
}

void CubeMap::keepLevels(int count) {
    mLevels.resize(std::min(mLevels.size(), size_t(std::max(count, 1))));
}

void CubeMap::buildMips() {
    clearMips();
    for (int level = 1; levelSize(level - 1) > 1; ++level) {
        const int fine = levelSize(level - 1), s = levelSize(level);
        mLevels.emplace_back(size_t(6) * s * s * 3, 0.0f);
        std::vector<double> weight(size_t(fine) * fine);
        for (int j = 0; j < fine; ++j)
            for (int i = 0; i < fine; ++i)
                weight[size_t(j) * fine + i] = cubeTexelSolidAngle(i, j, fine);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < s; ++j)
                for (int i = 0; i < s; ++i) {
                    // coarse texel (i, j) covers fine texels [i * fine / s, (i + 1) * fine / s)
                    double acc[3] = {0, 0, 0}, wsum = 0.0;
                    for (int fj = j * fine / s; fj < (j + 1) * fine / s; ++fj)
                        for (int fi = i * fine / s; fi < (i + 1) * fine / s; ++fi) {
                            const double w = weight[size_t(fj) * fine + fi];
                            const float* c = texel(f, fi, fj, level - 1);
                            for (int k = 0; k < 3; ++k) acc[k] += w * c[k];
                            wsum += w;
                        }
                    float* out = texel(f, i, j, level);
                    for (int k = 0; k < 3; ++k) out[k] = float(acc[k] / wsum);
                }
    }
}

const float* CubeMap::texelWrapped(int face, int i, int j, int level) const {
    const int s = levelSize(level);
    if (i >= 0 && i < s && j >= 0 && j < s) return texel(face, i, j, level);
    return data(level) + size_t(cubeTexelIndexWrapped(face, i, j, s)) * 3;
}

glm::vec3 CubeMap::sample(const glm::vec3& dir, int level) const {
    const CubeCoord c = cubeCoord(dir);
    const int s = levelSize(level);
    const float x = (c.u + 1.0f) * 0.5f * float(s) - 0.5f;
    const float y = (c.v + 1.0f) * 0.5f * float(s) - 0.5f;
    const int i0 = int(std::floor(x)), j0 = int(std::floor(y));
    const float fx = x - float(i0), fy = y - float(j0);
    // A tap off both edges (past a corner, where only three faces meet) is the mean of the
    // corner texel and its two neighbours across the edges, the same from all three faces.
    auto tap = [&](int i, int j) {
        const float* t = texelWrapped(c.face, i, j, level);
        glm::vec3 v(t[0], t[1], t[2]);
        const int ci = std::clamp(i, 0, s - 1), cj = std::clamp(j, 0, s - 1);
        if (ci != i && cj != j) {
            const float* a = texel(c.face, ci, cj, level);
            const float* b = texelWrapped(c.face, i, cj, level);
            const float* d = texelWrapped(c.face, ci, j, level);
            for (int k = 0; k < 3; ++k) v[k] = (a[k] + b[k] + d[k]) / 3.0f;
        }
        return v;
    };
    const glm::vec3 top = glm::mix(tap(i0, j0), tap(i0 + 1, j0), fx);
    const glm::vec3 bottom = glm::mix(tap(i0, j0 + 1), tap(i0 + 1, j0 + 1), fx);
    const glm::vec3 out = glm::mix(top, bottom, fy);
    return out;
}

glm::vec3 CubeMap::sampleLod(const glm::vec3& dir, float lod) const {
    lod = std::clamp(std::isfinite(lod) ? lod : 0.0f, 0.0f, float(levels() - 1));
    const int l0 = int(std::floor(lod));
    const float f = lod - float(l0);
    const glm::vec3 a = sample(dir, l0);
    if (f <= 0.0f || l0 + 1 >= levels()) return a;
    return a + f * (sample(dir, l0 + 1) - a);
}

void CubeMap::requireFinite(const char* what, bool nonNegative) const {
    for (const auto& level : mLevels)
        for (float v : level) {
            if (!std::isfinite(v)) throw InvalidArgument(std::string(what) + " must be finite");
            if (nonNegative && v < 0.0f) throw InvalidArgument(std::string(what) + " must be >= 0");
        }
}

} // namespace weft
