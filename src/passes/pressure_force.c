/* Pass: pressure force, as an acceleration a = F / (rho dV).
 *   symmetric: a_i = - sum_j m_j (p_i / rho_i^2 + p_j / rho_j^2) grad W_ij
 *              (from the Lagrangian; the pair terms are equal and opposite,
 *              so total momentum is conserved exactly up to round-off)
 *   shared:    a_i = - (1 / rho_i) sum_j (m_j / rho_j) (p_i + p_j) / 2 grad W_ij
 *              (the seed's form, Mueller 2003). It conserves momentum too:
 *              m_i a_i = -V_i V_j (p_i + p_j) / 2 grad W_ij with V = m / rho is
 *              antisymmetric in i, j. What it lacks is the link to the
 *              internal energy that the symmetric form has.
 * grad W_ij = W'(r) (x_i - x_j) / r. Coincident particles get a direction
 * (see below), else they would never separate.
 * With [compute] fuse_forces = on (and the forms of sph_forces_fused) this
 * pass also writes the viscous acceleration acc_v, in the same walk of the
 * lists, and the viscosity pass after it does nothing. */
#include "simd.h"
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!(def->effects & SPH_EFFECT(PRESSURE))) return "effects do not list pressure";
    return def->pressure_solver != SPH_PSOLVER_EOS ? "pressure_solver is not eos: its own pass makes the pressure"
                                                   : NULL;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "%s form, gradient of the %s kernel%s", sph_pressure_form_names[def->pressure_form],
             sph_kernel_names[def->kernel_pressure], sph_scene_wall_volume(def) ? ", walls push back" : "");
}

/* The force on one particle; dim and dbl are constants (SPH_SPECIALISE). */
static inline void pressure_one(const sph_sim *sim, const sph_kernel *k, int i, const int dim, const bool dbl,
                                const bool periodic)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const bool symmetric = sim->def.pressure_form == SPH_PFORM_SYMMETRIC;
    const float r_min = SPH_KERNEL_R_MIN * k->h; /* below this, particles count as coincident */
    const float *per = sim->period, *iper = sim->inv_period;
    const float rho_i = P->rho[i], p_i = P->p[i];
    const float pi_over = P->p_rho2[i];
    float xi[3], af[3] = {0, 0, 0};
    double ad[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) xi[d] = P->pred[d][i];
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = xi[d] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        float r;
        if (r2 < r_min * r_min) {
            /* Coincident (or nearly): the gradient has no direction. Push the
             * pair apart along x, in opposite senses for i and j so the pair
             * force stays equal and opposite (momentum kept). Only a
             * repulsion: a tensile (negative pressure) pair is already where
             * its attraction would bring it, and pushing it along an
             * arbitrary axis threw two particles at rest apart at the
             * speed of sound. */
            dx[0] = (uint32_t)i < j ? -r_min : r_min;
            for (int d = 1; d < dim; d++) dx[d] = 0.0f;
            r = r_min;
        } else {
            r = sqrtf(r2);
        }
        float dw_over_r = sph_kernel_dw(k, r) / r;
        float coef = symmetric ? P->mass[j] * (pi_over + P->p_rho2[j]) : P->vol[j] * 0.5f * (p_i + P->p[j]) / rho_i;
        if (r2 < r_min * r_min && coef < 0.0f) coef = 0.0f; /* a coincident pair only repels (below) */
        for (int d = 0; d < dim; d++) {
            float t = coef * dw_over_r * dx[d];
            if (dbl) ad[d] -= t;
            else af[d] -= t;
        }
    }
    float a[3];
    for (int d = 0; d < dim; d++) a[d] = dbl ? (float)ad[d] : af[d];
    if (sph_sim_wall_volume(sim)) {
        /* the walls' push ([domain] wall_force): the energy's gradient, or
         * the hidden lattice as ghost particles in the pair term, their
         * pressure extrapolated with gravity (docs/accuracy.md, section 6) */
        sph_wall_ghost_accel(sim, i, a);
    }
    for (int d = 0; d < dim; d++) P->acc_p[d][i] = a[d];
}

