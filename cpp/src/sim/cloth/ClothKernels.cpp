#include "sim/cloth/ClothKernels.h"

#include <cmath>
#include <cstring>

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#define WEFT_CLOTH_X86 1
#if defined(__GNUC__)
#define WEFT_AVX __attribute__((target("avx")))
// The SIMD body is inlined into its AVX or SSE caller and compiled with that caller's target,
// so no AVX value crosses a call between code with and without AVX (GCC warns that it would).
#define WEFT_FLATTEN inline __attribute__((always_inline))
#pragma GCC diagnostic ignored "-Wpsabi"
#else
#define WEFT_AVX
#define WEFT_FLATTEN inline
#endif
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
    float scale; // dl / len
    if (Compliant) {
        const float dl = (-C - alphaTilde * lambda) / (wsum + alphaTilde);
        lambda += dl;
        scale = dl / len;
    } else {
        scale = -C / (wsum * len); // one division instead of two (dl = -C / wsum)
    }
    const glm::vec3 corr = d * scale;
    A.x -= A.w * corr;
    B.x += B.w * corr;
}

template <bool Compliant>
void scalarRange(Particle* ps, const BatchJob& job, int q0) {
    for (int q = q0; q < job.count; ++q) {
        if (!job.on[q]) continue;
        Particle* a = ps + job.a[q];
        projectOne<Compliant>(a[0], a[job.delta], job.rest[q], job.alphaTilde, job.lambda[q],
                              job.restOffset);
    }
}

void scalarTethers(Particle* ps, const TetherJob& job, int k0) {
    for (int k = k0; k < job.end; ++k) {
        Particle& p = ps[k];
        if (p.w == 0.0f) continue;
        for (int s = 0; s < job.slots; ++s) {
            const size_t t = size_t(s) * size_t(job.n) + size_t(k);
            const float length = job.length[t];
            const glm::vec3 anchor = ps[job.anchor[t]].x;
            const glm::vec3 d = p.x - anchor;
            const float len2 = glm::dot(d, d);
            if (len2 > length * length) p.x = anchor + d * (length / std::sqrt(len2));
        }
    }
}

// The Verlet update of one free particle: stores x_prev and returns the new position, one
// register of x, y, z, w at a time for the SIMD version.
template <bool Windy>
inline glm::vec3 acceleration(const IntegrateJob& job, int k) {
    glm::vec3 a = job.gravity;
    if (Windy) {
        const glm::vec3 nn(job.normals[k]);
        a += job.windStrength * glm::dot(nn, job.windDirection) * nn;
    }
    return a * (job.h * job.h);
}

// Returns whether particle k is fixed (inverse mass 0), after doing what a fixed one needs.
inline bool fixedParticle(const Particle& p, Particle& prev, const IntegrateJob& job, int k) {
    if (p.w != 0.0f) return false;
    if (job.pinned[k] && !job.hole[k]) prev.x = p.x; // pinned: no velocity; grabbed: keep it
    return true;
}

template <bool Windy>
void scalarIntegrate(Particle* ps, Particle* prev, const IntegrateJob& job) {
    for (int k = job.begin; k < job.end; ++k) {
        if (fixedParticle(ps[k], prev[k], job, k)) continue;
        const glm::vec3 x = ps[k].x;
        ps[k].x = x + job.damping * (x - prev[k].x) + acceleration<Windy>(job, k);
        prev[k].x = x;
    }
}

template <bool Windy>
void scalarIntegrateToSoa(const Particle* ps, Particle* prev, const IntegrateJob& job,
                          const SoaParticles& s, const int* slot) {
    for (int k = job.begin; k < job.end; ++k) {
        const Particle p = ps[k];
        const int q = slot[k];
        s.w[q] = p.w;
        glm::vec3 next = p.x;
        if (p.w == 0.0f) {
            if (job.pinned[k] && !job.hole[k]) prev[k].x = p.x;
        } else {
            next = p.x + job.damping * (p.x - prev[k].x) + acceleration<Windy>(job, k);
            prev[k].x = p.x;
        }
        s.x[q] = next.x;
        s.y[q] = next.y;
        s.z[q] = next.z;
    }
}

#ifdef WEFT_CLOTH_X86

inline __m128 select(__m128 mask, __m128 a, __m128 b) {
    return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b));
}

template <bool Windy>
void sseIntegrate(Particle* ps, Particle* prev, const IntegrateJob& job) {
    const __m128 damping = _mm_set1_ps(job.damping);
    const __m128 xyz = _mm_castsi128_ps(_mm_set_epi32(0, -1, -1, -1));
    const glm::vec3 g = acceleration<false>(job, 0);
    __m128 a = _mm_set_ps(0.0f, g.z, g.y, g.x);
    for (int k = job.begin; k < job.end; ++k) {
        if (fixedParticle(ps[k], prev[k], job, k)) continue;
        if (Windy) {
            const glm::vec3 ak = acceleration<true>(job, k);
            a = _mm_set_ps(0.0f, ak.z, ak.y, ak.x);
        }
        float* xp = &ps[k].x.x;
        float* pp = &prev[k].x.x;
        const __m128 x = _mm_load_ps(xp);
        const __m128 next = _mm_add_ps(_mm_add_ps(x, _mm_mul_ps(damping, _mm_sub_ps(x, _mm_load_ps(pp)))), a);
        _mm_store_ps(xp, select(xyz, next, x)); // w stays
        _mm_store_ps(pp, x);
    }
}

