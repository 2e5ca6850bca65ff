/* Vector helpers shared by the pair passes (density, pressure_force,
 * viscosity): AVX-512, 16 neighbours of one particle at a time, or with
 * [search] vector_avx2 = on AVX2, 8 at a time, their data gathered by index.
 * Only where the build targets them ([search] vector = on selects them at run
 * time); every pass keeps its scalar loop for other CPUs, other kernels and
 * vector = off. */
#ifndef SPH_SIMD_H
#define SPH_SIMD_H

#include <stdbool.h>
#include <stdint.h>
#include <stdlib.h>

#include "sph_memory.h"
#include "sph_sim.h"

#ifdef __AVX512F__
#include <immintrin.h>
#define SPH_HAVE_AVX512 1

/* Lanes of the block of neighbours starting at e, up to end. */
static inline __mmask16 sph_simd_live(uint32_t e, uint32_t end)
{
    uint32_t left = end - e;
    return left >= 16 ? (__mmask16)0xFFFF : (__mmask16)((1u << left) - 1);
}

/* The row's neighbours k .. k + 15 (dead lanes 0), whatever the lists' storage. */
static inline __m512i sph_simd_nbr(const sph_nbr_row *r, uint32_t k, __mmask16 live)
{
    if (r->w) return _mm512_maskz_loadu_epi32(live, r->w + k);
    if (r->o) { /* 16 offsets, sign-extended, plus i */
#if defined(__AVX512BW__) && defined(__AVX512VL__)
        const __m256i o = _mm256_maskz_loadu_epi16(live, r->o + k);
#else /* no masked 16-bit load: copy the live offsets first (never read past the row) */
        int16_t t[16] = {0};
        memcpy(t, r->o + k, (size_t)__builtin_popcount((unsigned)live) * sizeof *t);
        const __m256i o = _mm256_loadu_si256((const __m256i *)(const void *)t);
#endif
        return _mm512_maskz_add_epi32(live, _mm512_cvtepi16_epi32(o), _mm512_set1_epi32((int)r->i));
    }
    return _mm512_maskz_loadu_epi32(live, r->x + 2 * (size_t)k);
}

/* Gathers a[idx] in the live lanes (0 elsewhere). */
static inline __m512 sph_simd_gather(__mmask16 live, __m512i idx, const float *a)
{
    return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), live, idx, a, 4);
}

/* The offsets d = x_i - x_j (predicted positions; d[2] = 0 in 2D) of 16
 * neighbours and their squared length, summed in the scalar loops' order. */
static inline __m512 sph_simd_offsets(const sph_particles *P, __mmask16 live, __m512i idx, const __m512 xi[3],
                                      const int dim, __m512 d[3])
{
    d[0] = _mm512_sub_ps(xi[0], sph_simd_gather(live, idx, P->pred[0]));
    d[1] = _mm512_sub_ps(xi[1], sph_simd_gather(live, idx, P->pred[1]));
    d[2] = dim == 3 ? _mm512_sub_ps(xi[2], sph_simd_gather(live, idx, P->pred[2])) : _mm512_setzero_ps();
    __m512 r2 = _mm512_add_ps(_mm512_mul_ps(d[0], d[0]), _mm512_mul_ps(d[1], d[1]));
    return dim == 3 ? _mm512_add_ps(r2, _mm512_mul_ps(d[2], d[2])) : r2;
}

/* A particle's position broadcast to every lane (z = 0 in 2D). */
static inline void sph_simd_centre(const sph_particles *P, int i, const int dim, __m512 xi[3])
{
    for (int d = 0; d < 3; d++) xi[d] = _mm512_set1_ps(d < dim ? P->pred[d][i] : 0.0f);
}
#else
#define SPH_HAVE_AVX512 0
#endif

/* [search] vector_avx2 = on: the same loops 8 neighbours at a time in AVX2
 * (with FMA), for CPUs without AVX-512 (and to compare on those with it).
 * The masks are vectors of all-ones or all-zero lanes. */
