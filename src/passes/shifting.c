/* Pass: particle shifting after Lind, Xu, Stansby & Rogers 2012 (J. Comput.
 * Phys. 231, 1499-1523, section 3; [physics] shifting = lind). After each
 * integration every fluid particle moves a little down the gradient of the
 * particle concentration, as in Fick's law, which spreads clumps and fills
 * voids before they grow into noise:
 *
 *   dr_i = -D grad C_i,
 *   grad C_i = sum_j V_j (1 + R (W_ij / W(dp_i))^n) grad_i W_ij,  R = 0.2, n = 4,
 *
 * Lind's eq. 13 (the second term, after Monaghan 2000, pushes apart pairs
 * closer than the spacing dp_i = V_i^(1/dim) more strongly). The distance
 * scales with the step, D = A h |v_i| dt (A = shifting_coefficient; the form of
 * Skillen et al. 2013, Comput. Methods Appl. Mech. Eng. 265:163, eq. 12, which
 * makes Lind's shift vanish for fluid at rest and stay a fraction of the
 * step's own displacement |v| dt in a weakly compressible scheme's small steps).
 *
 * The free surface: there grad C points into the fluid only because the
 * support is cut off, and shifting along it would pull the surface apart.
 * Lind et al. find the surface by the divergence of position,
 * div r_i = -sum_j V_j x_ij . grad_i W_ij (dim inside the fluid, about half
 * that at a flat surface); a particle with div r_i < dim - 0.5 is a surface
 * particle (field `surface`), and neither it nor a particle with a surface
 * particle in its support is shifted. Wall particles count in both sums (they
 * fill the support at a wall) and never move.
 *
 * Why not the transport-velocity formulation (Adami, Hu & Adams 2013): it
 * changes the momentum equation and needs a background pressure that has no
 * meaning at a free surface, where this project's lessons mostly are;
 * shifting is one pass after integration that can be switched off alone.
 * The carried density (density_method = continuity) is not corrected by
 * dr . grad rho: the shift is a small fraction of the step's displacement. */
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

#define LIND_R 0.2f /* Lind et al. 2012, eq. 13 */
#define LIND_N 4

static const char *skip_reason(const sph_scene_def *def)
{
    if (def->shifting != SPH_SHIFT_LIND) return "[physics] shifting is not lind";
    return sph_scene_needs_neighbours(def) ? NULL : "no effect of the scene needs density (the neighbour search)";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "Lind et al. 2012: dr = -D grad C, D = %g h |v| dt, none at the free surface",
             def->shifting_coefficient);
}

/* Sweep 1: the free-surface mark from the divergence of position. */
static inline void surface_one(sph_sim *sim, const sph_kernel *k, int i, const int dim, const bool periodic)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    const float r_min = SPH_KERNEL_R_MIN * k->h;
    float div = 0.0f;
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        float r2 = 0;
        for (int d = 0; d < dim; d++) {
            float dx = P->pred[d][i] - P->pred[d][j];
            if (periodic) dx = sph_min_image(dx, per[d], iper[d]);
            r2 += dx * dx;
        }
        if (r2 < r_min * r_min) continue;
        const float r = sqrtf(r2);
        div -= P->mass[j] / P->rho[j] * sph_kernel_dw(k, r) * r; /* V_j x_ij . (W'/r) x_ij */
    }
    P->surface[i] = !sph_is_wall(P, i) && div < (float)dim - 0.5f ? 1.0f : 0.0f;
}

/* Sweep 2: the shift, from the surface marks of sweep 1. */
static inline void shift_one(sph_sim *sim, const sph_kernel *k, float a_h_dt, int i, const int dim,
                             const bool periodic)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    for (int d = 0; d < dim; d++) P->shift[d][i] = 0.0f;
    if (sph_is_wall(P, i) || P->surface[i] != 0.0f) return;
    const float *per = sim->period, *iper = sim->inv_period;
    const float r_min = SPH_KERNEL_R_MIN * k->h;
    const float dp = powf(P->mass[i] / P->rho[i], 1.0f / (float)dim);
    const float inv_wdp = 1.0f / fmaxf(sph_kernel_w(k, dp), 1e-30f);
    float g[3] = {0, 0, 0};
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        if (P->surface[j] != 0.0f) return; /* near the free surface: no shift */
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = P->pred[d][i] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        if (r2 < r_min * r_min) continue;
        const float r = sqrtf(r2);
        float q = sph_kernel_w(k, r) * inv_wdp;
        q *= q;
        const float f = P->mass[j] / P->rho[j] * (1.0f + LIND_R * q * q) * sph_kernel_dw(k, r) / r;
        for (int d = 0; d < dim; d++) g[d] += f * dx[d];
    }
    _Static_assert(LIND_N == 4, "the power above is written out for n = 4");
    float v2 = 0;
    for (int d = 0; d < dim; d++) v2 += P->vel[d][i] * P->vel[d][i];
    const float D = a_h_dt * sqrtf(v2);
    for (int d = 0; d < dim; d++) {
        P->shift[d][i] = -D * g[d];
        P->pos[d][i] += P->shift[d][i];
    }
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const bool periodic = sph_sim_periodic(sim);
    const float a_h_dt = sim->def.shifting_coefficient * sim->def.h * sim->dt;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (periodic) dim == 2 ? surface_one(sim, &k, i, 2, true) : surface_one(sim, &k, i, 3, true);
        else dim == 2 ? surface_one(sim, &k, i, 2, false) : surface_one(sim, &k, i, 3, false);
    }
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (periodic) dim == 2 ? shift_one(sim, &k, a_h_dt, i, 2, true) : shift_one(sim, &k, a_h_dt, i, 3, true);
        else dim == 2 ? shift_one(sim, &k, a_h_dt, i, 2, false) : shift_one(sim, &k, a_h_dt, i, 3, false);
    }
    for (int d = 0; d < dim; d++) /* periodic axes: back into the domain */
        if (sim->period[d] > 0) {
            const float lo = sim->def.domain_min[d], per = sim->period[d], iper = sim->inv_period[d];
            float *restrict x = sim->P.pos[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++) x[i] = sph_wrap(x[i], lo, per, iper);
        }
}

const sph_pass sph_pass_shifting = {
    .name = "shifting",
    .summary = "particle shifting down the concentration gradient (Lind et al. 2012)",
    .reads = SPH_BIT(PRED) | SPH_BIT(VEL) | SPH_BIT(MASS) | SPH_BIT(RHO) | SPH_RES_LISTS,
    .writes = SPH_BIT(POS) | SPH_BIT(SHIFT) | SPH_BIT(SURFACE),
    .group = SPH_GROUP_INTEGRATE,
    .highlight = NULL,
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