#if SPH_HAVE_AVX512
/* Spiky: dW/dr = -3 sigma (h - r)^2. */
static inline void pressure_one_avx512(const sph_sim *sim, const sph_kernel *k, int i, const int dim)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const bool symmetric = sim->def.pressure_form == SPH_PFORM_SYMMETRIC;
    const float rmin = SPH_KERNEL_R_MIN * k->h;
    __m512 xi[3], d3[3];
    sph_simd_centre(P, i, dim, xi);
    const __m512 h = _mm512_set1_ps(k->h), m3s = _mm512_set1_ps(-3.0f * k->sigma);
    const __m512 rmin2 = _mm512_set1_ps(rmin * rmin), vrmin = _mm512_set1_ps(rmin);
    const __m512 pi_over = _mm512_set1_ps(P->p_rho2[i]), pi = _mm512_set1_ps(P->p[i]);
    const __m512 half_over_rho = _mm512_set1_ps(0.5f / P->rho[i]), zero = _mm512_setzero_ps();
    const __m512i vi = _mm512_set1_epi32(i);
    __m512 ax = zero, ay = zero, az = zero;
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    const uint32_t end = row.n;
    for (uint32_t e = 0; e < end; e += 16) {
        __mmask16 live = sph_simd_live(e, end);
        __m512i idx = sph_simd_nbr(&row, e, live);
        __m512 r2 = sph_simd_offsets(P, live, idx, xi, dim, d3);
        __m512 dx = d3[0], dy = d3[1], dz = d3[2];
        __mmask16 close = _mm512_mask_cmp_ps_mask(live, r2, rmin2, _CMP_LT_OQ);
        if (close) { /* coincident pairs: pushed apart along x, as in the scalar loop */
            __mmask16 before = _mm512_mask_cmplt_epu32_mask(close, vi, idx); /* i < j */
            __m512 along = _mm512_mask_mov_ps(vrmin, before, _mm512_sub_ps(zero, vrmin));
            dx = _mm512_mask_mov_ps(dx, close, along);
            dy = _mm512_mask_mov_ps(dy, close, zero);
            dz = _mm512_mask_mov_ps(dz, close, zero);
            r2 = _mm512_mask_mov_ps(r2, close, rmin2);
        }
        __m512 r = _mm512_sqrt_ps(r2);
        __m512 t = _mm512_max_ps(_mm512_sub_ps(h, r), zero);
        __m512 dw_over_r = _mm512_maskz_div_ps(live, _mm512_mul_ps(m3s, _mm512_mul_ps(t, t)), r);
        __m512 coef = symmetric ? _mm512_mul_ps(sph_simd_gather(live, idx, P->mass),
                                                _mm512_add_ps(pi_over, sph_simd_gather(live, idx, P->p_rho2)))
                                : _mm512_mul_ps(_mm512_mul_ps(sph_simd_gather(live, idx, P->vol), half_over_rho),
                                                _mm512_add_ps(pi, sph_simd_gather(live, idx, P->p)));
        if (close) /* a coincident pair only repels, as in the scalar loop */
            coef = _mm512_mask_mov_ps(coef, _mm512_mask_cmp_ps_mask(close, coef, zero, _CMP_LT_OQ), zero);
        __m512 f = _mm512_mul_ps(coef, dw_over_r);
        ax = _mm512_mask3_fnmadd_ps(f, dx, ax, live);
        ay = _mm512_mask3_fnmadd_ps(f, dy, ay, live);
        if (dim == 3) az = _mm512_mask3_fnmadd_ps(f, dz, az, live);
    }
    float a[3] = {_mm512_reduce_add_ps(ax), _mm512_reduce_add_ps(ay), _mm512_reduce_add_ps(az)};
    if (sph_sim_wall_volume(sim)) {
        sph_wall_ghost_accel(sim, i, a);
    }
    for (int d = 0; d < dim; d++) P->acc_p[d][i] = a[d];
}

