// Irradiance: exact cosine convolution, SH9 (Ramamoorthi & Hanrahan 2001) and the seed's blurs.
#include <weft/IblConvert.h>
#include <weft/IblFilter.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <memory>
#include <mutex>

#include <weft/Error.h>

#include "CubeTexels.h"
#include "IblParallel.h"
#include "IblValidate.h"

namespace weft {

namespace {

constexpr float kPi = 3.14159265358979f;

// Per-texel basis x solid angle, 9 floats per texel, cached per face size.
std::shared_ptr<const std::vector<float>> shTable(int s) {
    static std::mutex mutex;
    static std::map<int, std::shared_ptr<const std::vector<float>>> cache;
    std::lock_guard<std::mutex> lock(mutex);
    auto it = cache.find(s);
    if (it != cache.end()) return it->second;
    auto table = std::make_shared<std::vector<float>>(size_t(6) * s * s * 9);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) {
                const auto y = sh9Basis(cubeTexelDirection(f, i, j, s));
                const float w = float(cubeTexelSolidAngle(i, j, s));
                float* out = table->data() + ((size_t(f) * s + j) * s + i) * 9;
                for (int k = 0; k < 9; ++k) out[k] = y[size_t(k)] * w;
            }
    if (cache.size() > 8) cache.clear();
    cache[s] = table;
    return table;
}

CubeMap scaled(CubeMap cube, float factor) {
    for (size_t k = 0; k < cube.floatCount(); ++k) cube.data()[k] *= factor;
    return cube;
}

template <class Fn> CubeMap mapTexels(int size, Fn fn) {
    CubeMap out(size);
    iblParallelFor(6 * size, [&](int begin, int end) {
        for (int row = begin; row < end; ++row) {
            const int f = row / size, j = row % size;
            for (int i = 0; i < size; ++i) {
                const glm::vec3 c = fn(cubeTexelDirection(f, i, j, size));
                float* p = out.texel(f, i, j);
                p[0] = c.x;
                p[1] = c.y;
                p[2] = c.z;
            }
        }
    });
    return out;
}

glm::mat3 axisRotation(int axis, float angle) {
    const float c = std::cos(angle), s = std::sin(angle);
    glm::mat3 r(1.0f); // column-major: r[col][row]
    const int a = (axis + 1) % 3, b = (axis + 2) % 3;
    r[a][a] = c;
    r[a][b] = s;
    r[b][a] = -s;
    r[b][b] = c;
    return r;
}

} // namespace

std::array<float, 9> sh9Basis(const glm::vec3& d) {
    return {0.282095f,
            0.488603f * d.y,
            0.488603f * d.z,
            0.488603f * d.x,
            1.092548f * d.x * d.y,
            1.092548f * d.y * d.z,
            0.315392f * (3.0f * d.z * d.z - 1.0f),
            1.092548f * d.x * d.z,
            0.546274f * (d.x * d.x - d.y * d.y)};
}

Sh9 projectSh9(const CubeMap& radiance) {
    if (radiance.empty()) throw InvalidArgument("radiance cube map is empty");
    const int s = radiance.size();
    const auto table = shTable(s);
    const int rows = 6 * s;
    std::vector<double> partial(size_t(rows) * 27, 0.0);
    iblParallelFor(rows, [&](int begin, int end) {
        for (int row = begin; row < end; ++row) {
            const float* w = table->data() + size_t(row) * s * 9;
            const float* c = radiance.data() + size_t(row) * s * 3;
            float acc[27] = {};
            for (int i = 0; i < s; ++i, w += 9, c += 3)
                for (int k = 0; k < 9; ++k) {
                    acc[k] += w[k] * c[0];
                    acc[9 + k] += w[k] * c[1];
                    acc[18 + k] += w[k] * c[2];
                }
            for (int k = 0; k < 27; ++k) partial[size_t(row) * 27 + k] = acc[k];
        }
    });
    double total[27] = {};
    for (int row = 0; row < rows; ++row)
        for (int k = 0; k < 27; ++k) total[k] += partial[size_t(row) * 27 + k];
    for (double v : total)
        if (!std::isfinite(v)) requireCube(radiance, "radiance cube map"); // names the problem
    Sh9 sh;
    for (int k = 0; k < 9; ++k)
        sh.coeffs[size_t(k)] =
            glm::vec3(float(total[k]), float(total[9 + k]), float(total[18 + k]));
    return sh;
}

