#include "sim/cloth/ClothKernels.h"

#include <cmath>
#include <cstring>

#if defined(__SSE2__) || defined(_M_X64)
#include <emmintrin.h>
#define WEFT_CLOTH_SSE 1
#endif

namespace weft::cloth {

namespace {

// Coincident particles have no direction: they are separated along their rest offset, so a
// collapsed cloth unfolds instead of staying stuck.
constexpr float kCoincident2 = 1e-24f;
constexpr float kUnfold = 1e-6f;

template <bool Compliant>
inline void projectOne(Particle& A, Particle& B, float restLen, float alphaTilde, float& lambda,
                       const glm::vec3& restOffset) {
    const float wsum = A.w + B.w;
    if (wsum <= 0.0f) return;
    glm::vec3 d = B.x - A.x;
    float len2 = glm::dot(d, d);
    if (len2 < kCoincident2) {
        d = restOffset * kUnfold;
        len2 = glm::dot(d, d);
    }
    const float len = std::sqrt(len2);
    const float C = len - restLen;
    float dl;
    if (Compliant) {
        dl = (-C - alphaTilde * lambda) / (wsum + alphaTilde);
        lambda += dl;
    } else {
        dl = -C / wsum;
    }
    const glm::vec3 corr = d * (dl / len);
    A.x -= A.w * corr;
    B.x += B.w * corr;
}

template <bool Compliant>
void scalarRange(Particle* base, const RowJob& job, int q0) {
    for (int q = q0; q < job.count; ++q) {
        if (!job.on[q]) continue;
        Particle* a = base + job.cols[q];
        projectOne<Compliant>(a[0], a[job.delta], job.rest[q], job.alphaTilde, job.lambda[q],
                              job.restOffset);
    }
}

#ifdef WEFT_CLOTH_SSE

// Four records (x, y, z, w) <-> four registers of x, of y, of z, of w.
inline void transpose(__m128& r0, __m128& r1, __m128& r2, __m128& r3) {
    const __m128 t0 = _mm_unpacklo_ps(r0, r1), t1 = _mm_unpacklo_ps(r2, r3);
    const __m128 t2 = _mm_unpackhi_ps(r0, r1), t3 = _mm_unpackhi_ps(r2, r3);
    r0 = _mm_movelh_ps(t0, t1);
    r1 = _mm_movehl_ps(t1, t0);
    r2 = _mm_movelh_ps(t2, t3);
    r3 = _mm_movehl_ps(t3, t2);
}

inline __m128 select(__m128 mask, __m128 a, __m128 b) {
    return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b));
}