/* [compute] fuse_forces = on: the pressure force above and the viscosity of
 * viscosity_one_avx512 (src/passes/viscosity.c) in one walk of the list, so
 * each block of 16 neighbours has its index loaded, its positions gathered
 * and r = sqrt(r^2) taken once for both (9 gathers per block instead of 12
 * in the symmetric form). The arithmetic of each force is the separate
 * loops', operation for operation, so the result is the same to the bit. */
static inline void forces_one_avx512(const sph_sim *sim, const sph_kernel *k, const sph_kernel *kv, int i,
                                     const int dim)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const bool symmetric = sim->def.pressure_form == SPH_PFORM_SYMMETRIC;
    const float rmin = SPH_KERNEL_R_MIN * k->h;
    __m512 xi[3], d3[3];
    sph_simd_centre(P, i, dim, xi);
    const __m512 h = _mm512_set1_ps(k->h), m3s = _mm512_set1_ps(-3.0f * k->sigma);
    const __m512 rmin2 = _mm512_set1_ps(rmin * rmin), vrmin = _mm512_set1_ps(rmin);
    const __m512 pi_over = _mm512_set1_ps(P->p_rho2[i]), pi = _mm512_set1_ps(P->p[i]);
    const __m512 half_over_rho = _mm512_set1_ps(0.5f / P->rho[i]), zero = _mm512_setzero_ps();
    const __m512 vxi = _mm512_set1_ps(P->vel[0][i]), vyi = _mm512_set1_ps(P->vel[1][i]);
    const __m512 vzi = _mm512_set1_ps(dim == 3 ? P->vel[2][i] : 0.0f);
    float *const *vj = P->vel_visc[0] ? P->vel_visc : P->vel;
    const __m512 inv_hv = _mm512_set1_ps(kv->inv_h), one = _mm512_set1_ps(1.0f);
    const __m512 h2 = _mm512_set1_ps(sim->def.h * sim->def.h);
    const __m512i vi = _mm512_set1_epi32(i);
    __m512 ax = zero, ay = zero, az = zero, bx = zero, by = zero, bz = zero;
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    const uint32_t end = row.n;
    for (uint32_t e = 0; e < end; e += 16) {
        __mmask16 live = sph_simd_live(e, end);
        __m512i idx = sph_simd_nbr(&row, e, live);
        __m512 r2 = sph_simd_offsets(P, live, idx, xi, dim, d3);
        __m512 vol = sph_simd_gather(live, idx, P->vol);
        /* viscosity first, from the true r^2 (the pressure term below moves coincident pairs); pairs
         * within h only, as in viscosity_one_avx512 */
        const __mmask16 in = _mm512_mask_cmp_ps_mask(live, r2, h2, _CMP_LT_OQ);
        __m512 lap = _mm512_max_ps(_mm512_fnmadd_ps(_mm512_sqrt_ps(r2), inv_hv, one), zero); /* 1 - r/h */
        __m512 cv = _mm512_mul_ps(vol, lap);
        bx = _mm512_mask3_fmadd_ps(cv, _mm512_sub_ps(sph_simd_gather(live, idx, vj[0]), vxi), bx, in);
        by = _mm512_mask3_fmadd_ps(cv, _mm512_sub_ps(sph_simd_gather(live, idx, vj[1]), vyi), by, in);
        if (dim == 3) bz = _mm512_mask3_fmadd_ps(cv, _mm512_sub_ps(sph_simd_gather(live, idx, vj[2]), vzi), bz, in);
        __m512 dx = d3[0], dy = d3[1], dz = d3[2];
        __mmask16 close = _mm512_mask_cmp_ps_mask(live, r2, rmin2, _CMP_LT_OQ);
        if (close) { /* coincident pairs: pushed apart along x, as in pressure_one */
            __mmask16 before = _mm512_mask_cmplt_epu32_mask(close, vi, idx); /* i < j */
            __m512 along = _mm512_mask_mov_ps(vrmin, before, _mm512_sub_ps(zero, vrmin));
            dx = _mm512_mask_mov_ps(dx, close, along);
            dy = _mm512_mask_mov_ps(dy, close, zero);
            dz = _mm512_mask_mov_ps(dz, close, zero);
            r2 = _mm512_mask_mov_ps(r2, close, rmin2);
        }
        __m512 r = _mm512_sqrt_ps(r2);
        __m512 t = _mm512_max_ps(_mm512_sub_ps(h, r), zero);
        __m512 dw_over_r = _mm512_maskz_div_ps(live, _mm512_mul_ps(m3s, _mm512_mul_ps(t, t)), r);
        __m512 coef = symmetric ? _mm512_mul_ps(sph_simd_gather(live, idx, P->mass),
                                                _mm512_add_ps(pi_over, sph_simd_gather(live, idx, P->p_rho2)))
                                : _mm512_mul_ps(_mm512_mul_ps(vol, half_over_rho),
                                                _mm512_add_ps(pi, sph_simd_gather(live, idx, P->p)));
        if (close) /* a coincident pair only repels */
            coef = _mm512_mask_mov_ps(coef, _mm512_mask_cmp_ps_mask(close, coef, zero, _CMP_LT_OQ), zero);
        __m512 f = _mm512_mul_ps(coef, dw_over_r);
        ax = _mm512_mask3_fnmadd_ps(f, dx, ax, live);
        ay = _mm512_mask3_fnmadd_ps(f, dy, ay, live);
        if (dim == 3) az = _mm512_mask3_fnmadd_ps(f, dz, az, live);
    }
    float a[3] = {_mm512_reduce_add_ps(ax), _mm512_reduce_add_ps(ay), _mm512_reduce_add_ps(az)};
    if (sph_sim_wall_volume(sim)) {
        sph_wall_ghost_accel(sim, i, a);
    }
    for (int d = 0; d < dim; d++) P->acc_p[d][i] = a[d];
    /* the scale of viscosity_one_avx512 */
    const float c = kv->sigma * kv->inv_h * kv->inv_h * (dim == 3 ? 6.0f : 1.0f);
    const float s = c * sim->def.viscosity * sim->def.rest_density / P->rho[i];
    P->acc_v[0][i] = s * _mm512_reduce_add_ps(bx);
    P->acc_v[1][i] = s * _mm512_reduce_add_ps(by);
    if (dim == 3) P->acc_v[2][i] = s * _mm512_reduce_add_ps(bz);
}
#endif

