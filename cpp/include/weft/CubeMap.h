#pragma once
// Float RGB cube maps for image-based lighting, their face convention and seamless sampling.
//
// Face order and orientation follow Vulkan/OpenGL: faces +X, -X, +Y, -Y, +Z, -Z (index 0..5);
// the major axis of a direction picks the face. Texel (row j, column i) of a face of size S has
// face coordinates s = (i + 0.5) / S, t = (j + 0.5) / S, u = 2s - 1, v = 2t - 1 (row 0 = t = 0)
// and points along
//   +X ( 1, -v, -u)   -X (-1, -v,  u)   +Y ( u,  1,  v)
//   -Y ( u, -1, -v)   +Z ( u, -v,  1)   -Z (-u, -v, -1)   (normalised).
// Storage: level 0 is 6 x S x S x RGB floats, face-major then row-major, so NumPy sees
// (6, S, S, 3). Sampling is seamless: bilinear taps that fall off a face are fetched from the
// neighbouring face, and mip levels are solid-angle weighted 2x2 averages.
#include <array>
#include <vector>

#include <glm/glm.hpp>

namespace weft {

/// Face index and continuous face coordinates (u, v in [-1, 1]) of a non-zero direction.
struct CubeCoord {
    int face = 0;
    float u = 0.0f;
    float v = 0.0f;
};

/// The face and (u, v) a direction hits; throws InvalidArgument for a zero or non-finite one.
CubeCoord cubeCoord(const glm::vec3& dir);
/// Unit direction through face coordinates (u, v) of `face`.
glm::vec3 cubeDirection(int face, float u, float v);
/// Unit direction through the centre of texel (i, j) (column, row) of a face of size `size`.
glm::vec3 cubeTexelDirection(int face, int i, int j, int size);
/// Flat index face * S^2 + j * S + i of texel (i, j) of `face`, where i or j may lie one texel
/// outside the face: such texels map to the nearest texel of the neighbouring face.
int cubeTexelIndexWrapped(int face, int i, int j, int size);
/// Exact solid angle (sr) of texel (i, j) of a face of size `size`; the 6 S^2 texels sum to 4 pi.
double cubeTexelSolidAngle(int i, int j, int size);

class CubeMap {
public:
    CubeMap() = default;
    /// A black cube map; throws InvalidArgument unless 1 <= size <= 8192.
    explicit CubeMap(int size);

    int size() const { return mSize; }
    bool empty() const { return mSize == 0; }
    /// Number of levels (1 until buildMips()); level l has size max(1, size >> l), each texel the
    /// solid-angle weighted mean of the finer texels it covers.
    int levels() const { return int(mLevels.size()); }
    int levelSize(int level) const;
    float* data(int level = 0) { return mLevels[size_t(level)].data(); }
    const float* data(int level = 0) const { return mLevels[size_t(level)].data(); }
    size_t floatCount(int level = 0) const { return mLevels[size_t(level)].size(); }
    float* texel(int face, int i, int j, int level = 0);
    const float* texel(int face, int i, int j, int level = 0) const;

    /// Builds the full chain down to 1x1 (replaces existing levels above 0).
    void buildMips();
    /// Drops all levels above 0 (call after editing level 0).
    void clearMips() { keepLevels(1); }
    /// Keeps the first `count` levels (at least 1).
    void keepLevels(int count);
    /// Seamless bilinear sample of `level` in direction `dir` (any length > 0).
    glm::vec3 sample(const glm::vec3& dir, int level = 0) const;
    /// Trilinear between levels; lod is clamped to [0, levels() - 1].
    glm::vec3 sampleLod(const glm::vec3& dir, float lod) const;
    /// Texel of `level` at integer (i, j) that may lie one texel outside the face: such taps are
    /// fetched from the neighbouring face (the texel nearest the extended face's direction).
    const float* texelWrapped(int face, int i, int j, int level = 0) const;
    /// Throws InvalidArgument when any value is NaN/inf (or negative when `nonNegative`).
    void requireFinite(const char* what, bool nonNegative = false) const;

private:
    int mSize = 0;
    std::vector<std::vector<float>> mLevels;
};

} // namespace weft
