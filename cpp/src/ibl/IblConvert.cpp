// Sphere map / fisheye / equirectangular <-> cube map conversions and push-pull hole filling.
#include <weft/IblConvert.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <weft/Error.h>

#include "IblParallel.h"
#include "IblValidate.h"

namespace weft {

namespace {

constexpr float kPi = 3.14159265358979f;

// Bilinear sample at continuous pixel coordinates (centres at integers); x wraps or clamps.
glm::vec3 bilinear(RgbView img, float px, float py, bool wrapX) {
    const int x0 = int(std::floor(px)), y0 = int(std::floor(py));
    const float fx = px - float(x0), fy = py - float(y0);
    auto fetch = [&](int x, int y) {
        x = wrapX ? ((x % img.width) + img.width) % img.width : std::clamp(x, 0, img.width - 1);
        y = std::clamp(y, 0, img.height - 1);
        const float* p = img.pixels + (size_t(y) * img.width + x) * 3;
        return glm::vec3(p[0], p[1], p[2]);
    };
    const glm::vec3 top = glm::mix(fetch(x0, y0), fetch(x0 + 1, y0), fx);
    const glm::vec3 bottom = glm::mix(fetch(x0, y0 + 1), fetch(x0 + 1, y0 + 1), fx);
    return glm::mix(top, bottom, fy);
}

// Sample at disc coordinates (x right, y up, [-1, 1] across the image).
glm::vec3 sampleDisc(RgbView img, float x, float y) {
    return bilinear(img, (x * 0.5f + 0.5f) * float(img.width) - 0.5f,
                    (0.5f - y * 0.5f) * float(img.height) - 0.5f, false);
}

// Fills every texel of `cube` with the mean of `ss` x `ss` taps of fn(direction); valid (if
// given) gets seen(centre direction).
template <class Fn, class Seen>
void fillCube(CubeMap& cube, int ss, Fn fn, Seen seen, std::vector<uint8_t>* valid) {
    const int s = cube.size();
    if (valid) valid->assign(size_t(6) * s * s, 1);
    iblParallelFor(6 * s, [&](int begin, int end) {
        for (int row = begin; row < end; ++row) {
            const int f = row / s, j = row % s;
            for (int i = 0; i < s; ++i) {
                glm::vec3 acc(0.0f);
                for (int b = 0; b < ss; ++b)
                    for (int a = 0; a < ss; ++a) {
                        const float fi = float(i) + (float(a) + 0.5f) / float(ss);
                        const float fj = float(j) + (float(b) + 0.5f) / float(ss);
                        const float u = 2.0f * fi / float(s) - 1.0f;
                        const float v = 2.0f * fj / float(s) - 1.0f;
                        acc += fn(cubeDirection(f, u, v));
                    }
                acc /= float(ss * ss);
                float* out = cube.texel(f, i, j);
                out[0] = acc.x;
                out[1] = acc.y;
                out[2] = acc.z;
                if (valid)
                    (*valid)[(size_t(f) * s + j) * s + i] = seen(cubeTexelDirection(f, i, j, s));
            }
        }
    });
}

glm::mat3 rotationPart(const glm::mat4& m, const char* what) {
    requireFinite(m, what);
    const glm::mat3 r(m);
    if (std::fabs(glm::determinant(r)) < 1e-8f)
        throw InvalidArgument(std::string(what) + " must have an invertible 3x3 part");
    return r;
}

void requireSupersample(int ss) {
    if (ss < 1 || ss > 16) throw InvalidArgument("supersample must be in [1, 16]");
}

} // namespace

RgbView rgbView(const ImageF& image) {
    image.validate();
    if (image.channels != 3)
        throw InvalidArgument("environment images must have 3 channels, got " +
                              std::to_string(image.channels));
    return {image.pixels.data(), image.width, image.height};
}

CaptureCube sphereToCube(RgbView sphere, const glm::mat4& worldToSphere, float wrap, int size,
                         int supersample) {
    requireRgb(sphere, "sphere map");
    if (!(wrap > 0.0f && wrap <= 1.0f))
        throw InvalidArgument("wrap value must be in (0, 1], got " + std::to_string(wrap));
    requireSupersample(supersample);
    const glm::mat3 r = rotationPart(worldToSphere, "world_to_sphere");
    CaptureCube out{CubeMap(size), {}};
    const glm::vec3 eye(0.0f, 0.0f, wrap);
    fillCube(
        out.cube, supersample,
        [&](const glm::vec3& d) {
            glm::vec3 h = glm::normalize(eye + glm::normalize(r * d));
            if (h.z < 0.0f) h = glm::normalize(glm::vec3(h.x, h.y, 0.0f));
            return sampleDisc(sphere, h.x, h.y);
        },
        [&](const glm::vec3& d) { return wrap + glm::normalize(r * d).z > 1e-4f; }, &out.valid);
    return out;
}

CaptureCube fisheyeToCube(RgbView fisheye, const glm::mat4& worldToCamera, float fov, int size,
                          int supersample) {
    requireRgb(fisheye, "fisheye image");
    if (!(fov > 0.0f && fov <= 2.0f * kPi))
        throw InvalidArgument("fisheye field of view must be in (0, 2 pi] radians");
    requireSupersample(supersample);
    const glm::mat3 r = rotationPart(worldToCamera, "world_to_camera");
    CaptureCube out{CubeMap(size), {}};
    const float half = 0.5f * fov;
    fillCube(
        out.cube, supersample,
        [&](const glm::vec3& d) {
            const glm::vec3 v = glm::normalize(r * d);
            const float theta = std::acos(std::clamp(v.z, -1.0f, 1.0f));
            const float len = std::sqrt(v.x * v.x + v.y * v.y);
            const float rad = std::min(theta / half, 1.0f);
            const float cx = len > 0.0f ? v.x / len : 0.0f, cy = len > 0.0f ? v.y / len : 0.0f;
            return sampleDisc(fisheye, rad * cx, rad * cy);
        },
        [&](const glm::vec3& d) {
            return std::acos(std::clamp(glm::normalize(r * d).z, -1.0f, 1.0f)) <= half;
        },
        &out.valid);
    return out;
}

CubeMap equirectToCube(RgbView equirect, int size, int supersample) {
    requireRgb(equirect, "equirectangular image");
    requireSupersample(supersample);
    CubeMap cube(size);
    fillCube(
        cube, supersample,
        [&](const glm::vec3& d) {
            const float u = 0.5f + std::atan2(d.x, -d.z) / (2.0f * kPi);
            const float v = std::acos(std::clamp(d.y, -1.0f, 1.0f)) / kPi;
            return bilinear(equirect, u * float(equirect.width) - 0.5f,
                            v * float(equirect.height) - 0.5f, true);
        },
        [](const glm::vec3&) { return true; }, nullptr);
    return cube;
}

std::vector<float> cubeToEquirect(const CubeMap& cube, int width, int height) {
    requireCube(cube, "cube map");
    requireImageSize(width, height, "equirectangular image");
    std::vector<float> out(size_t(width) * height * 3);
    iblParallelFor(height, [&](int begin, int end) {
        for (int row = begin; row < end; ++row) {
            const float theta = kPi * (float(row) + 0.5f) / float(height);
            for (int col = 0; col < width; ++col) {
                const float phi = 2.0f * kPi * ((float(col) + 0.5f) / float(width) - 0.5f);
                const glm::vec3 d(std::sin(theta) * std::sin(phi), std::cos(theta),
                                  -std::sin(theta) * std::cos(phi));
                const glm::vec3 c = cube.sample(d);
                float* p = out.data() + (size_t(row) * width + col) * 3;
                p[0] = c.x;
                p[1] = c.y;
                p[2] = c.z;
            }
        }
    });
    return out;
}

std::vector<float> cubeToSphere(const CubeMap& cube, int size, const glm::mat4& worldToSphere,
                                float wrap, int level) {
    requireCube(cube, "cube map");
    if (level < 0 || level >= cube.levels())
        throw InvalidArgument("cube map level " + std::to_string(level) + " does not exist");
    requireImageSize(size, size, "sphere map");
    if (!(wrap > 0.0f && wrap <= 1.0f))
        throw InvalidArgument("wrap value must be in (0, 1], got " + std::to_string(wrap));
    const glm::mat3 inv = glm::inverse(rotationPart(worldToSphere, "world_to_sphere"));
    std::vector<float> out(size_t(size) * size * 3);
    iblParallelFor(size, [&](int begin, int end) {
        for (int row = begin; row < end; ++row)
            for (int col = 0; col < size; ++col) {
                float x = 2.0f * (float(col) + 0.5f) / float(size) - 1.0f;
                float y = 1.0f - 2.0f * (float(row) + 0.5f) / float(size);
                const float r2 = x * x + y * y;
                if (r2 > 1.0f) {
                    x /= std::sqrt(r2);
                    y /= std::sqrt(r2);
                }
                const glm::vec3 h(x, y, std::sqrt(std::max(0.0f, 1.0f - x * x - y * y)));
                const float t =
                    wrap * h.z +
                    std::sqrt(std::max(0.0f, wrap * wrap * h.z * h.z - wrap * wrap + 1.0f));
                glm::vec3 v = t * h - glm::vec3(0.0f, 0.0f, wrap);
                if (glm::dot(v, v) < 1e-12f) v = glm::vec3(0.0f, 0.0f, -1.0f);
                const glm::vec3 c = cube.sample(inv * v, level);
                float* p = out.data() + (size_t(row) * size + col) * 3;
                p[0] = c.x;
                p[1] = c.y;
                p[2] = c.z;
            }
    });
    return out;
}

void fillUnseen(CubeMap& cube, const std::vector<uint8_t>& valid) {
    requireCube(cube, "cube map");
    const int s0 = cube.size();
    if (valid.size() != size_t(6) * s0 * s0)
        throw InvalidArgument("validity mask must have 6 * size * size entries");
    // Push: premultiplied colour sums and coverage per level.
    std::vector<std::vector<float>> colour(1), weight(1);
    std::vector<int> sizes{s0};
    colour[0].resize(size_t(6) * s0 * s0 * 3);
    weight[0].resize(size_t(6) * s0 * s0);
    double seen = 0.0;
    for (size_t t = 0; t < weight[0].size(); ++t) {
        const float w = valid[t] ? 1.0f : 0.0f;
        weight[0][t] = w;
        seen += w;
        for (int k = 0; k < 3; ++k) colour[0][t * 3 + k] = w * cube.data()[t * 3 + k];
    }
    if (seen == 0.0) throw InvalidArgument("validity mask marks no texel as seen");
    if (seen == double(weight[0].size())) return;
    for (int s = s0; s > 1; s = (s + 1) / 2) {
        const int c = (s + 1) / 2;
        const auto& fc = colour.back();
        const auto& fw = weight.back();
        std::vector<float> nc(size_t(6) * c * c * 3, 0.0f), nw(size_t(6) * c * c, 0.0f);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < s; ++j)
                for (int i = 0; i < s; ++i) {
                    const size_t src = (size_t(f) * s + j) * s + i;
                    const size_t dst = (size_t(f) * c + j / 2) * c + i / 2;
                    nw[dst] += 0.25f * fw[src];
                    for (int k = 0; k < 3; ++k) nc[dst * 3 + k] += 0.25f * fc[src * 3 + k];
                }
        colour.push_back(std::move(nc));
        weight.push_back(std::move(nw));
        sizes.push_back(c);
    }
    // Top (1x1 per face): faces that saw nothing take the coverage-weighted mean of the others.
    CubeMap coarse(1);
    {
        glm::dvec3 sum(0.0);
        double wsum = 0.0;
        for (int f = 0; f < 6; ++f) {
            wsum += weight.back()[size_t(f)];
            for (int k = 0; k < 3; ++k) sum[k] += colour.back()[size_t(f) * 3 + k];
        }
        for (int f = 0; f < 6; ++f) {
            const float w = weight.back()[size_t(f)];
            for (int k = 0; k < 3; ++k)
                coarse.data()[f * 3 + k] =
                    w > 0.0f ? colour.back()[size_t(f) * 3 + k] / w : float(sum[k] / wsum);
        }
    }
    // Pull: blend each level's own average with the seamless upsampled coarser level.
    for (int level = int(colour.size()) - 2; level >= 0; --level) {
        const int s = sizes[size_t(level)];
        CubeMap fine(s);
        for (int f = 0; f < 6; ++f)
            for (int j = 0; j < s; ++j)
                for (int i = 0; i < s; ++i) {
                    const size_t t = (size_t(f) * s + j) * s + i;
                    const float w = std::min(1.0f, weight[size_t(level)][t]);
                    const glm::vec3 up = coarse.sample(cubeTexelDirection(f, i, j, s));
                    for (int k = 0; k < 3; ++k) {
                        const float own =
                            w > 0.0f ? colour[size_t(level)][t * 3 + k] / weight[size_t(level)][t]
                                     : 0.0f;
                        fine.data()[t * 3 + k] = w * own + (1.0f - w) * up[k];
                    }
                }
        coarse = std::move(fine);
    }
    cube.clearMips();
    std::copy(coarse.data(), coarse.data() + coarse.floatCount(), cube.data());
}