// The operations of projectOne, lane by lane; lanes that projectOne would skip get dl = 0,
// which leaves their positions unchanged.
template <bool Compliant>
void simdRows(Particle* base, const RowJob& job) {
    const glm::vec3 u = job.restOffset * kUnfold;
    const float u2 = glm::dot(u, u);
    const __m128 ux = _mm_set1_ps(u.x), uy = _mm_set1_ps(u.y), uz = _mm_set1_ps(u.z);
    const __m128 uLen2 = _mm_set1_ps(u2), tiny = _mm_set1_ps(kCoincident2);
    const __m128 zero = _mm_setzero_ps(), alpha = _mm_set1_ps(job.alphaTilde);
    const __m128 signBit = _mm_set1_ps(-0.0f);
    float* pf = &base[0].x.x;
    const int delta4 = 4 * job.delta;
    int q = 0;
    for (; q + 4 <= job.count; q += 4) {
        float* a0 = pf + 4 * job.cols[q];
        float* a1 = pf + 4 * job.cols[q + 1];
        float* a2 = pf + 4 * job.cols[q + 2];
        float* a3 = pf + 4 * job.cols[q + 3];
        __m128 ax = _mm_load_ps(a0), ay = _mm_load_ps(a1), az = _mm_load_ps(a2), aw = _mm_load_ps(a3);
        __m128 bx = _mm_load_ps(a0 + delta4), by = _mm_load_ps(a1 + delta4);
        __m128 bz = _mm_load_ps(a2 + delta4), bw = _mm_load_ps(a3 + delta4);
        transpose(ax, ay, az, aw);
        transpose(bx, by, bz, bw);
        uint32_t on4;
        std::memcpy(&on4, job.on + q, 4);
        const __m128i onBytes = _mm_cvtsi32_si128(int(on4));
        const __m128i onWords = _mm_unpacklo_epi16(_mm_unpacklo_epi8(onBytes, _mm_setzero_si128()),
                                                   _mm_setzero_si128());
        const __m128 wsum = _mm_add_ps(aw, bw);
        const __m128 ok = _mm_and_ps(_mm_cmpgt_ps(wsum, zero),
                                     _mm_castsi128_ps(_mm_cmpgt_epi32(onWords, _mm_setzero_si128())));
        __m128 dx = _mm_sub_ps(bx, ax), dy = _mm_sub_ps(by, ay), dz = _mm_sub_ps(bz, az);
        __m128 len2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
        const __m128 coincident = _mm_cmplt_ps(len2, tiny);
        if (_mm_movemask_ps(coincident)) {
            dx = select(coincident, ux, dx);
            dy = select(coincident, uy, dy);
            dz = select(coincident, uz, dz);
            len2 = select(coincident, uLen2, len2);
        }
        const __m128 len = _mm_sqrt_ps(len2);
        const __m128 negC = _mm_xor_ps(_mm_sub_ps(len, _mm_loadu_ps(job.rest + q)), signBit);
        __m128 dl;
        if (Compliant) {
            const __m128 lam = _mm_loadu_ps(job.lambda + q);
            dl = _mm_div_ps(_mm_sub_ps(negC, _mm_mul_ps(alpha, lam)), _mm_add_ps(wsum, alpha));
            dl = _mm_and_ps(ok, dl);
            _mm_storeu_ps(job.lambda + q, select(ok, _mm_add_ps(lam, dl), lam));
        } else {
            dl = _mm_and_ps(ok, _mm_div_ps(negC, wsum));
        }
        const __m128 s = _mm_div_ps(dl, len);
        const __m128 cx = _mm_mul_ps(dx, s), cy = _mm_mul_ps(dy, s), cz = _mm_mul_ps(dz, s);
        ax = _mm_sub_ps(ax, _mm_mul_ps(aw, cx));
        ay = _mm_sub_ps(ay, _mm_mul_ps(aw, cy));
        az = _mm_sub_ps(az, _mm_mul_ps(aw, cz));
        bx = _mm_add_ps(bx, _mm_mul_ps(bw, cx));
        by = _mm_add_ps(by, _mm_mul_ps(bw, cy));
        bz = _mm_add_ps(bz, _mm_mul_ps(bw, cz));
        transpose(ax, ay, az, aw);
        transpose(bx, by, bz, bw);
        _mm_store_ps(a0, ax);
        _mm_store_ps(a1, ay);
        _mm_store_ps(a2, az);
        _mm_store_ps(a3, aw);
        _mm_store_ps(a0 + delta4, bx);
        _mm_store_ps(a1 + delta4, by);
        _mm_store_ps(a2 + delta4, bz);
        _mm_store_ps(a3 + delta4, bw);
    }
    scalarRange<Compliant>(base, job, q);
}

#endif

} // namespace

void projectRowScalar(Particle* base, const RowJob& job) {
    if (job.alphaTilde == 0.0f) scalarRange<false>(base, job, 0);
    else scalarRange<true>(base, job, 0);
}

void projectRow(Particle* base, const RowJob& job) {
#ifdef WEFT_CLOTH_SSE
    if (job.alphaTilde == 0.0f) simdRows<false>(base, job);
    else simdRows<true>(base, job);
#else
    projectRowScalar(base, job);
#endif
}

} // namespace weft::cloth
