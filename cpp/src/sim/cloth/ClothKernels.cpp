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

template <bool Compliant> void scalarRange(Particle* ps, const BatchJob& job, int q0) {
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

// Returns whether particle k is fixed (inverse mass 0), after doing what a fixed one needs.
inline bool fixedParticle(const Particle& p, Particle& prev, const IntegrateJob& job, int k) {
    if (p.w != 0.0f) return false;
    if (job.pinned[k] && !job.hole[k]) prev.x = p.x; // pinned: no velocity; grabbed: keep it
    return true;
}

template <bool Windy> void scalarIntegrate(Particle* ps, Particle* prev, const IntegrateJob& job) {
    for (int k = job.begin; k < job.end; ++k) {
        if (fixedParticle(ps[k], prev[k], job, k)) continue;
        const glm::vec3 x = ps[k].x;
        ps[k].x = x + job.damping * (x - prev[k].x) + acceleration<Windy>(job, k);
        prev[k].x = x;
    }
}

#ifdef WEFT_CLOTH_X86

inline __m128 select(__m128 mask, __m128 a, __m128 b) {
    return _mm_or_ps(_mm_and_ps(mask, a), _mm_andnot_ps(mask, b));
}

template <bool Windy> void sseIntegrate(Particle* ps, Particle* prev, const IntegrateJob& job) {
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
        const __m128 next =
            _mm_add_ps(_mm_add_ps(x, _mm_mul_ps(damping, _mm_sub_ps(x, _mm_load_ps(pp)))), a);
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
        const __m128i words =
            _mm_unpacklo_epi16(_mm_unpacklo_epi8(_mm_cvtsi32_si128(int(bytes)), z), z);
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

template <class S, bool Compliant> WEFT_FLATTEN int simdRange(Particle* ps, const BatchJob& job) {
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
template <class S> WEFT_FLATTEN int simdTethers(Particle* ps, const TetherJob& job) {
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

template <bool Compliant> void sseRange(Particle* ps, const BatchJob& job) {
    scalarRange<Compliant>(ps, job, simdRange<Sse, Compliant>(ps, job));
}

template <bool Compliant> WEFT_AVX void avxRange(Particle* ps, const BatchJob& job) {
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

} // namespace

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
        return compliant ? scalarRange<true>(particles, job, 0)
                         : scalarRange<false>(particles, job, 0);
    }
}

void projectTethers(Particle* particles, const TetherJob& job, Isa isa) {
    switch (isa) {
#ifdef WEFT_CLOTH_X86
    case Isa::Avx: return avxTethers(particles, job);
    case Isa::Sse: return sseTethers(particles, job);
#endif
    default: return scalarTethers(particles, job, job.begin);
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
    windy ? scalarIntegrate<true>(particles, previous, job)
          : scalarIntegrate<false>(particles, previous, job);
}

} // namespace weft::cloth