#if SPH_HAVE_AVX2
/* pressure_one_avx512 (fused = false) and forces_one_avx512 (fused = true, with
 * the viscosity kernel kv) 8 neighbours at a time ([search] vector_avx2 = on):
 * the same operations per pair; the lanes are summed in another order, so the
 * result differs from the 16-lane loops by round-off only. With rec
 * (packed_records = on) each neighbour's x, y, z, volume, velocity and p/rho^2
 * (or p) come from its record (two sph_simd8_rec4) instead of 8 gathers: the
 * same values, the same operations, the same result to the bit. With one_mass
 * (uniform_mass = on, every particle's mass the same) the mass is that
 * constant, not a gather: the same value, so the same result again. dim,
 * fused, packed (rec_or_null holds the records) and one_mass are constants in
 * each caller (forces_avx2_pick). */
SPH_INLINE void forces_one_avx2(const sph_sim *sim, const sph_kernel *k, const sph_kernel *kv, int i, const int dim,
                                const bool fused, const float *rec_or_null, const bool packed, const bool one_mass)
{
    const float *const rec = packed ? rec_or_null : NULL; /* packed a constant: the compiler drops the other path */
    const sph_particles *P = &sim->P;
    /* one_mass is only ever set in the symmetric form (run): then a constant, and the shared form's vectors go */
    const bool symmetric = one_mass || sim->def.pressure_form == SPH_PFORM_SYMMETRIC;
    const float rmin = SPH_KERNEL_R_MIN * k->h;
    __m256 xi[3], d3[3];
    sph_simd8_centre(P, i, dim, xi);
    const __m256 h = _mm256_set1_ps(k->h), m3s = _mm256_set1_ps(-3.0f * k->sigma);
    const __m256 rmin2 = _mm256_set1_ps(rmin * rmin), vrmin = _mm256_set1_ps(rmin);
    const __m256 pi_over = _mm256_set1_ps(P->p_rho2[i]), pi = _mm256_set1_ps(P->p[i]);
    const __m256 half_over_rho = _mm256_set1_ps(0.5f / P->rho[i]), zero = _mm256_setzero_ps();
    const __m256 vxi = _mm256_set1_ps(P->vel[0][i]), vyi = _mm256_set1_ps(P->vel[1][i]);
    const __m256 vzi = _mm256_set1_ps(dim == 3 ? P->vel[2][i] : 0.0f);
    float *const *vj = P->vel_visc[0] ? P->vel_visc : P->vel;
    const __m256 inv_hv = _mm256_set1_ps(fused ? kv->inv_h : 0.0f), one = _mm256_set1_ps(1.0f);
    const __m256 h2 = _mm256_set1_ps(sim->def.h * sim->def.h);
    const __m256i vi = _mm256_set1_epi32(i);
    const __m256 mall = _mm256_set1_ps(one_mass ? P->mass[0] : 0.0f); /* one_mass: every neighbour's mass [kg] */
    __m256 ax = zero, ay = zero, az = zero, bx = zero, by = zero, bz = zero;
    const sph_nbr_row row = sph_nbr_row_of(&sim->S, (uint32_t)i);
    const uint32_t end = row.n;
    const float *const rec_i = packed ? rec + 8 * (size_t)i : NULL; /* this particle's record */
    for (uint32_t e = 0; e < end; e += 8) {
        const __m256i live = sph_simd8_live(e, end);
        /* packed, a compact row (the common case): the records' addresses straight from the offsets, no index
         * vector; the last block's dead lanes get offset 0, the particle's own record, whose lanes the masks
         * below zero (exact zeros, as for record 0 on the other path: the same sums to the bit). Else the
         * indices as a vector (dead lanes 0). */
        const bool by_offset = packed && row.o;
        const __m256i idx = by_offset ? _mm256_setzero_si256() : sph_simd8_nbr(&row, e, end, live);
        int16_t o_last[8];
        const int16_t *o = by_offset ? sph_simd8_block_offsets(row.o, e, end, o_last) : NULL;
        __m256 r2, vol = zero, q[4], g[4]; /* q, g: the records' halves */
        uint32_t j[8];                     /* packed, not by_offset: the indices */
        if (packed) { /* sph_simd8_offsets' sums on the records' positions */
            if (by_offset) {
                sph_simd8_rec4_off(rec_i, o, 0, q);
            } else {
                sph_simd8_indices(idx, j);
                sph_simd8_rec4(rec, 8, j, q);
            }
            for (int d = 0; d < 3; d++) d3[d] = d < dim ? _mm256_sub_ps(xi[d], q[d]) : zero;
            r2 = _mm256_add_ps(_mm256_mul_ps(d3[0], d3[0]), _mm256_mul_ps(d3[1], d3[1]));
            if (dim == 3) r2 = _mm256_add_ps(r2, _mm256_mul_ps(d3[2], d3[2]));
            vol = q[3];
            if (by_offset) /* the second half after the distances: fewer vectors live at once */
                sph_simd8_rec4_off(rec_i, o, 4, g);
            else
                sph_simd8_rec4(rec + 4, 8, j, g);
        } else {
            r2 = sph_simd8_offsets(P, live, idx, xi, dim, d3);
            if (fused || !symmetric) vol = sph_simd8_gather(live, idx, P->vol);
        }
        if (fused) { /* viscosity first, from the true r^2, pairs within h only (forces_one_avx512) */
            const __m256i in = _mm256_and_si256(live, _mm256_castps_si256(_mm256_cmp_ps(r2, h2, _CMP_LT_OQ)));
            __m256 lap = _mm256_max_ps(_mm256_fnmadd_ps(_mm256_sqrt_ps(r2), inv_hv, one), zero); /* 1 - r/h */
            __m256 cv = sph_simd8_keep(in, _mm256_mul_ps(vol, lap));
            const __m256 ux = packed ? g[0] : sph_simd8_gather(live, idx, vj[0]);
            const __m256 uy = packed ? g[1] : sph_simd8_gather(live, idx, vj[1]);
            bx = _mm256_fmadd_ps(cv, _mm256_sub_ps(ux, vxi), bx);
            by = _mm256_fmadd_ps(cv, _mm256_sub_ps(uy, vyi), by);
            if (dim == 3) {
                const __m256 uz = packed ? g[2] : sph_simd8_gather(live, idx, vj[2]);
                bz = _mm256_fmadd_ps(cv, _mm256_sub_ps(uz, vzi), bz);
            }
        }
        __m256 dx = d3[0], dy = d3[1], dz = d3[2];
        const __m256i close = _mm256_and_si256(live, _mm256_castps_si256(_mm256_cmp_ps(r2, rmin2, _CMP_LT_OQ)));
        const bool any_close = !_mm256_testz_si256(close, close);
        if (any_close) { /* coincident pairs: pushed apart along x, as in pressure_one */
            const __m256i jv = by_offset ? sph_simd8_nbr(&row, e, end, live) : idx;
            const __m256i before = _mm256_cmpgt_epi32(jv, vi); /* i < j (indices below 2^31) */
            __m256 along = sph_simd8_pick(before, _mm256_sub_ps(zero, vrmin), vrmin);
            dx = sph_simd8_pick(close, along, dx);
            dy = sph_simd8_pick(close, zero, dy);
            dz = sph_simd8_pick(close, zero, dz);
            r2 = sph_simd8_pick(close, rmin2, r2);
        }
        __m256 r = _mm256_sqrt_ps(r2);
        __m256 t = _mm256_max_ps(_mm256_sub_ps(h, r), zero);
        __m256 dw_over_r = _mm256_div_ps(_mm256_mul_ps(m3s, _mm256_mul_ps(t, t)), r);
        const __m256 pj = packed ? g[3] : sph_simd8_gather(live, idx, symmetric ? P->p_rho2 : P->p);
        /* by offset there is no index vector (idx is 0): unequal masses are gathered by the row's indices */
        const __m256 mj = one_mass    ? mall
                          : !symmetric ? zero
                                       : sph_simd8_gather(live, by_offset ? sph_simd8_nbr(&row, e, end, live) : idx,
                                                          P->mass);
        __m256 coef = symmetric ? _mm256_mul_ps(mj, _mm256_add_ps(pi_over, pj))
                                : _mm256_mul_ps(_mm256_mul_ps(vol, half_over_rho), _mm256_add_ps(pi, pj));
        if (any_close) /* a coincident pair only repels */
            coef = sph_simd8_pick(_mm256_and_si256(close, _mm256_castps_si256(_mm256_cmp_ps(coef, zero, _CMP_LT_OQ))),
                                  zero, coef);
        __m256 f = sph_simd8_keep(live, _mm256_mul_ps(coef, dw_over_r)); /* dead lanes: r may be 0 */
        ax = _mm256_fnmadd_ps(f, dx, ax);
        ay = _mm256_fnmadd_ps(f, dy, ay);
        if (dim == 3) az = _mm256_fnmadd_ps(f, dz, az);
    }
    float a[3] = {sph_simd8_sum(ax), sph_simd8_sum(ay), sph_simd8_sum(az)};
    if (sph_sim_wall_volume(sim)) sph_wall_ghost_accel(sim, i, a); /* the push wall_force names, as the other loops */
    for (int d = 0; d < dim; d++) P->acc_p[d][i] = a[d];
    if (!fused) return;
    const float c = kv->sigma * kv->inv_h * kv->inv_h * (dim == 3 ? 6.0f : 1.0f); /* viscosity_one_avx512's scale */
    const float s = c * sim->def.viscosity * sim->def.rest_density / P->rho[i];
    P->acc_v[0][i] = s * sph_simd8_sum(bx);
    P->acc_v[1][i] = s * sph_simd8_sum(by);
    if (dim == 3) P->acc_v[2][i] = s * sph_simd8_sum(bz);
}