// The SIMD kernels below are one template over a register type V: the operations of
// projectOne, lane by lane. Lanes that projectOne would skip get a zero correction, which
// leaves their positions unchanged.

// Four records (x, y, z, w) <-> four registers of x, of y, of z, of w.
inline void transpose(__m128& r0, __m128& r1, __m128& r2, __m128& r3) {
    const __m128 t0 = _mm_unpacklo_ps(r0, r1), t1 = _mm_unpacklo_ps(r2, r3);
    const __m128 t2 = _mm_unpackhi_ps(r0, r1), t3 = _mm_unpackhi_ps(r2, r3);
    r0 = _mm_movelh_ps(t0, t1);
    r1 = _mm_movehl_ps(t1, t0);
    r2 = _mm_movelh_ps(t2, t3);
    r3 = _mm_movehl_ps(t3, t2);
}

struct Sse {
    using V = __m128;
    static constexpr int kWidth = 4;
    static V set1(float v) { return _mm_set1_ps(v); }
    static V zero() { return _mm_setzero_ps(); }
    static V add(V a, V b) { return _mm_add_ps(a, b); }
    static V sub(V a, V b) { return _mm_sub_ps(a, b); }
    static V mul(V a, V b) { return _mm_mul_ps(a, b); }
    static V div(V a, V b) { return _mm_div_ps(a, b); }
    static V sqrt(V a) { return _mm_sqrt_ps(a); }
    static V andv(V a, V b) { return _mm_and_ps(a, b); }
    static V xorv(V a, V b) { return _mm_xor_ps(a, b); }
    static V lt(V a, V b) { return _mm_cmplt_ps(a, b); }
    static V gt(V a, V b) { return _mm_cmpgt_ps(a, b); }
    static V ne(V a, V b) { return _mm_cmpneq_ps(a, b); }
    static V sel(V m, V a, V b) { return select(m, a, b); }
    static bool any(V m) { return _mm_movemask_ps(m) != 0; }
    static V load(const float* p) { return _mm_loadu_ps(p); }
    static void store(float* p, V v) { _mm_storeu_ps(p, v); }
    // All-ones lanes where on[q] != 0.
    static V active(const uint8_t* on) {
        uint32_t bytes;
        std::memcpy(&bytes, on, 4);
        const __m128i z = _mm_setzero_si128();
        const __m128i words = _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(int(bytes)), z), z);
        return _mm_castsi128_ps(_mm_cmpgt_epi32(words, z));
    }
    // Records p[0..3] -> x, y, z, w registers, and back.
    static void gather(float* const* p, V& x, V& y, V& z, V& w) {
        x = _mm_load_ps(p[0]);
        y = _mm_load_ps(p[1]);
        z = _mm_load_ps(p[2]);
        w = _mm_load_ps(p[3]);
        transpose(x, y, z, w);
    }
    static void scatter(float* const* p, V x, V y, V z, V w) {
        transpose(x, y, z, w);
        _mm_store_ps(p[0], x);
        _mm_store_ps(p[1], y);
        _mm_store_ps(p[2], z);
        _mm_store_ps(p[3], w);
    }
};

