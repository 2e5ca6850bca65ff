/* AVX-512 helpers shared by the pair passes (density, pressure_force,
 * viscosity): 16 neighbours of one particle at a time, their data gathered
 * by index. Only where the build targets AVX-512 ([search] vector = on
 * selects them at run time); every pass keeps its scalar loop for other
 * CPUs, other kernels and vector = off. */
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

/* Whether a pass may use its vector loop for this scene and kernel. */
static inline bool sph_simd_on(const sph_sim *sim)
{
    return SPH_HAVE_AVX512 && sim->def.vector == SPH_ON && sim->def.accumulate == SPH_ACC_FLOAT &&
           !sph_sim_periodic(sim);
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
