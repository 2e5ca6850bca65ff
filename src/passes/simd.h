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
#else
#define SPH_HAVE_AVX2 0
#endif

/* Whether a pass may use its 8-lane AVX2 loop ([search] vector_avx2 = on). */
static inline bool sph_simd8_on(const sph_sim *sim)
{
    return SPH_HAVE_AVX2 && sim->def.vector == SPH_ON && sim->def.vector_avx2 == SPH_ON &&
           sim->def.accumulate == SPH_ACC_FLOAT && !sph_sim_periodic(sim);
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