struct Avx {
    using V = __m256;
    static constexpr int kWidth = 8;
    WEFT_AVX static V set1(float v) { return _mm256_set1_ps(v); }
    WEFT_AVX static V zero() { return _mm256_setzero_ps(); }
    WEFT_AVX static V add(V a, V b) { return _mm256_add_ps(a, b); }
    WEFT_AVX static V sub(V a, V b) { return _mm256_sub_ps(a, b); }
    WEFT_AVX static V mul(V a, V b) { return _mm256_mul_ps(a, b); }
    WEFT_AVX static V div(V a, V b) { return _mm256_div_ps(a, b); }
    WEFT_AVX static V sqrt(V a) { return _mm256_sqrt_ps(a); }
    WEFT_AVX static V andv(V a, V b) { return _mm256_and_ps(a, b); }
    WEFT_AVX static V xorv(V a, V b) { return _mm256_xor_ps(a, b); }
    WEFT_AVX static V lt(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_LT_OQ); }
    WEFT_AVX static V gt(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_GT_OQ); }
    WEFT_AVX static V ne(V a, V b) { return _mm256_cmp_ps(a, b, _CMP_NEQ_UQ); }
    WEFT_AVX static V sel(V m, V a, V b) { return _mm256_blendv_ps(b, a, m); }
    WEFT_AVX static bool any(V m) { return _mm256_movemask_ps(m) != 0; }
    WEFT_AVX static V load(const float* p) { return _mm256_loadu_ps(p); }
    WEFT_AVX static void store(float* p, V v) { _mm256_storeu_ps(p, v); }
    WEFT_AVX static V active(const uint8_t* on) {
        return _mm256_set_m128(Sse::active(on + 4), Sse::active(on));
    }
    // Records p[0..7]: lane k of the low half from p[k], of the high half from p[k + 4]; the
    // in-lane 4 x 4 transpose then gives x = (x0 .. x7) and so on.
    WEFT_AVX static void transpose8(V& r0, V& r1, V& r2, V& r3) {
        const V t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpacklo_ps(r2, r3);
        const V t2 = _mm256_unpackhi_ps(r0, r1), t3 = _mm256_unpackhi_ps(r2, r3);
        r0 = _mm256_shuffle_ps(t0, t1, 0x44);
        r1 = _mm256_shuffle_ps(t0, t1, 0xEE);
        r2 = _mm256_shuffle_ps(t2, t3, 0x44);
        r3 = _mm256_shuffle_ps(t2, t3, 0xEE);
    }
    WEFT_AVX static V pair(const float* lo, const float* hi) {
        return _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps(lo)), _mm_load_ps(hi), 1);
    }
    WEFT_AVX static void unpair(V v, float* lo, float* hi) {
        _mm_store_ps(lo, _mm256_castps256_ps128(v));
        _mm_store_ps(hi, _mm256_extractf128_ps(v, 1));
    }
    WEFT_AVX static void gather(float* const* p, V& x, V& y, V& z, V& w) {
        x = pair(p[0], p[4]);
        y = pair(p[1], p[5]);
        z = pair(p[2], p[6]);
        w = pair(p[3], p[7]);
        transpose8(x, y, z, w);
    }
    WEFT_AVX static void scatter(float* const* p, V x, V y, V z, V w) {
        transpose8(x, y, z, w);
        unpair(x, p[0], p[4]);
        unpair(y, p[1], p[5]);
        unpair(z, p[2], p[6]);
        unpair(w, p[3], p[7]);
    }
};

template <class S, bool Compliant>
WEFT_FLATTEN int simdRange(Particle* ps, const BatchJob& job) {
    using V = typename S::V;
    constexpr int W = S::kWidth;
    const glm::vec3 u = job.restOffset * kUnfold;
    const V ux = S::set1(u.x), uy = S::set1(u.y), uz = S::set1(u.z);
    const V uLen2 = S::set1(glm::dot(u, u)), tiny = S::set1(kCoincident2);
    const V zero = S::zero(), alpha = S::set1(job.alphaTilde), signBit = S::set1(-0.0f);
    float* pf = &ps[0].x.x;
    const int delta4 = 4 * job.delta;
    int q = 0;
    for (; q + W <= job.count; q += W) {
        float* pa[W];
        float* pb[W];
        for (int k = 0; k < W; ++k) {
            pa[k] = pf + 4 * job.a[q + k];
            pb[k] = pa[k] + delta4;
        }
        V ax, ay, az, aw, bx, by, bz, bw;
        S::gather(pa, ax, ay, az, aw);
        S::gather(pb, bx, by, bz, bw);
        const V wsum = S::add(aw, bw);
        const V ok = S::andv(S::gt(wsum, zero), S::active(job.on + q));
        V dx = S::sub(bx, ax), dy = S::sub(by, ay), dz = S::sub(bz, az);
        V len2 = S::add(S::add(S::mul(dx, dx), S::mul(dy, dy)), S::mul(dz, dz));
        const V coincident = S::lt(len2, tiny);
        if (S::any(coincident)) {
            dx = S::sel(coincident, ux, dx);
            dy = S::sel(coincident, uy, dy);
            dz = S::sel(coincident, uz, dz);
            len2 = S::sel(coincident, uLen2, len2);
        }
        const V len = S::sqrt(len2);
        const V negC = S::xorv(S::sub(len, S::load(job.rest + q)), signBit);
        V s; // dl / len
        if (Compliant) {
            const V lam = S::load(job.lambda + q);
            const V dl = S::andv(ok, S::div(S::sub(negC, S::mul(alpha, lam)), S::add(wsum, alpha)));
            S::store(job.lambda + q, S::sel(ok, S::add(lam, dl), lam));
            s = S::div(dl, len);
        } else {
            s = S::andv(ok, S::div(negC, S::mul(wsum, len)));
        }
        const V cx = S::mul(dx, s), cy = S::mul(dy, s), cz = S::mul(dz, s);
        S::scatter(pa, S::sub(ax, S::mul(aw, cx)), S::sub(ay, S::mul(aw, cy)),
                   S::sub(az, S::mul(aw, cz)), aw);
        S::scatter(pb, S::add(bx, S::mul(bw, cx)), S::add(by, S::mul(bw, cy)),
                   S::add(bz, S::mul(bw, cz)), bw);
    }
    return q;
}