#if defined(__AVX2__) && defined(__FMA__)
#include <immintrin.h>
#include <string.h>
#define SPH_HAVE_AVX2 1

/* Lanes of the block of neighbours starting at e, up to end. */
static inline __m256i sph_simd8_live(uint32_t e, uint32_t end)
{
    uint32_t left = end - e;
    return _mm256_cmpgt_epi32(_mm256_set1_epi32(left >= 8 ? 8 : (int)left), _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7));
}

/* The row's neighbours k .. k + 7 (dead lanes 0), whatever the lists' storage; never reads past the row. */
static inline __m256i sph_simd8_nbr(const sph_nbr_row *r, uint32_t k, uint32_t end, __m256i live)
{
    const bool full = end - k >= 8;
    if (r->w)
        return full ? _mm256_loadu_si256((const __m256i *)(const void *)(r->w + k))
                    : _mm256_maskload_epi32((const int *)(const void *)(r->w + k), live);
    if (r->o) { /* 8 offsets, sign-extended, plus i */
        __m128i o;
        if (full) {
            o = _mm_loadu_si128((const __m128i *)(const void *)(r->o + k));
        } else {
            int16_t t[8] = {0};
            memcpy(t, r->o + k, (size_t)(end - k) * sizeof *t);
            o = _mm_loadu_si128((const __m128i *)(const void *)t);
        }
        return _mm256_and_si256(live, _mm256_add_epi32(_mm256_cvtepi16_epi32(o), _mm256_set1_epi32((int)r->i)));
    }
    return _mm256_maskload_epi32((const int *)(const void *)(r->x + 2 * (size_t)k), live);
}

/* Gathers a[idx] in the live lanes (0 elsewhere). */
static inline __m256 sph_simd8_gather(__m256i live, __m256i idx, const float *a)
{
    return _mm256_mask_i32gather_ps(_mm256_setzero_ps(), a, idx, _mm256_castsi256_ps(live), 4);
}

/* The offsets d = x_i - x_j of 8 neighbours and their squared length, summed in the scalar loops' order. */
static inline __m256 sph_simd8_offsets(const sph_particles *P, __m256i live, __m256i idx, const __m256 xi[3],
                                       const int dim, __m256 d[3])
{
    d[0] = _mm256_sub_ps(xi[0], sph_simd8_gather(live, idx, P->pred[0]));
    d[1] = _mm256_sub_ps(xi[1], sph_simd8_gather(live, idx, P->pred[1]));
    d[2] = dim == 3 ? _mm256_sub_ps(xi[2], sph_simd8_gather(live, idx, P->pred[2])) : _mm256_setzero_ps();
    __m256 r2 = _mm256_add_ps(_mm256_mul_ps(d[0], d[0]), _mm256_mul_ps(d[1], d[1]));
    return dim == 3 ? _mm256_add_ps(r2, _mm256_mul_ps(d[2], d[2])) : r2;
}

static inline void sph_simd8_centre(const sph_particles *P, int i, const int dim, __m256 xi[3])
{
    for (int d = 0; d < 3; d++) xi[d] = _mm256_set1_ps(d < dim ? P->pred[d][i] : 0.0f);
}

/* The sum of the 8 lanes, always in the same order (the result is the same on any thread count). */
static inline float sph_simd8_sum(__m256 v)
{
    __m128 s = _mm_add_ps(_mm256_castps256_ps128(v), _mm256_extractf128_ps(v, 1));
    s = _mm_add_ps(s, _mm_movehl_ps(s, s));
    s = _mm_add_ss(s, _mm_movehdup_ps(s));
    return _mm_cvtss_f32(s);
}

/* a where the mask is set, b elsewhere. */
static inline __m256 sph_simd8_pick(__m256i mask, __m256 a, __m256 b)
{
    return _mm256_blendv_ps(b, a, _mm256_castsi256_ps(mask));
}