glm::vec3 shIrradiance(const Sh9& sh, const glm::vec3& n) {
    static const float band[9] = {kPi,     2 * kPi / 3, 2 * kPi / 3, 2 * kPi / 3, kPi / 4,
                                  kPi / 4, kPi / 4,     kPi / 4,     kPi / 4};
    const auto y = sh9Basis(glm::normalize(n));
    glm::vec3 e(0.0f);
    for (int k = 0; k < 9; ++k) e += band[k] * y[size_t(k)] * sh.coeffs[size_t(k)];
    return glm::max(e, glm::vec3(0.0f));
}

CubeMap irradianceFromSh(const Sh9& sh, int size) {
    for (const auto& c : sh.coeffs)
        if (!std::isfinite(c.x + c.y + c.z))
            throw InvalidArgument("SH coefficients must be finite");
    return mapTexels(size, [&](const glm::vec3& d) { return shIrradiance(sh, d); });
}

CubeMap irradianceExact(const CubeMap& radiance, int size, int sourceSize) {
    requireExactIrradianceArguments(radiance, size, sourceSize);
    const CubeTexels t = cubeTexels(reducedCube(radiance, sourceSize));
    const size_t n = t.size();
    return mapTexels(size, [&](const glm::vec3& d) {
        float r = 0.0f, g = 0.0f, b = 0.0f;
        for (size_t k = 0; k < n; ++k) {
            const float c = std::max(0.0f, d.x * t.x[k] + d.y * t.y[k] + d.z * t.z[k]);
            r += c * t.r[k];
            g += c * t.g[k];
            b += c * t.b[k];
        }
        return glm::vec3(r, g, b);
    });
}

CubeMap irradianceBoxBlur(const CubeMap& radiance, int size, int sphereSize, int radius,
                          int passes) {
    requireCube(radiance, "radiance cube map");
    requireCount(size, 1024, "output size");
    requireCount(sphereSize, 4096, "sphere map size");
    if (radius < 0 || radius >= sphereSize)
        throw InvalidArgument("blur radius must be in [0, sphere size)");
    if (passes < 0 || passes > 16) throw InvalidArgument("blur passes must be in [0, 16]");
    requireAffordable(6.0 * passes * (2 * radius + 1) * sphereSize * sphereSize, "box blur");
    const glm::mat4 identity(1.0f);
    std::vector<float> img = cubeToSphere(radiance, sphereSize, identity, 1.0f);
    std::vector<float> tmp(img.size());
    const int s = sphereSize;
    const float norm = 1.0f / float(2 * radius + 1);
    for (int pass = 0; pass < passes; ++pass)
        for (int dir = 0; dir < 2; ++dir) { // horizontal, then vertical; edges clamp
            for (int y = 0; y < s; ++y)
                for (int x = 0; x < s; ++x)
                    for (int k = 0; k < 3; ++k) {
                        float acc = 0.0f;
                        for (int o = -radius; o <= radius; ++o) {
                            const int xx = dir == 0 ? std::clamp(x + o, 0, s - 1) : x;
                            const int yy = dir == 1 ? std::clamp(y + o, 0, s - 1) : y;
                            acc += img[(size_t(yy) * s + xx) * 3 + k];
                        }
                        tmp[(size_t(y) * s + x) * 3 + k] = acc * norm;
                    }
            img.swap(tmp);
        }
    const CaptureCube cube = sphereToCube(RgbView{img.data(), s, s}, identity, 1.0f, size, 2);
    return scaled(cube.cube, kPi);
}

CubeMap irradianceRotationalBlur(const CubeMap& radiance, int size, float halfAngle, int steps) {
    requireCube(radiance, "radiance cube map");
    requireCount(size, 1024, "output size");
    requireCount(steps, 1024, "rotation steps");
    requireAffordable(18.0 * size * size * steps, "rotational blur");
    if (!(halfAngle >= 0.0f && halfAngle <= kPi))
        throw InvalidArgument("half angle must be in [0, pi]");
    CubeMap current = reducedCube(radiance, size);
    for (int axis : {0, 2, 1}) {
        std::vector<glm::mat3> rotations;
        for (int k = 0; k < steps; ++k) {
            const float t = steps == 1 ? 0.5f : float(k) / float(steps - 1);
            const float a = halfAngle * (2.0f * t - 1.0f);
            rotations.push_back(axisRotation(axis, a));
        }
        current = mapTexels(size, [&](const glm::vec3& d) {
            glm::vec3 acc(0.0f);
            for (const auto& r : rotations) acc += current.sample(r * d);
            return acc / float(steps);
        });
    }
    return scaled(std::move(current), kPi);
}

} // namespace weft