// The operations of scalarTethers, lane by lane; returns the first particle left over.
template <class S>
WEFT_FLATTEN int simdTethers(Particle* ps, const TetherJob& job) {
    using V = typename S::V;
    constexpr int W = S::kWidth;
    float* pf = &ps[0].x.x;
    const V zero = S::zero();
    int k = job.begin;
    for (; k + W <= job.end; k += W) {
        float* pk[W];
        for (int l = 0; l < W; ++l) pk[l] = pf + 4 * (k + l);
        V x, y, z, w;
        S::gather(pk, x, y, z, w);
        const V free = S::ne(w, zero);
        for (int s = 0; s < job.slots; ++s) {
            const size_t t = size_t(s) * size_t(job.n) + size_t(k);
            float* pa[W];
            for (int l = 0; l < W; ++l) pa[l] = pf + 4 * job.anchor[t + size_t(l)];
            V ax, ay, az, aw;
            S::gather(pa, ax, ay, az, aw);
            const V length = S::load(job.length + t);
            const V dx = S::sub(x, ax), dy = S::sub(y, ay), dz = S::sub(z, az);
            const V len2 = S::add(S::add(S::mul(dx, dx), S::mul(dy, dy)), S::mul(dz, dz));
            const V pull = S::andv(free, S::gt(len2, S::mul(length, length)));
            if (!S::any(pull)) continue;
            const V scale = S::div(length, S::sqrt(len2));
            x = S::sel(pull, S::add(ax, S::mul(dx, scale)), x);
            y = S::sel(pull, S::add(ay, S::mul(dy, scale)), y);
            z = S::sel(pull, S::add(az, S::mul(dz, scale)), z);
        }
        S::scatter(pk, x, y, z, w);
    }
    return k;
}

template <bool Compliant>
void sseRange(Particle* ps, const BatchJob& job) {
    scalarRange<Compliant>(ps, job, simdRange<Sse, Compliant>(ps, job));
}

template <bool Compliant>
WEFT_AVX void avxRange(Particle* ps, const BatchJob& job) {
    int q = simdRange<Avx, Compliant>(ps, job);
    BatchJob rest = job; // the last 4..7: one SSE group first
    rest.a += q;
    rest.rest += q;
    rest.on += q;
    rest.lambda += q;
    rest.count -= q;
    sseRange<Compliant>(ps, rest);
}

void sseTethers(Particle* ps, const TetherJob& job) {
    scalarTethers(ps, job, simdTethers<Sse>(ps, job));
}

WEFT_AVX void avxTethers(Particle* ps, const TetherJob& job) {
    TetherJob rest = job;
    rest.begin = simdTethers<Avx>(ps, job);
    sseTethers(ps, rest);
}

#endif

#if defined(WEFT_CLOTH_X86) && defined(__GNUC__)
#define WEFT_CLOTH_AVX512 1
// AVX-512F implies FMA for GCC: no contraction, or a * b + c would round once instead of twice.
#define WEFT_AVX512 __attribute__((target("avx512f"), optimize("fp-contract=off")))

// The SoA kernels: 16 slots per vector, masked loads and stores, so only the particles of
// active constraints are read and written (no shuffles, no scatter). The float operations per
// constraint are those of projectOne / scalarTethers in the same order.