/* v where the mask is set, 0 elsewhere. */
static inline __m256 sph_simd8_keep(__m256i mask, __m256 v) { return _mm256_and_ps(_mm256_castsi256_ps(mask), v); }

/* [compute] packed_records = on: the neighbours idx as 8 indices (dead lanes
 * hold index 0: a real record, whose lanes the loops then mask). */
static inline void sph_simd8_indices(__m256i idx, uint32_t j[8])
{
    _mm256_storeu_si256((__m256i *)(void *)j, idx);
}

/* Four consecutive floats of each neighbour j[l]'s record (records of `per`
 * floats, 16-byte aligned) as 8 16-byte loads and 8 shuffles instead of 4
 * gathers: f[k] holds float k of lane l's four. Written out, not looped, so
 * that the compiler keeps everything in registers. */
/* Four floats from `off` of each of 8 records a0 .. a7 (16-byte aligned), as 8 16-byte loads and 8 shuffles instead
 * of 4 gathers: f[k] holds float k of lane l's four. Written out, not looped, so that the compiler keeps everything
 * in registers. */
SPH_INLINE void sph_simd8_rec4_at(const float *a0, const float *a1, const float *a2, const float *a3, const float *a4,
                                  const float *a5, const float *a6, const float *a7, size_t off, __m256 f[4])
{
#define SPH_REC_PAIR(p, q)                                                                                      \
    _mm256_insertf128_ps(_mm256_castps128_ps256(_mm_load_ps((p) + off)), _mm_load_ps((q) + off), 1)
    const __m256 r0 = SPH_REC_PAIR(a0, a4), r1 = SPH_REC_PAIR(a1, a5), r2 = SPH_REC_PAIR(a2, a6);
    const __m256 r3 = SPH_REC_PAIR(a3, a7);
#undef SPH_REC_PAIR
    const __m256 t0 = _mm256_unpacklo_ps(r0, r1), t1 = _mm256_unpackhi_ps(r0, r1); /* lanes 0 1 0 1 | 4 5 4 5 */
    const __m256 t2 = _mm256_unpacklo_ps(r2, r3), t3 = _mm256_unpackhi_ps(r2, r3); /* lanes 2 3 2 3 | 6 7 6 7 */
    f[0] = _mm256_shuffle_ps(t0, t2, 0x44);
    f[1] = _mm256_shuffle_ps(t0, t2, 0xEE);
    f[2] = _mm256_shuffle_ps(t1, t3, 0x44);
    f[3] = _mm256_shuffle_ps(t1, t3, 0xEE);
}

/* Four consecutive floats of each neighbour j[l]'s record (records of `per` floats, 16-byte aligned), as
 * sph_simd8_rec4_at. */
SPH_INLINE void sph_simd8_rec4(const float *rec, size_t per, const uint32_t j[8], __m256 f[4])
{
    sph_simd8_rec4_at(rec + per * j[0], rec + per * j[1], rec + per * j[2], rec + per * j[3], rec + per * j[4],
                      rec + per * j[5], rec + per * j[6], rec + per * j[7], 0, f);
}

/* sph_simd8_rec4 for 8 neighbours of a compact row (offsets j - i), in records of `per` floats, from float `off`
 * of each: the addresses come from the offsets o[0..7] read as scalars, so each record's loads wait on one 16-bit
 * load and not on a round trip of the indices through a vector register. rec_i: the row's own record. */
SPH_INLINE void sph_simd8_rec4_off_per(const float *rec_i, ptrdiff_t per, const int16_t *o, size_t off, __m256 f[4])
{
#define SPH_REC_AT(k) (rec_i + per * (ptrdiff_t)o[k])
    sph_simd8_rec4_at(SPH_REC_AT(0), SPH_REC_AT(1), SPH_REC_AT(2), SPH_REC_AT(3), SPH_REC_AT(4), SPH_REC_AT(5),
                      SPH_REC_AT(6), SPH_REC_AT(7), off, f);
#undef SPH_REC_AT
}

