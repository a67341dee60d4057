// Light extraction: max-filter downsample, threshold, connected components across face edges.
#include <weft/IblLights.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include <weft/Error.h>

#include "IblValidate.h"

namespace weft {

namespace {

int findRoot(std::vector<int>& parent, int x) {
    while (parent[size_t(x)] != x) {
        parent[size_t(x)] = parent[size_t(parent[size_t(x)])];
        x = parent[size_t(x)];
    }
    return x;
}

} // namespace

std::vector<EnvLight> extractLights(const CubeMap& radiance, const LightExtractionParams& p,
                                    std::vector<int>* labels) {
    requireCube(radiance, "radiance cube map");
    requireCount(p.downsample, 1024, "downsample size");
    requireCount(p.maxLights, 1 << 16, "maximum light count");
    if (!std::isfinite(p.threshold) || !(p.relativeThreshold > 0.0f) ||
        !std::isfinite(p.relativeThreshold))
        throw InvalidArgument("light thresholds must be finite, relative threshold > 0");
    const int s = radiance.size(), d = std::min(p.downsample, s);
    const size_t n = size_t(6) * s * s, nd = size_t(6) * d * d;
    std::vector<float> lum(n), omega(n);
    double total = 0.0;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) {
                const size_t k = (size_t(f) * s + j) * s + i;
                const float* c = radiance.texel(f, i, j);
                lum[k] = luminance({c[0], c[1], c[2]});
                omega[k] = float(cubeTexelSolidAngle(i, j, s));
                total += double(lum[k]) * omega[k];
            }
    const float threshold =
        p.threshold > 0.0f ? p.threshold : p.relativeThreshold * float(total / (4.0 * M_PI));
    auto lowIndex = [&](int f, int i, int j) {
        return (size_t(f) * d + size_t(j) * d / s) * d + size_t(i) * d / s;
    };
    std::vector<float> maxLum(nd, 0.0f);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) {
                float& m = maxLum[lowIndex(f, i, j)];
                m = std::max(m, lum[(size_t(f) * s + j) * s + i]);
            }
    std::vector<int> parent(nd);
    std::iota(parent.begin(), parent.end(), 0);
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < d; ++j)
            for (int i = 0; i < d; ++i) {
                const int k = (f * d + j) * d + i;
                if (!(maxLum[size_t(k)] > threshold)) continue;
                const int nbr[4][2] = {{i + 1, j}, {i - 1, j}, {i, j + 1}, {i, j - 1}};
                for (const auto& q : nbr) {
                    const int o = cubeTexelIndexWrapped(f, q[0], q[1], d);
                    if (maxLum[size_t(o)] > threshold)
                        parent[size_t(findRoot(parent, k))] = findRoot(parent, o);
                }
            }
    std::vector<int> lightOf(nd, -1);
    std::vector<int> texelLight(n, -1);
    std::vector<EnvLight> lights;
    std::vector<glm::dvec3> dirSum, colSum;
    std::vector<double> lumSum, lumPeak;
    for (int f = 0; f < 6; ++f)
        for (int j = 0; j < s; ++j)
            for (int i = 0; i < s; ++i) {
                const size_t k = (size_t(f) * s + j) * s + i;
                const size_t low = lowIndex(f, i, j);
                if (!(maxLum[low] > threshold) || !(lum[k] > threshold)) continue;
                const int root = findRoot(parent, int(low));
                int& id = lightOf[size_t(root)];
                if (id < 0) {
                    id = int(lights.size());
                    lights.emplace_back();
                    dirSum.emplace_back(0.0);
                    colSum.emplace_back(0.0);
                    lumSum.push_back(0.0);
                    lumPeak.push_back(0.0);
                }
                const float* c = radiance.texel(f, i, j);
                const double w = omega[k];
                const glm::dvec3 dir(cubeTexelDirection(f, i, j, s));
                dirSum[size_t(id)] += double(lum[k]) * w * dir;
                colSum[size_t(id)] += w * glm::dvec3(c[0], c[1], c[2]);
                lumSum[size_t(id)] += double(lum[k]) * w;
                lumPeak[size_t(id)] = std::max(lumPeak[size_t(id)], double(lum[k]));
                lights[size_t(id)].texels += 1;
                texelLight[k] = id;
            }
    for (size_t l = 0; l < lights.size(); ++l) {
        const double len = glm::length(dirSum[l]);
        lights[l].direction = len > 0.0 ? glm::vec3(dirSum[l] / len) : glm::vec3(0, 1, 0);
        lights[l].colour = glm::vec3(colSum[l]);
        lights[l].solidAngle = float(lumSum[l] / lumPeak[l]);
    }
    std::vector<int> order(lights.size());
    std::iota(order.begin(), order.end(), 0);
    std::stable_sort(order.begin(), order.end(), [&](int a, int b) {
        return luminance(lights[size_t(a)].colour) > luminance(lights[size_t(b)].colour);
    });
    const size_t kept = std::min(lights.size(), size_t(p.maxLights));
    std::vector<int> rank(lights.size(), -1);
    std::vector<EnvLight> sorted;
    for (size_t r = 0; r < kept; ++r) {
        rank[size_t(order[r])] = int(r);
        sorted.push_back(lights[size_t(order[r])]);
    }
    if (labels) {
        labels->assign(n, -1);
        for (size_t k = 0; k < n; ++k)
            if (texelLight[k] >= 0) (*labels)[k] = rank[size_t(texelLight[k])];
    }
    lights.swap(sorted);
    return lights;
}

} // namespace weft