// Projects the constraints of the slots [begin, begin + count) of a batch (b = a + d).
template <bool Compliant>
WEFT_AVX512 void denseRun(const SoaParticles& p, const DenseBatchJob& job, ptrdiff_t begin,
                          int count, ptrdiff_t d) {
    const glm::vec3 u = job.restOffset * kUnfold;
    const __m512 ux = _mm512_set1_ps(u.x), uy = _mm512_set1_ps(u.y), uz = _mm512_set1_ps(u.z);
    const __m512 uLen2 = _mm512_set1_ps(glm::dot(u, u)), tiny = _mm512_set1_ps(kCoincident2);
    const __m512 zero = _mm512_setzero_ps(), alpha = _mm512_set1_ps(job.alphaTilde);
    const __m512i signBit = _mm512_set1_epi32(int(0x80000000u));
    for (int i = 0; i < count; i += 16) {
        const __mmask16 inRow = count - i >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (count - i)) - 1u);
        const ptrdiff_t a = begin + i;
        const __m512 rest = _mm512_maskz_loadu_ps(inRow, job.rest + a);
        __mmask16 ok = _mm512_mask_cmp_ps_mask(inRow, rest, zero, _CMP_GE_OQ);
        if (!ok) continue;
        const __m512 aw = _mm512_maskz_loadu_ps(ok, p.w + a);
        const __m512 bw = _mm512_maskz_loadu_ps(ok, p.w + a + d);
        const __m512 wsum = _mm512_add_ps(aw, bw);
        ok = _mm512_mask_cmp_ps_mask(ok, wsum, zero, _CMP_GT_OQ);
        if (!ok) continue;
        const __m512 ax = _mm512_maskz_loadu_ps(ok, p.x + a), bx = _mm512_maskz_loadu_ps(ok, p.x + a + d);
        const __m512 ay = _mm512_maskz_loadu_ps(ok, p.y + a), by = _mm512_maskz_loadu_ps(ok, p.y + a + d);
        const __m512 az = _mm512_maskz_loadu_ps(ok, p.z + a), bz = _mm512_maskz_loadu_ps(ok, p.z + a + d);
        __m512 dx = _mm512_sub_ps(bx, ax), dy = _mm512_sub_ps(by, ay), dz = _mm512_sub_ps(bz, az);
        __m512 len2 = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)),
                                    _mm512_mul_ps(dz, dz));
        const __mmask16 coincident = _mm512_mask_cmp_ps_mask(ok, len2, tiny, _CMP_LT_OQ);
        if (coincident) {
            dx = _mm512_mask_mov_ps(dx, coincident, ux);
            dy = _mm512_mask_mov_ps(dy, coincident, uy);
            dz = _mm512_mask_mov_ps(dz, coincident, uz);
            len2 = _mm512_mask_mov_ps(len2, coincident, uLen2);
        }
        const __m512 len = _mm512_sqrt_ps(len2);
        const __m512 negC = _mm512_castsi512_ps(
            _mm512_xor_si512(_mm512_castps_si512(_mm512_sub_ps(len, rest)), signBit));
        __m512 s; // dl / len
        if (Compliant) {
            const __m512 lam = _mm512_maskz_loadu_ps(ok, job.lambda + a);
            const __m512 dl = _mm512_div_ps(_mm512_sub_ps(negC, _mm512_mul_ps(alpha, lam)),
                                            _mm512_add_ps(wsum, alpha));
            _mm512_mask_storeu_ps(job.lambda + a, ok, _mm512_add_ps(lam, dl));
            s = _mm512_div_ps(dl, len);
        } else {
            s = _mm512_div_ps(negC, _mm512_mul_ps(wsum, len));
        }
        const __m512 cx = _mm512_mul_ps(dx, s), cy = _mm512_mul_ps(dy, s), cz = _mm512_mul_ps(dz, s);
        _mm512_mask_storeu_ps(p.x + a, ok, _mm512_sub_ps(ax, _mm512_mul_ps(aw, cx)));
        _mm512_mask_storeu_ps(p.y + a, ok, _mm512_sub_ps(ay, _mm512_mul_ps(aw, cy)));
        _mm512_mask_storeu_ps(p.z + a, ok, _mm512_sub_ps(az, _mm512_mul_ps(aw, cz)));
        _mm512_mask_storeu_ps(p.x + a + d, ok, _mm512_add_ps(bx, _mm512_mul_ps(bw, cx)));
        _mm512_mask_storeu_ps(p.y + a + d, ok, _mm512_add_ps(by, _mm512_mul_ps(bw, cy)));
        _mm512_mask_storeu_ps(p.z + a + d, ok, _mm512_add_ps(bz, _mm512_mul_ps(bw, cz)));
    }
}

// A batch's runs: per class, all its rows at once, or (dx = 0 and rows of at least a vector)
// only the rows of the batch's colour.
template <bool Compliant>
WEFT_AVX512 void denseRows(const SoaParticles& p, const DenseBatchJob& job) {
    const int L = job.length;
    const bool byRow = job.colourRows > 0 && L >= 16;
    for (int g = 0; g < job.segmentCount; ++g) {
        const DenseSegment& seg = job.segments[g];
        if (!byRow) {
            denseRun<Compliant>(p, job, seg.offset + ptrdiff_t(job.rowBegin) * L,
                                (job.rowEnd - job.rowBegin) * L, seg.delta);
            continue;
        }
        for (int j = job.rowBegin; j < job.rowEnd; ++j)
            if ((j / job.colourRows) % 2 == job.parity)
                denseRun<Compliant>(p, job, seg.offset + ptrdiff_t(j) * L, L, seg.delta);
    }
}

