#pragma once
// Rendering of synthetic BTFs from known ground truth (SPEC §3.1): the material model of
// BtfMaterialMaps per sample, optionally with cast shadows from a height field.
#include <vector>

#include <weft/BtfFit.h>

namespace weft {

struct BtfShadowing {
    std::vector<float> height; ///< (H, W) in texel units; empty = no cast shadows
    bool wrap = true;          ///< the pattern tiles (rays leaving one side enter the other)
};

/// Renders `maps` for each of `angles`; where a height field is given, a texel whose ray towards
/// the light passes below the height field receives only the ambient term.
BtfSamples renderBtf(const BtfMaterialMaps& maps, const std::vector<BtfAngles>& angles,
                     const BtfShadowing& shadowing = {}, int threads = 0);

} // namespace weft
