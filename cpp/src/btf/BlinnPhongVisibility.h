#pragma once
// The cast-shadow (visibility) pass of the per-texel Blinn-Phong fit (SPEC §3.5 robustness):
// the model's parts per sample, the classification of a texel's samples against a fit
// (BtfShadowClassify.h), the highlight-free Lambert fit the pass starts from, and the data's
// noise level that bounds the classification's σ.
#include <vector>

#include <glm/glm.hpp>

#include "btf/BlinnPhongTexel.h"

namespace weft {

class BtfSamples;
struct BtfMaterialMaps;
struct BtfNonlinearOptions;

/// Per sample, channel sums: the fit r's light-dependent part (lit), its diffuse part, and the
/// observed value (`planes`, [channel][padded sample]) less the fit's constant term (seen).
/// Returns that constant term.
double blinnPhongParts(const BlinnPhongTexel& tx, const BlinnPhongResult& r, const float* planes,
                       std::vector<double>& lit, std::vector<double>& diffuse,
                       std::vector<double>& seen);

/// Cast shadows of the texel's samples for the fit r, σ at most sigmaCap: writes the weights of
/// the next round into `weights` (padded size) and returns the number left out; `misfit` as
/// classifyCastShadows.
int classifyBlinnPhongShadows(const BlinnPhongTexel& tx, const BlinnPhongResult& r,
                              const float* planes, std::vector<float>& weights, int& misfit,
                              double sigmaCap);

/// Lambert + ambient (no highlight) over the texel's used samples by linear least squares on
/// the channel sums, then (m, b) >= 0 per channel at that normal; θ = (u, v, eta). The normal of
/// `start` (u, v) is kept when the samples do not determine one.
BlinnPhongResult lambertFit(BlinnPhongTexel& tx, const double start[2], double eta);

/// The start exponent's η for texel t: the seed's, inside [etaMin, etaMax].
double seedEta(const BtfMaterialMaps& seed, size_t t, double etaMin, double etaMax);

/// A texel's samples as [channel][padded sample] planes (zero padding), or its BT.601 luma in
/// all three channels when `luma`.
void texelPlanes(const BtfSamples& samples, size_t t, size_t padded, bool luma, float* out);

/// The noise level of the data (channel sums), for the σ cap: the median over up to 1024
/// texels spread evenly over the image of the steep-light residual σ of their first fit from
/// the seed (all samples, the built-in solver).
double blinnPhongDataNoise(const BtfSamples& samples, const BlinnPhongGeometry& geometry,
                           const std::vector<glm::vec3>& lights,
                           const std::vector<glm::vec3>& halves, const BtfMaterialMaps& seed,
                           const BtfNonlinearOptions& options, double etaMin, double etaMax);

} // namespace weft
