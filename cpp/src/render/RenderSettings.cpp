// RenderSettings: the ranges each renderer setting accepts.
#include <weft/Renderer.h>

#include <cmath>
#include <string>

namespace weft {

void RenderSettings::validate() const {
    if (shadowMapSize < 16 || shadowMapSize > 16384)
        throw InvalidArgument("shadow_map_size must be in [16, 16384] (got " +
                              std::to_string(shadowMapSize) + ")");
    if (probeSize < 4 || probeSize > 2048)
        throw InvalidArgument("probe_size must be in [4, 2048] (got " + std::to_string(probeSize) +
                              ")");
    if (pcfRadius < 0 || pcfRadius > 7)
        throw InvalidArgument("pcf_radius must be in [0, 7] (got " + std::to_string(pcfRadius) +
                              ")");
    for (float v : {biasConstant, biasSlope, biasMax, normalOffset})
        if (!(std::isfinite(v) && v >= 0.0f))
            throw InvalidArgument("shadow bias and normal offset must be finite and >= 0");
    if (!(std::isfinite(hairWidth) && hairWidth > 0.0f))
        throw InvalidArgument("hair_width must be finite and > 0");
    if (!(std::isfinite(hairDomLayerSize) && hairDomLayerSize >= 0.0f))
        throw InvalidArgument("hair_dom_layer_size must be finite and >= 0 (0: automatic)");
    if (hairDomSize < 16 || hairDomSize > 8192)
        throw InvalidArgument("hair_dom_size must be in [16, 8192] (got " +
                              std::to_string(hairDomSize) + ")");
    const int w = int(hairOitWeight);
    if (w < 7 || w > 10) throw InvalidArgument("hair OIT weight must be eq. 7, 8, 9 or 10");
    if (msaa != 1 && msaa != 2 && msaa != 4 && msaa != 8)
        throw InvalidArgument("msaa must be 1, 2, 4 or 8 samples (got " + std::to_string(msaa) +
                              ")");
    if (!(std::isfinite(exposure) && std::fabs(exposure) <= 64.0f))
        throw InvalidArgument("exposure must be finite, in [-64, 64] stops");
    if (int(toneMap) < 0 || int(toneMap) > 3)
        throw InvalidArgument("tone map must be clamp, aces, agx or neutral");
    if (ambientOcclusion > 64 || ambientOcclusion % 8 != 0)
        throw InvalidArgument("ambient_occlusion must be 0 or a multiple of 8 up to 64 dome lights "
                              "(got " +
                              std::to_string(ambientOcclusion) + ")");
    if (!(std::isfinite(ambientOcclusionBlur) && ambientOcclusionBlur >= 0.0f &&
          ambientOcclusionBlur <= 64.0f))
        throw InvalidArgument("ambient_occlusion_blur must be in [0, 64] pixels");
    if (hairPrimitive != HairPrimitive::Lines && hairPrimitive != HairPrimitive::Ribbons)
        throw InvalidArgument("hair primitive must be lines or ribbons");
}

} // namespace weft