/* One function for each combination, so that dim, fused, packed and one_mass
 * are constants in its loop: a single forces_one_avx2 with them as arguments
 * (gcc would not inline it at all twelve calls) kept every path's vectors
 * live and spilled them. */
typedef void (*forces_avx2_fn)(const sph_sim *sim, const sph_kernel *k, const sph_kernel *kv, int i,
                               const float *rec);
#define SPH_FORCES_AVX2_FN(NAME, DIM, F, R, M)                                                                    \
    static void NAME(const sph_sim *sim, const sph_kernel *k, const sph_kernel *kv, int i, const float *rec)      \
    {                                                                                                              \
        forces_one_avx2(sim, k, kv, i, DIM, F, rec, R, M);                                                         \
    }
SPH_FORCES_AVX2_FN(forces3_fused_packed_one, 3, true, true, true)
SPH_FORCES_AVX2_FN(forces3_packed_one, 3, false, true, true)
SPH_FORCES_AVX2_FN(forces3_fused_packed, 3, true, true, false)
SPH_FORCES_AVX2_FN(forces3_packed, 3, false, true, false)
SPH_FORCES_AVX2_FN(forces3_fused, 3, true, false, false)
SPH_FORCES_AVX2_FN(forces3, 3, false, false, false)
SPH_FORCES_AVX2_FN(forces2_fused_packed_one, 2, true, true, true)
SPH_FORCES_AVX2_FN(forces2_packed_one, 2, false, true, true)
SPH_FORCES_AVX2_FN(forces2_fused_packed, 2, true, true, false)
SPH_FORCES_AVX2_FN(forces2_packed, 2, false, true, false)
SPH_FORCES_AVX2_FN(forces2_fused, 2, true, false, false)
SPH_FORCES_AVX2_FN(forces2, 2, false, false, false)
#undef SPH_FORCES_AVX2_FN

