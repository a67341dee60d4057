#pragma once
// Reading and writing BTFs in the Bonn database layout (shared/formats/bonn-btf.md): a folder or
// a zip holding `tvTTT_pvPPP/NNNNN tlAAA plBBB tvCCC pvDDD.jpg` images (also the underscore
// variant with a material prefix; .jpg, .png (8 or 16 bits), .exr).
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include <weft/BtfSamples.h>

namespace weft {

struct BtfLoadOptions {
    /// Views to load as (θ_v, φ_v) degrees; empty = every view present. Default: frontal.
    std::vector<glm::vec2> views{glm::vec2(0.0f, 0.0f)};
    /// Raw: value / 255 (16-bit PNG: value / 65535); Linear: the same raised to 2.2. Values
    /// are taken as stored: PNG gAMA/sRGB/iCCP chunks are ignored, as JPEG has none.
    BtfGamma gamma = BtfGamma::Raw;
    int threads = 0; ///< decoding threads, 0 = all cores, else 1..256
    /// Keep the JPEG coefficients and quantisation tables (BtfSamples::jpegCells) when every
    /// image is a grey or YCbCr JPEG of one layout and gamma is Raw (the cells constrain the
    /// 8-bit values, value / 255); a second entropy-decoding pass, 25% more memory, so only
    /// when asked for (the JPEG-cell refinement of the Blinn-Phong fit uses them).
    bool jpegCells = false;
};

/// Angles parsed from a file name by their tl/pl/tv/pv keys (space or underscore separated).
/// Returns false when one of the four keys is missing.
bool parseBtfFileName(const std::string& name, BtfAngles& out);

/// Loads a folder or a .zip. Every selected view must hold each of the 81 standard light
/// directions exactly once; all images must be RGB (or grey) of one size and opaque (a PNG
/// with any alpha below its maximum is refused: compositing would change the measurement).
/// macOS metadata (`__MACOSX/` folders, `._*` AppleDouble files) is skipped. Images are read,
/// decoded and converted one at a time per thread, and every zip entry's declared size is
/// checked first (against the archive and a 256 MiB per-image limit), so a zip bomb is refused
/// without being inflated. Throws IoError naming the file (or the missing angles) otherwise,
/// InvalidArgument for impossible options.
BtfSamples loadBtf(const std::string& path, const BtfLoadOptions& options = {});

enum class BtfImageFormat { Jpeg, Png };

struct BtfWriteOptions {
    BtfImageFormat format = BtfImageFormat::Jpeg;
    int jpegQuality = 95;           ///< 1..100
    bool zip = false;               ///< write `path` as a zip archive instead of a folder
    BtfGamma gamma = BtfGamma::Raw; ///< Linear: values are encoded with 1/2.2 before quantising
    std::string prefix; ///< empty: `NNNNN tl.. pl.. tv.. pv..`; else `PREFIX_NNNNN_tl.._...`
};

/// Writes samples (values in [0, 1], clipped, quantised to 8 bits) in the Bonn layout under
/// `path/UBO2003/MANYFILES/tvTTT_pvPPP/`. Angles must be whole degrees.
void writeBtf(const std::string& path, const BtfSamples& samples, const BtfWriteOptions& options);

} // namespace weft