template <bool Table>
WEFT_AVX512 void tethersSoa(const SoaParticles& p, const SoaTetherJob& tj) {
    const TetherJob& job = tj.tethers;
    const __m512 zero = _mm512_setzero_ps();
    __m512 tx = zero, ty = zero, tz = zero; // the anchors' positions, when Table
    if (Table) {
        alignas(64) float bx[16] = {}, by[16] = {}, bz[16] = {};
        for (int e = 0; e < tj.tableSize; ++e) {
            bx[e] = p.x[tj.table[e]];
            by[e] = p.y[tj.table[e]];
            bz[e] = p.z[tj.table[e]];
        }
        tx = _mm512_load_ps(bx);
        ty = _mm512_load_ps(by);
        tz = _mm512_load_ps(bz);
    }
    for (int k = job.begin; k < job.end; k += 16) {
        const __mmask16 in = job.end - k >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (job.end - k)) - 1u);
        const __m512 w = _mm512_maskz_loadu_ps(in, p.w + k);
        const __mmask16 free = _mm512_mask_cmp_ps_mask(in, w, zero, _CMP_NEQ_UQ);
        if (!free) continue;
        __m512 x = _mm512_maskz_loadu_ps(free, p.x + k);
        __m512 y = _mm512_maskz_loadu_ps(free, p.y + k);
        __m512 z = _mm512_maskz_loadu_ps(free, p.z + k);
        for (int s = 0; s < job.slots; ++s) {
            const size_t t = size_t(s) * size_t(job.n) + size_t(k);
            const __m512i idx = _mm512_maskz_loadu_epi32(free, job.anchor + t);
            __m512 ax, ay, az;
            if (Table) {
                ax = _mm512_permutexvar_ps(idx, tx);
                ay = _mm512_permutexvar_ps(idx, ty);
                az = _mm512_permutexvar_ps(idx, tz);
            } else {
                ax = _mm512_mask_i32gather_ps(zero, free, idx, p.x, 4);
                ay = _mm512_mask_i32gather_ps(zero, free, idx, p.y, 4);
                az = _mm512_mask_i32gather_ps(zero, free, idx, p.z, 4);
            }
            const __m512 length = _mm512_maskz_loadu_ps(free, job.length + t);
            const __m512 dx = _mm512_sub_ps(x, ax), dy = _mm512_sub_ps(y, ay), dz = _mm512_sub_ps(z, az);
            const __m512 len2 = _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)),
                                              _mm512_mul_ps(dz, dz));
            const __mmask16 pull = _mm512_mask_cmp_ps_mask(free, len2, _mm512_mul_ps(length, length), _CMP_GT_OQ);
            if (!pull) continue;
            const __m512 scale = _mm512_div_ps(length, _mm512_sqrt_ps(len2));
            x = _mm512_mask_mov_ps(x, pull, _mm512_add_ps(ax, _mm512_mul_ps(dx, scale)));
            y = _mm512_mask_mov_ps(y, pull, _mm512_add_ps(ay, _mm512_mul_ps(dy, scale)));
            z = _mm512_mask_mov_ps(z, pull, _mm512_add_ps(az, _mm512_mul_ps(dz, scale)));
        }
        _mm512_mask_storeu_ps(p.x + k, free, x);
        _mm512_mask_storeu_ps(p.y + k, free, y);
        _mm512_mask_storeu_ps(p.z + k, free, z);
    }
}

// 16 records (x, y, z, w) in r[0..3] (4 per register) <-> x, y, z, w of the 16 particles.
WEFT_AVX512 inline void recordsToColumns(const __m512* r, __m512& X, __m512& Y, __m512& Z, __m512& W) {
    const __m512i ixy = _mm512_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25, 29);
    const __m512i izw = _mm512_setr_epi32(2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15, 19, 23, 27, 31);
    const __m512 t0 = _mm512_permutex2var_ps(r[0], ixy, r[1]); // x0..7, y0..7
    const __m512 t1 = _mm512_permutex2var_ps(r[0], izw, r[1]); // z0..7, w0..7
    const __m512 t2 = _mm512_permutex2var_ps(r[2], ixy, r[3]); // x8..15, y8..15
    const __m512 t3 = _mm512_permutex2var_ps(r[2], izw, r[3]);
    X = _mm512_shuffle_f32x4(t0, t2, 0x44);
    Y = _mm512_shuffle_f32x4(t0, t2, 0xEE);
    Z = _mm512_shuffle_f32x4(t1, t3, 0x44);
    W = _mm512_shuffle_f32x4(t1, t3, 0xEE);
}

WEFT_AVX512 inline void columnsToRecords(__m512 X, __m512 Y, __m512 Z, __m512 W, __m512* r) {
    const __m512 t0 = _mm512_shuffle_f32x4(X, Y, 0x44); // x0..7, y0..7
    const __m512 t2 = _mm512_shuffle_f32x4(X, Y, 0xEE); // x8..15, y8..15
    const __m512 t1 = _mm512_shuffle_f32x4(Z, W, 0x44);
    const __m512 t3 = _mm512_shuffle_f32x4(Z, W, 0xEE);
    const __m512i lo = _mm512_setr_epi32(0, 8, 16, 24, 1, 9, 17, 25, 2, 10, 18, 26, 3, 11, 19, 27);
    const __m512i hi = _mm512_setr_epi32(4, 12, 20, 28, 5, 13, 21, 29, 6, 14, 22, 30, 7, 15, 23, 31);
    r[0] = _mm512_permutex2var_ps(t0, lo, t1);
    r[1] = _mm512_permutex2var_ps(t0, hi, t1);
    r[2] = _mm512_permutex2var_ps(t2, lo, t3);
    r[3] = _mm512_permutex2var_ps(t2, hi, t3);
}