/* The variant for this pass's keys: [dim == 3][fused][gathers, records, records and one mass]. */
static forces_avx2_fn forces_avx2_pick(int dim, bool fused, bool packed, bool one_mass)
{
    static const forces_avx2_fn fns[2][2][3] = {
        {{forces2, forces2_packed, forces2_packed_one},
         {forces2_fused, forces2_fused_packed, forces2_fused_packed_one}},
        {{forces3, forces3_packed, forces3_packed_one},
         {forces3_fused, forces3_fused_packed, forces3_fused_packed_one}},
    };
    return fns[dim == 3][fused][packed ? (one_mass ? 2 : 1) : 0];
}
#endif

#if SPH_HAVE_AVX2
/* The records forces_one_avx2 reads (packed_records = on), 8 floats a particle:
 * x, y, z [m], volume [m^3], the velocity the viscosity reads [m/s], and
 * p/rho^2 [m^5/(kg s^2)] (symmetric form) or p [Pa]. With check (uniform_mass
 * = on) it also says whether every particle's mass is the first's, bit for
 * bit, so that the walk may take it as a constant (the same loop reads it
 * alongside: no pass of its own). */
static bool pack_records(const sph_sim *sim, float *rec, const bool check)
{
    const sph_particles *P = &sim->P;
    const int n = (int)sim->n, dim = sim->dim;
    float *const *vj = P->vel_visc[0] ? P->vel_visc : P->vel;
    const float *pj = sim->def.pressure_form == SPH_PFORM_SYMMETRIC ? P->p_rho2 : P->p;
    const float m0 = n > 0 ? P->mass[0] : 0.0f;
    int differ = 0; /* particles whose mass is not m0 */
#pragma omp parallel for schedule(static) reduction(+ : differ) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        /* bits: the very value a gather reads (-0 == 0 as floats) */
        if (check) differ += memcmp(&P->mass[i], &m0, sizeof m0) != 0;
        float *r = rec + 8 * (size_t)i;
        for (int d = 0; d < 3; d++) {
            r[d] = d < dim ? P->pred[d][i] : 0.0f;
            r[4 + d] = d < dim ? vj[d][i] : 0.0f;
        }
        r[3] = P->vol[i];
        r[7] = pj[i];
    }
    return check && differ == 0;
}
#endif

