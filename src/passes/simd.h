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

/* Gathers a[idx] in the live lanes (0 elsewhere). */
static inline __m512 sph_simd_gather(__mmask16 live, __m512i idx, const float *a)
{
    return _mm512_mask_i32gather_ps(_mm512_setzero_ps(), live, idx, a, 4);
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

#endif
