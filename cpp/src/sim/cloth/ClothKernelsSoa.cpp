// The relaxation on CPUs with AVX-512 in the structure-of-arrays layout (SoaParticles,
// ClothKernels.h): dense batches, tethers, the Verlet step written straight into the SoA slots and
// the copy back to the records. Bit-identical to the record kernels of ClothKernels.cpp.
#include "sim/cloth/ClothKernels.h"

#include <cstring>

#if defined(__x86_64__) || defined(_M_X64)
#include <immintrin.h>
#define WEFT_CLOTH_X86 1
#if defined(__GNUC__)
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
#endif

namespace weft::cloth {

namespace {

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
        const __mmask16 inRow =
            count - i >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (count - i)) - 1u);
        const ptrdiff_t a = begin + i;
        const __m512 rest = _mm512_maskz_loadu_ps(inRow, job.rest + a);
        __mmask16 ok = _mm512_mask_cmp_ps_mask(inRow, rest, zero, _CMP_GE_OQ);
        if (!ok) continue;
        const __m512 aw = _mm512_maskz_loadu_ps(ok, p.w + a);
        const __m512 bw = _mm512_maskz_loadu_ps(ok, p.w + a + d);
        const __m512 wsum = _mm512_add_ps(aw, bw);
        ok = _mm512_mask_cmp_ps_mask(ok, wsum, zero, _CMP_GT_OQ);
        if (!ok) continue;
        const __m512 ax = _mm512_maskz_loadu_ps(ok, p.x + a),
                     bx = _mm512_maskz_loadu_ps(ok, p.x + a + d);
        const __m512 ay = _mm512_maskz_loadu_ps(ok, p.y + a),
                     by = _mm512_maskz_loadu_ps(ok, p.y + a + d);
        const __m512 az = _mm512_maskz_loadu_ps(ok, p.z + a),
                     bz = _mm512_maskz_loadu_ps(ok, p.z + a + d);
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
        const __m512 cx = _mm512_mul_ps(dx, s), cy = _mm512_mul_ps(dy, s),
                     cz = _mm512_mul_ps(dz, s);
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

template <bool Table> WEFT_AVX512 void tethersSoa(const SoaParticles& p, const SoaTetherJob& tj) {
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
        const __mmask16 in =
            job.end - k >= 16 ? __mmask16(0xFFFF) : __mmask16((1u << (job.end - k)) - 1u);
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
            const __m512 dx = _mm512_sub_ps(x, ax), dy = _mm512_sub_ps(y, ay),
                         dz = _mm512_sub_ps(z, az);
            const __m512 len2 = _mm512_add_ps(
                _mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)), _mm512_mul_ps(dz, dz));
            const __mmask16 pull =
                _mm512_mask_cmp_ps_mask(free, len2, _mm512_mul_ps(length, length), _CMP_GT_OQ);
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
WEFT_AVX512 inline void recordsToColumns(const __m512* r, __m512& X, __m512& Y, __m512& Z,
                                         __m512& W) {
    const __m512i ixy = _mm512_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28, 1, 5, 9, 13, 17, 21, 25, 29);
    const __m512i izw =
        _mm512_setr_epi32(2, 6, 10, 14, 18, 22, 26, 30, 3, 7, 11, 15, 19, 23, 27, 31);
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
    const __m512i hi =
        _mm512_setr_epi32(4, 12, 20, 28, 5, 13, 21, 29, 6, 14, 22, 30, 7, 15, 23, 31);
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
            _mm512_mask_storeu_ps(base + row + ptrdiff_t(c) * stride + i / m - c * g, lanes,
                                  grouped);
        }
    }
    WEFT_AVX512 __m512 load(const float* base, ptrdiff_t row, ptrdiff_t stride, int i) const {
        __m512 grouped = _mm512_setzero_ps();
        for (int c = 0; c < m; ++c) {
            const __mmask16 lanes = __mmask16(((1u << g) - 1u) << (c * g));
            grouped = _mm512_mask_loadu_ps(grouped, lanes,
                                           base + row + ptrdiff_t(c) * stride + i / m - c * g);
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
            const __m512 nx_ =
                _mm512_add_ps(_mm512_add_ps(X, _mm512_mul_ps(damping, _mm512_sub_ps(X, PX))), ax);
            const __m512 ny_ =
                _mm512_add_ps(_mm512_add_ps(Y, _mm512_mul_ps(damping, _mm512_sub_ps(Y, PY))), ay);
            const __m512 nz_ =
                _mm512_add_ps(_mm512_add_ps(Z, _mm512_mul_ps(damping, _mm512_sub_ps(Z, PZ))), az);
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
    if (job.normals)
        scalarIntegrateToSoa<true>(particles, previous, job, soa, slot);
    else
        scalarIntegrateToSoa<false>(particles, previous, job, soa, slot);
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
    if (16 % grid.m == 0 && hasSoaKernels())
        return soaRows(soa, particles, rowBegin, rowEnd, grid, slot);
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
    if (job.alphaTilde != 0.0f)
        denseRows<true>(p, job);
    else
        denseRows<false>(p, job);
#else
    (void)p;
    (void)job;
#endif
}

void projectTethersSoa(const SoaParticles& p, const SoaTetherJob& job) {
#ifdef WEFT_CLOTH_AVX512
    if (job.table)
        tethersSoa<true>(p, job);
    else
        tethersSoa<false>(p, job);
#else
    (void)p;
    (void)job;
#endif
}

} // namespace weft::cloth