/* Wall particles (wall_model = particles) get no acceleration: they never move. */
static inline bool wall_still(sph_sim *sim, int i)
{
    if (!sph_is_wall(&sim->P, i)) return false;
    for (int d = 0; d < sim->dim; d++) sim->P.acc_p[d][i] = 0.0f;
    return true;
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_pressure;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
#if SPH_HAVE_AVX2
    if (sph_simd8_on(sim) && k.kind == SPH_KERNEL_SPIKY) {
        const sph_kernel kv = sim->k_viscosity;
        const bool fused = sph_forces_fused(sim); /* also writes acc_v; the viscosity pass then does nothing */
        float *rec = sph_simd8_packed(sim) ? sph_simd8_records(sim, 8) : NULL;
        /* uniform_mass: the symmetric form's one gather the records leave, gone when every mass is the same */
        const bool want_one = sim->def.uniform_mass == SPH_ON && sim->def.pressure_form == SPH_PFORM_SYMMETRIC;
        const bool one_mass = rec && pack_records(sim, rec, want_one);
        const forces_avx2_fn walk = forces_avx2_pick(dim, fused, rec != NULL, one_mass);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) {
            if (sph_is_wall(&sim->P, i)) {
                for (int d = 0; d < dim; d++) sim->P.acc_p[d][i] = 0.0f;
                if (fused)
                    for (int d = 0; d < dim; d++) sim->P.acc_v[d][i] = 0.0f;
                continue;
            }
            walk(sim, &k, &kv, i, rec);
        }
        return;
    }