/* The offsets of a compact row's block of 8 from entry e: the row's own words, or for the last block (fewer than
 * 8 left) a copy in last[] whose dead lanes hold offset 0, the particle's own record, which the loops then mask. */
SPH_INLINE const int16_t *sph_simd8_block_offsets(const int16_t *o, uint32_t e, uint32_t end, int16_t last[8])
{
    o += e;
    if (end - e >= 8) return o;
#if defined(__AVX512BW__) && defined(__AVX512VL__) /* a masked load: the same words, no calls */
    _mm_storeu_si128((__m128i *)(void *)last, _mm_maskz_loadu_epi16((__mmask8)((1u << (end - e)) - 1), o));
#else
    memset(last, 0, 8 * sizeof *last);
    memcpy(last, o, (size_t)(end - e) * sizeof *last);
#endif
    return last;
}

/* The same in the force walk's records of 8 floats. */
SPH_INLINE void sph_simd8_rec4_off(const float *rec_i, const int16_t *o, size_t off, __m256 f[4])
{
    sph_simd8_rec4_off_per(rec_i, 8, o, off, f);
}
#else
#define SPH_HAVE_AVX2 0
#endif

#if SPH_HAVE_AVX512 && SPH_HAVE_AVX2
/* [compute] wide_density = on (with packed_records): density's record walk
 * takes 16 neighbours at a time. Four floats from `off` of each of 16 records of a
 * compact row's block (offsets o[0..15] from the row's own record rec_i,
 * records of `per` floats, 16-byte aligned): 16 16-byte loads gathered into
 * four registers (records l, l + 4, l + 8, l + 12 in register l) and the
 * transpose of sph_simd8_rec4_at within each 128-bit lane, so that lane l of
 * f[k] holds float k of record l. */
SPH_INLINE void sph_simd16_rec4_off(const float *rec_i, ptrdiff_t per, const int16_t *o, size_t off, __m512 f[4])
{
#define SPH_REC16_AT(k) _mm_load_ps(rec_i + per * (ptrdiff_t)o[k] + off)
#define SPH_REC16_QUAD(a, b, c, d)                                                                              \
    _mm512_insertf32x4(                                                                                        \
        _mm512_insertf32x4(_mm512_insertf32x4(_mm512_castps128_ps512(SPH_REC16_AT(a)), SPH_REC16_AT(b), 1),     \
                           SPH_REC16_AT(c), 2),                                                                \
        SPH_REC16_AT(d), 3)
    const __m512 r0 = SPH_REC16_QUAD(0, 4, 8, 12), r1 = SPH_REC16_QUAD(1, 5, 9, 13);
    const __m512 r2 = SPH_REC16_QUAD(2, 6, 10, 14), r3 = SPH_REC16_QUAD(3, 7, 11, 15);
#undef SPH_REC16_QUAD
#undef SPH_REC16_AT
    const __m512 t0 = _mm512_unpacklo_ps(r0, r1), t1 = _mm512_unpackhi_ps(r0, r1);
    const __m512 t2 = _mm512_unpacklo_ps(r2, r3), t3 = _mm512_unpackhi_ps(r2, r3);
    f[0] = _mm512_shuffle_ps(t0, t2, 0x44);
    f[1] = _mm512_shuffle_ps(t0, t2, 0xEE);
    f[2] = _mm512_shuffle_ps(t1, t3, 0x44);
    f[3] = _mm512_shuffle_ps(t1, t3, 0xEE);
}

/* The offsets of a compact row's block of 16 from entry e: the row's own
 * words, or for the last block a copy in last[] whose dead lanes hold offset
 * 0 (the particle's own record, which the loops mask). */
