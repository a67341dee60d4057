#pragma once
// BTF measurements of one material: per sample (light direction, view direction) an RGB image,
// stored planar as float32 [sample][channel][texel] so one pass streams over the samples.
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace weft {

/// A measurement direction in the Bonn convention: polar angle θ from the surface normal (+z)
/// and azimuth φ, both in whole or fractional degrees (the file names use degrees).
struct BtfAngles {
    float thetaLight = 0, phiLight = 0, thetaView = 0, phiView = 0;
};

/// (sin θ cos φ, sin θ sin φ, cos θ) for angles in degrees (SPEC eq. 4.28).
glm::vec3 btfDirection(float thetaDeg, float phiDeg);

/// The 81 directions shared by light and view in the Bonn database, ring by ring
/// (θ = 0, 15, ..., 75 degrees), each ring by increasing φ. Elements are (θ, φ) in degrees.
const std::vector<glm::vec2>& btfStandardDirections();

/// How 8-bit file values become sample values in [0, 1].
enum class BtfGamma {
    Raw,   ///< value / 255, as the seed fitted the JPEG values (gamma-encoded)
    Linear ///< (value / 255)^2.2: linearised with the usual display gamma
};

/// For samples read from JPEG files: what the files store, per sample and colour component the
/// quantised 8x8 block-DCT coefficients c and the quantisation steps q (libjpeg's
/// jpeg_read_coefficients, natural order). The encoder's DCT of the 8-bit image (levels shifted
/// by -128; JFIF YCbCr with chroma subsampled as `components` say) lay in the cells
/// [(c - 1/2) q, (c + 1/2) q]: a constraint on the image, which the decoded values (the cells'
/// centres) do not carry. 3 bytes per texel and sample for 4:2:0 colour (the floats take 12).
struct BtfJpegCells {
    struct Component {
        int blocksWide = 0, blocksHigh = 0; ///< blocks holding image data
        int hSampling = 1, vSampling = 1;   ///< sampling factors (luma 2 x 2 for 4:2:0)
        size_t offset = 0;                  ///< first coefficient within a sample
    };
    bool ycbcr = false;                ///< 3 components Y, Cb, Cr; false: 1 grey component
    std::vector<Component> components; ///< the same for every sample
    size_t coefficientsPerSample = 0;
    std::vector<int16_t> coefficients; ///< [sample][component][blockRow][blockCol][64]
    std::vector<uint16_t> quant;       ///< [sample][component][64]
};

class BtfSamples {
public:
    BtfSamples() = default;
    /// Zero-filled samples; throws InvalidArgument for non-positive sizes or mismatched angles.
    BtfSamples(int width, int height, std::vector<BtfAngles> angles);

    int width() const { return mWidth; }
    int height() const { return mHeight; }
    size_t texels() const { return size_t(mWidth) * size_t(mHeight); }
    int count() const { return int(mAngles.size()); }
    const std::vector<BtfAngles>& angles() const { return mAngles; }
    glm::vec3 light(int s) const { return mLights[size_t(s)]; }
    glm::vec3 view(int s) const { return mViews[size_t(s)]; }

    /// Channel c (0..2) of sample s: texels() floats, rows top to bottom.
    float* plane(int s, int c) { return mValues.data() + (size_t(s) * 3 + size_t(c)) * texels(); }
    const float* plane(int s, int c) const {
        return mValues.data() + (size_t(s) * 3 + size_t(c)) * texels();
    }
    std::vector<float>& values() { return mValues; }
    const std::vector<float>& values() const { return mValues; }

    /// Throws InvalidArgument when a value is NaN/inf.
    void requireFinite() const;

    /// The JPEG cells the samples were decoded from (loadBtf of JPEG files with raw gamma), or
    /// null. They describe the values as loaded: changing values() makes them stale.
    const BtfJpegCells* jpegCells() const { return mJpegCells.get(); }
    void setJpegCells(std::shared_ptr<const BtfJpegCells> cells) { mJpegCells = std::move(cells); }

private:
    int mWidth = 0, mHeight = 0;
    std::vector<BtfAngles> mAngles;
    std::vector<glm::vec3> mLights, mViews;
    std::vector<float> mValues;
    std::shared_ptr<const BtfJpegCells> mJpegCells;
};

} // namespace weft