#endif
#if SPH_HAVE_AVX512
    if (sph_forces_fused(sim)) { /* also writes acc_v; the viscosity pass then does nothing */
        const sph_kernel kv = sim->k_viscosity;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) {
            if (sph_is_wall(&sim->P, i)) {
                for (int d = 0; d < dim; d++) sim->P.acc_p[d][i] = sim->P.acc_v[d][i] = 0.0f;
                continue;
            }
            dim == 3 ? forces_one_avx512(sim, &k, &kv, i, 3) : forces_one_avx512(sim, &k, &kv, i, 2);
        }
        return;
    }
    if (sph_simd_on(sim) && k.kind == SPH_KERNEL_SPIKY) {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++)
            if (!wall_still(sim, i))
                dim == 3 ? pressure_one_avx512(sim, &k, i, 3) : pressure_one_avx512(sim, &k, i, 2);
        return;
    }
#endif
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++)
        if (!wall_still(sim, i)) SPH_SPECIALISE_P(dim, dbl, periodic, pressure_one, sim, &k, i);
}

const sph_pass sph_pass_pressure_force = {
    .name = "pressure_force",
    .summary = "pressure force (acceleration)",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(RHO) | SPH_BIT(VOL) | SPH_BIT(P) | SPH_BIT(PRHO2) | SPH_RES_LISTS,
    .writes = SPH_BIT(ACC_P),
    .group = SPH_GROUP_FORCES,
    .highlight = "pressure-acc",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