CubeMap loadEnvironmentCube(const std::string& path, int size) {
    if (size < 1)
        throw InvalidArgument("environment cube size must be positive, got " +
                              std::to_string(size));
    const ImageF image = loadImageF(path);
    if (image.channels < 3)
        throw InvalidArgument("environment image '" + path + "' needs RGB, it has " +
                              std::to_string(image.channels) + " channel(s)");
    // The RGB of every pixel, each value checked: an EXR may hold NaN, inf or negative values,
    // an RGBE file values up to ~1.7e38 whose resampling sums overflow to inf.
    ImageF rgb(image.width, image.height, 3);
    const size_t pixels = size_t(image.width) * size_t(image.height);
    for (size_t t = 0; t < pixels; ++t)
        for (size_t c = 0; c < 3; ++c) {
            const float v = image.pixels[t * size_t(image.channels) + c];
            if (!(v >= 0.0f && v <= kMaxEnvironmentRadiance))
                throw InvalidArgument("environment image '" + path +
                                      "': radiance must be finite and in [0, 1e30], "
                                      "got " +
                                      std::to_string(v) + " at pixel (" +
                                      std::to_string(t % size_t(image.width)) + ", " +
                                      std::to_string(t / size_t(image.width)) + ")");
            rgb.pixels[t * 3 + c] = v;
        }
    if (image.width == 2 * image.height) return equirectToCube(rgbView(rgb), size);
    if (image.width == image.height) {
        CaptureCube capture = sphereToCube(rgbView(rgb), glm::mat4(1.0f), 1.0f, size);
        fillUnseen(capture.cube, capture.valid);
        return std::move(capture.cube);
    }
    throw InvalidArgument("environment image '" + path +
                          "' must be equirectangular (2:1) or "
                          "a sphere map (square), got " +
                          std::to_string(image.width) + "x" + std::to_string(image.height));
}

} // namespace weft