// Columns i .. i + 15 of a row (i a multiple of m, m dividing 16) lie in segment c = l mod m
// at index i / m + l / m: lanes grouped by segment, g = 16 / m lanes each.
struct SegmentShuffle {
    __m512i toSegments, fromSegments;
    int m, g;
    WEFT_AVX512 explicit SegmentShuffle(int m_) : m(m_), g(16 / m_) {
        alignas(64) int to[16], from[16];
        for (int l = 0; l < 16; ++l) {
            const int pos = (l % m) * g + l / m; // lane l goes to position pos
            to[pos] = l;
            from[l] = pos;
        }
        toSegments = _mm512_load_si512(to);
        fromSegments = _mm512_load_si512(from);
    }
    // v holds columns i..i+15 of the row whose column 0 is slot row; stride: slots per class.
    WEFT_AVX512 void store(float* base, ptrdiff_t row, ptrdiff_t stride, int i, __m512 v) const {
        const __m512 grouped = _mm512_permutexvar_ps(toSegments, v);
        for (int c = 0; c < m; ++c) {
            const __mmask16 lanes = __mmask16(((1u << g) - 1u) << (c * g));
            _mm512_mask_storeu_ps(base + row + ptrdiff_t(c) * stride + i / m - c * g, lanes, grouped);
        }
    }
    WEFT_AVX512 __m512 load(const float* base, ptrdiff_t row, ptrdiff_t stride, int i) const {
        __m512 grouped = _mm512_setzero_ps();
        for (int c = 0; c < m; ++c) {
            const __mmask16 lanes = __mmask16(((1u << g) - 1u) << (c * g));
            grouped = _mm512_mask_loadu_ps(grouped, lanes, base + row + ptrdiff_t(c) * stride + i / m - c * g);
        }
        return _mm512_permutexvar_ps(fromSegments, grouped);
    }
};

// Bits of the 16 bytes at p that are non-zero.
inline unsigned nonZero16(const uint8_t* p) {
    const __m128i v = _mm_loadu_si128(reinterpret_cast<const __m128i*>(p));
    return ~unsigned(_mm_movemask_epi8(_mm_cmpeq_epi8(v, _mm_setzero_si128()))) & 0xFFFFu;
}

WEFT_AVX512 void integrateRows(const Particle* ps, Particle* prev, const IntegrateJob& job,
                               const SoaParticles& s, const SoaGrid& grid, const int* slot) {
    const SegmentShuffle seg(grid.m);
    const glm::vec3 g = acceleration<false>(job, 0);
    const __m512 ax = _mm512_set1_ps(g.x), ay = _mm512_set1_ps(g.y), az = _mm512_set1_ps(g.z);
    const __m512 damping = _mm512_set1_ps(job.damping), zero = _mm512_setzero_ps();
    const ptrdiff_t stride = ptrdiff_t(grid.ny) * grid.L;
    for (int j = job.begin; j < job.end; ++j) {
        const int k0 = j * grid.nx;
        const ptrdiff_t row = ptrdiff_t(j) * grid.L;
        int i = 0;
        for (; i + 16 <= grid.nx; i += 16) {
            const int k = k0 + i;
            const float* pf = &ps[k].x.x;
            float* qf = &prev[k].x.x;
            __m512 r[4], q[4];
            for (int t = 0; t < 4; ++t) {
                r[t] = _mm512_loadu_ps(pf + 16 * t);
                q[t] = _mm512_loadu_ps(qf + 16 * t);
            }
            __m512 X, Y, Z, W, PX, PY, PZ, PW;
            recordsToColumns(r, X, Y, Z, W);
            recordsToColumns(q, PX, PY, PZ, PW);
            const __mmask16 free = _mm512_cmp_ps_mask(W, zero, _CMP_NEQ_UQ);
            const __mmask16 stay = __mmask16(nonZero16(job.pinned + k) & ~nonZero16(job.hole + k));
            const __m512 nx_ = _mm512_add_ps(_mm512_add_ps(X, _mm512_mul_ps(damping, _mm512_sub_ps(X, PX))), ax);
            const __m512 ny_ = _mm512_add_ps(_mm512_add_ps(Y, _mm512_mul_ps(damping, _mm512_sub_ps(Y, PY))), ay);
            const __m512 nz_ = _mm512_add_ps(_mm512_add_ps(Z, _mm512_mul_ps(damping, _mm512_sub_ps(Z, PZ))), az);
            const __mmask16 moved = free | stay; // x_prev becomes x
            columnsToRecords(_mm512_mask_mov_ps(PX, moved, X), _mm512_mask_mov_ps(PY, moved, Y),
                             _mm512_mask_mov_ps(PZ, moved, Z), PW, q);
            for (int t = 0; t < 4; ++t) _mm512_storeu_ps(qf + 16 * t, q[t]);
            seg.store(s.x, row, stride, i, _mm512_mask_mov_ps(X, free, nx_));
            seg.store(s.y, row, stride, i, _mm512_mask_mov_ps(Y, free, ny_));
            seg.store(s.z, row, stride, i, _mm512_mask_mov_ps(Z, free, nz_));
            seg.store(s.w, row, stride, i, W);
        }
        IntegrateJob rest = job;
        rest.begin = k0 + i;
        rest.end = k0 + grid.nx;
        scalarIntegrateToSoa<false>(ps, prev, rest, s, slot);
    }
}