SPH_INLINE const int16_t *sph_simd16_block_offsets(const int16_t *o, uint32_t e, uint32_t end, int16_t last[16])
{
    o += e;
    if (end - e >= 16) return o;
#if defined(__AVX512BW__) && defined(__AVX512VL__) /* a masked load: the same words, no calls */
    _mm256_storeu_si256((__m256i *)(void *)last, _mm256_maskz_loadu_epi16((__mmask16)((1u << (end - e)) - 1), o));
#else
    memset(last, 0, 16 * sizeof *last);
    memcpy(last, o, (size_t)(end - e) * sizeof *last);
#endif
    return last;
}
#define SPH_HAVE_WIDE_RECORDS 1
#else
#define SPH_HAVE_WIDE_RECORDS 0
#endif

/* Whether a pass may use its 8-lane AVX2 loop ([search] vector_avx2 = on). */
static inline bool sph_simd8_on(const sph_sim *sim)
{
    return SPH_HAVE_AVX2 && sim->def.vector == SPH_ON && sim->def.vector_avx2 == SPH_ON &&
           sim->def.accumulate == SPH_ACC_FLOAT && !sph_sim_periodic(sim);
}

/* Whether the 8-lane loops read neighbours from packed records ([compute] packed_records = on). */
static inline bool sph_simd8_packed(const sph_sim *sim)
{
    return sph_simd8_on(sim) && sim->def.packed_records == SPH_ON;
}

/* Whether density's record walk takes 16 neighbours at a time ([compute] wide_density = on, packed records,
 * AVX-512). */
static inline bool sph_simd16_density(const sph_sim *sim)
{
    return SPH_HAVE_WIDE_RECORDS && sph_simd8_packed(sim) && sim->def.wide_density == SPH_ON;
}

/* The records' buffer, `per` floats for each particle (grown, never shrunk). */
static inline float *sph_simd8_records(sph_sim *sim, size_t per)
{
    sph_search_data *S = &sim->S;
    const size_t need = (per * (sim->n ? sim->n : 1) + 7) & ~(size_t)7; /* whole 32-byte blocks */
    if (S->rec_cap < need) {
        free(S->rec);
        S->rec = aligned_alloc(32, need * sizeof(float));
        S->rec_cap = S->rec ? need : 0;
        if (!S->rec) {
            char size[32];
            sph_memory_fail("the packed records could not be made (%s; [compute] packed_records = off needs none)",
                            sph_memory_text((double)need * sizeof(float), size, sizeof size));
        }
    }
    return S->rec;
}

/* Whether a pass may use its vector loop for this scene and kernel: the
 * 8-lane one where sph_simd8_on, else the 16-lane AVX-512 one. */
static inline bool sph_simd_on(const sph_sim *sim)
{
    return (SPH_HAVE_AVX512 || sph_simd8_on(sim)) && sim->def.vector == SPH_ON &&
           sim->def.accumulate == SPH_ACC_FLOAT && !sph_sim_periodic(sim);
}

/* Whether the pressure_force pass also computes the viscosity in its walk
 * ([compute] fuse_forces = on): both passes in the pipeline, both in the
 * forms whose vector loops exist (spiky pressure gradient, laplacian
 * viscosity with the viscosity kernel), both switched on. The viscosity
 * pass then only keeps its place; in every other case the two passes run apart. */
static inline bool sph_forces_fused(const sph_sim *sim)
{
    return sim->def.fuse_forces == SPH_ON && sph_simd_on(sim) && sim->in_pipeline[SPH_PASS_PRESSURE_FORCE] &&
           sim->enabled[SPH_PASS_PRESSURE_FORCE] && sim->in_pipeline[SPH_PASS_VISCOSITY] &&
           sim->enabled[SPH_PASS_VISCOSITY] && sim->k_pressure.kind == SPH_KERNEL_SPIKY &&
           sim->k_viscosity.kind == SPH_KERNEL_VISCOSITY && sim->def.viscosity_form == SPH_VFORM_LAPLACIAN;
}

#endif
