#pragma once
// Environment capture conversions: sphere map (mirror ball), fisheye, equirectangular -> cube map
// and back for viewing, plus filling what the capture cannot see (SPEC §4.1, §4.2).
//
// Images are interleaved RGB floats, rows top to bottom. Image-space conventions:
// - Sphere map: pixel (row, col) of a W x H map sits at x = 2 (col + 0.5) / W - 1,
//   y = 1 - 2 (row + 0.5) / H (y up). A world direction V is moved into sphere-map space with
//   the 4x4 `worldToSphere` (w = 0), then H = normalize(wrap (0, 0, 1) + V); if H.z < 0,
//   H = normalize(H.x, H.y, 0); it is sampled at H.xy (SPEC §4.2). The centre shows +Z of
//   sphere space (towards the camera), the rim (wrap = 1) shows -Z.
// - Fisheye (equidistant): camera space +Z is the optical axis, x right, y up; a direction at
//   angle theta from the axis lands at radius theta / (fov / 2) of the inscribed image disc.
// - Equirectangular: column u = 0.5 + atan2(d.x, -d.z) / (2 pi) (centre looks along -Z, +X to
//   the right), row v = acos(d.y) / pi (+Y at the top); wraps horizontally.
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <weft/CubeMap.h>
#include <weft/Image.h>

namespace weft {

/// A read-only view of an interleaved RGB float image (rows top to bottom).
struct RgbView {
    const float* pixels = nullptr;
    int width = 0;
    int height = 0;
};

/// The view of a 3-channel ImageF (e.g. from loadHdr / loadExr); throws InvalidArgument for
/// other channel counts.
RgbView rgbView(const ImageF& image);

/// A cube map and which texels the capture saw (6 * S * S bytes, 1 = seen).
struct CaptureCube {
    CubeMap cube;
    std::vector<uint8_t> valid;
};

/// Sphere map -> cube map with the seed's wrap value (wrap in (0, 1]; 1 = a perfect 360 degree
/// sphere map). Texels whose H.z was clamped (w + V.z <= 0 in sphere space) are marked unseen
/// and left black; fill them with fillUnseen(). `supersample` taps per axis (>= 1).
CaptureCube sphereToCube(RgbView sphere, const glm::mat4& worldToSphere, float wrap, int size,
                         int supersample = 2);
/// Fisheye (equidistant, field of view `fov` radians in (0, 2 pi]) -> cube map with mask.
CaptureCube fisheyeToCube(RgbView fisheye, const glm::mat4& worldToCamera, float fov, int size,
                          int supersample = 2);
/// Equirectangular (latitude-longitude) -> cube map.
CubeMap equirectToCube(RgbView equirect, int size, int supersample = 2);
/// Cube map -> equirectangular image (height x width x 3), for viewing and median cut.
std::vector<float> cubeToEquirect(const CubeMap& cube, int width, int height);
/// Cube map -> sphere map (size x size x 3) with the same mapping as sphereToCube; pixels
/// outside the unit disc repeat the rim. `level` picks the cube's mip level.
std::vector<float> cubeToSphere(const CubeMap& cube, int size, const glm::mat4& worldToSphere,
                                float wrap, int level = 0);
/// Fills texels with valid == 0 by push-pull over the seamless mip pyramid: seen texels keep
/// their value, unseen ones get a smooth interpolation of the nearest seen regions (across
/// faces). Throws InvalidArgument when nothing was seen or the mask size is wrong.
void fillUnseen(CubeMap& cube, const std::vector<uint8_t>& valid);

/// Largest radiance an environment file may hold (weft.ibl.capture.MAX_RADIANCE is the same):
/// far above any real capture, low enough that the resampling sums stay finite in float.
constexpr float kMaxEnvironmentRadiance = 1e30f;

/// Reads an environment capture (weft-demo's --environment) with loadImageF (.hdr / .pic, .exr,
/// or .png as value / 255) and converts it to a radiance cube map of face `size` (> 0): a 2:1
/// image as an equirectangular panorama, a square one as a 360-degree sphere map (wrap 1,
/// sphere space = world space, unseen texels filled). Channels after the third are ignored.
/// Throws IoError when the file cannot be read, InvalidArgument naming the file for fewer than
/// 3 channels, any other shape, or a value that is not finite, negative or above
/// kMaxEnvironmentRadiance (an EXR can store NaN and inf, which would light the scene with NaN).
CubeMap loadEnvironmentCube(const std::string& path, int size);

} // namespace weft