WEFT_AVX512 void soaRows(const SoaParticles& s, Particle* ps, int rowBegin, int rowEnd,
                         const SoaGrid& grid, const int* slot) {
    const SegmentShuffle seg(grid.m);
    const ptrdiff_t stride = ptrdiff_t(grid.ny) * grid.L;
    for (int j = rowBegin; j < rowEnd; ++j) {
        const int k0 = j * grid.nx;
        const ptrdiff_t row = ptrdiff_t(j) * grid.L;
        int i = 0;
        for (; i + 16 <= grid.nx; i += 16) {
            __m512 r[4];
            columnsToRecords(seg.load(s.x, row, stride, i), seg.load(s.y, row, stride, i),
                             seg.load(s.z, row, stride, i), _mm512_setzero_ps(), r);
            float* pf = &ps[k0 + i].x.x;
            for (int t = 0; t < 4; ++t) _mm512_mask_storeu_ps(pf + 16 * t, 0x7777, r[t]); // w stays
        }
        for (; i < grid.nx; ++i) {
            const int q = slot[k0 + i];
            ps[k0 + i].x = glm::vec3(s.x[q], s.y[q], s.z[q]);
        }
    }
}
#endif

} // namespace

void integrateToSoa(const Particle* particles, Particle* previous, const IntegrateJob& job,
                    const SoaParticles& soa, const int* slot) {
    if (job.normals) scalarIntegrateToSoa<true>(particles, previous, job, soa, slot);
    else scalarIntegrateToSoa<false>(particles, previous, job, soa, slot);
}

void integrateRowsToSoa(const Particle* particles, Particle* previous, const IntegrateJob& job,
                        const SoaParticles& soa, const SoaGrid& grid, const int* slot) {
#ifdef WEFT_CLOTH_AVX512
    if (!job.normals && 16 % grid.m == 0 && hasSoaKernels())
        return integrateRows(particles, previous, job, soa, grid, slot);
#endif
    IntegrateJob part = job;
    part.begin = job.begin * grid.nx;
    part.end = job.end * grid.nx;
    integrateToSoa(particles, previous, part, soa, slot);
}

void soaRowsToRecords(const SoaParticles& soa, Particle* particles, int rowBegin, int rowEnd,
                      const SoaGrid& grid, const int* slot) {
#ifdef WEFT_CLOTH_AVX512
    if (16 % grid.m == 0 && hasSoaKernels()) return soaRows(soa, particles, rowBegin, rowEnd, grid, slot);
#endif
    for (int k = rowBegin * grid.nx; k < rowEnd * grid.nx; ++k) {
        const int q = slot[k];
        particles[k].x = glm::vec3(soa.x[q], soa.y[q], soa.z[q]);
    }
}

bool hasSoaKernels() {
#ifdef WEFT_CLOTH_AVX512
    static const bool has = __builtin_cpu_supports("avx512f");
    return has;
#else
    return false;
#endif
}

void projectDense(const SoaParticles& p, const DenseBatchJob& job) {
#ifdef WEFT_CLOTH_AVX512
    if (job.alphaTilde != 0.0f) denseRows<true>(p, job);
    else denseRows<false>(p, job);
#else
    (void)p;
    (void)job;
#endif
}

void projectTethersSoa(const SoaParticles& p, const SoaTetherJob& job) {
#ifdef WEFT_CLOTH_AVX512
    if (job.table) tethersSoa<true>(p, job);
    else tethersSoa<false>(p, job);
#else
    (void)p;
    (void)job;
#endif
}

Isa bestIsa() {
#ifdef WEFT_CLOTH_X86
#if defined(__GNUC__)
    static const Isa best = __builtin_cpu_supports("avx") ? Isa::Avx : Isa::Sse;
    return best;
#else
    return Isa::Sse;
#endif
#else
    return Isa::Scalar;
#endif
}

void projectBatch(Particle* particles, const BatchJob& job, Isa isa) {
    const bool compliant = job.alphaTilde != 0.0f;
    switch (isa) {
#ifdef WEFT_CLOTH_X86
    case Isa::Avx:
        return compliant ? avxRange<true>(particles, job) : avxRange<false>(particles, job);
    case Isa::Sse:
        return compliant ? sseRange<true>(particles, job) : sseRange<false>(particles, job);
#endif
    default:
        return compliant ? scalarRange<true>(particles, job, 0) : scalarRange<false>(particles, job, 0);
    }
}

void projectTethers(Particle* particles, const TetherJob& job, Isa isa) {
    switch (isa) {
#ifdef WEFT_CLOTH_X86
    case Isa::Avx:
        return avxTethers(particles, job);
    case Isa::Sse:
        return sseTethers(particles, job);
#endif
    default:
        return scalarTethers(particles, job, job.begin);
    }
}

void integrate(Particle* particles, Particle* previous, const IntegrateJob& job, Isa isa) {
    const bool windy = job.normals != nullptr;
#ifdef WEFT_CLOTH_X86
    if (isa != Isa::Scalar)
        return windy ? sseIntegrate<true>(particles, previous, job)
                     : sseIntegrate<false>(particles, previous, job);
#endif
    (void)isa;
    windy ? scalarIntegrate<true>(particles, previous, job) : scalarIntegrate<false>(particles, previous, job);
}

} // namespace weft::cloth
