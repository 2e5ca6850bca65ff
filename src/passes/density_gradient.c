/* Pass: the renormalised gradient of the carried density, for the density
 * diffusion term of Antuono et al. 2010 (Comput. Phys. Commun. 181, 532-549,
 * eq. 9-10; [physics] delta_form = antuono):
 *
 *   <grad rho>^L_i = L_i sum_j (rho_j - rho_i) grad_i W_ij V_j,
 *   L_i = [ sum_j (x_j - x_i) (x) grad_i W_ij V_j ]^-1,
 *
 * V_j = m_j / rho_j, the density kernel's gradient, the carried density
 * rho_c. The matrix sum is what the plain gradient sum makes of the linear
 * field x itself; its inverse corrects the sum so that the gradient of any
 * linear field is exact, in the interior as at a free surface or a wall where
 * the support is truncated (Randles & Libersky 1996, Bonet & Lok 1999). The
 * hydrostatic density is linear in depth: there the two gradients of
 * Antuono's psi_ij cancel Molteni's difference term (passes/density_rate.c).
 *
 * Wall particles (wall_model = particles) count, with the density the
 * wall_state pass gave them in the previous step (from the fluid's pressure
 * extrapolated with the hydrostatic gradient, Adami et al. 2012, so a
 * hydrostatic density stays linear across the wall): the first fluid rows
 * then see a full support, as with the mirrored ghost particles of Antuono et
 * al. A one-sided support would let the renormalised gradient follow a
 * perturbation of the row itself, and the term would no longer damp it (the
 * wall row's density drifted by 10 % of rho0 g H a second without them).
 * Their own gradient is made the same way, for the pairs they form with fluid
 * particles. Where the matrix is singular
 * (a particle with too few neighbours, all in a line) the gradient is 0 and
 * the term falls back to Molteni & Colagrossi's. */
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!sph_scene_needs_density(def)) return "no effect of the scene needs density (the neighbour search)";
    if (def->density_method != SPH_DMETHOD_CONTINUITY) return "[physics] density_method = summation: no diffusion";
    if (!(def->delta > 0)) return "[physics] delta = 0: no density diffusion";
    return def->delta_form == SPH_DFORM_ANTUONO ? NULL : "[physics] delta_form = molteni needs no density gradient";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    (void)def;
    snprintf(out, (size_t)n, "renormalised density gradient L_i sum (rho_j - rho_i) grad W V_j (Antuono et al. 2010)");
}

/* Solves M g = b for a symmetric dim x dim M (2 or 3) by Cramer's rule;
 * false (g = 0) when M is singular relative to its size. */
static bool solve_small(const double M[3][3], const double b[3], int dim, double g[3])
{
    g[0] = g[1] = g[2] = 0.0;
    double scale = 0.0;
    for (int d = 0; d < dim; d++) scale += fabs(M[d][d]);
    scale /= dim;
    if (dim == 2) {
        const double det = M[0][0] * M[1][1] - M[0][1] * M[1][0];
        if (!(fabs(det) > 1e-6 * scale * scale)) return false;
        g[0] = (b[0] * M[1][1] - M[0][1] * b[1]) / det;
        g[1] = (M[0][0] * b[1] - b[0] * M[1][0]) / det;
        return true;
    }
    const double c00 = M[1][1] * M[2][2] - M[1][2] * M[2][1], c01 = M[1][2] * M[2][0] - M[1][0] * M[2][2],
                 c02 = M[1][0] * M[2][1] - M[1][1] * M[2][0];
    const double det = M[0][0] * c00 + M[0][1] * c01 + M[0][2] * c02;
    if (!(fabs(det) > 1e-6 * scale * scale * scale)) return false;
    const double inv[3][3] = {
        {c00, M[0][2] * M[2][1] - M[0][1] * M[2][2], M[0][1] * M[1][2] - M[0][2] * M[1][1]},
        {c01, M[0][0] * M[2][2] - M[0][2] * M[2][0], M[0][2] * M[1][0] - M[0][0] * M[1][2]},
        {c02, M[0][1] * M[2][0] - M[0][0] * M[2][1], M[0][0] * M[1][1] - M[0][1] * M[1][0]},
    };
    for (int a = 0; a < 3; a++) g[a] = (inv[a][0] * b[0] + inv[a][1] * b[1] + inv[a][2] * b[2]) / det;
    return true;
}

static inline void gradient_one(sph_sim *sim, const sph_kernel *k, int i, const int dim, const bool periodic)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float r_min = SPH_KERNEL_R_MIN * k->h;
    const float *per = sim->period, *iper = sim->inv_period;
    const float rho_i = sph_rho_diffused(P, i);
    double M[3][3] = {{0}}, b[3] = {0, 0, 0};
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = P->pred[d][i] - P->pred[d][j]; /* x_ij */
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        if (r2 < r_min * r_min) continue;
        const float r = sqrtf(r2);
        /* grad_i W_ij V_j = (W'(r)/r) x_ij V_j */
        const float rho_j = sph_rho_diffused(P, j);
        const double gw = (double)(sph_kernel_dw(k, r) / r) * P->mass[j] / rho_j;
        const double drho = (double)rho_j - rho_i;
        for (int a = 0; a < dim; a++) {
            b[a] += drho * gw * dx[a];
            for (int c = 0; c < dim; c++) M[a][c] -= dx[a] * gw * dx[c]; /* (x_j - x_i)_a (grad W V)_c */
        }
    }
    double g[3];
    solve_small(M, b, dim, g);
    for (int d = 0; d < dim; d++) P->grad_rho[d][i] = (float)g[d];
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const bool periodic = sph_sim_periodic(sim);
    if (!sim->rho_carried) { /* the start: nothing carried yet, and density_rate writes drho = 0 */
        for (int d = 0; d < dim; d++)
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++) P->grad_rho[d][i] = 0.0f;
        return;
    }
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (periodic) dim == 2 ? gradient_one(sim, &k, i, 2, true) : gradient_one(sim, &k, i, 3, true);
        else dim == 2 ? gradient_one(sim, &k, i, 2, false) : gradient_one(sim, &k, i, 3, false);
    }
}

const sph_pass sph_pass_density_gradient = {
    .name = "density_gradient",
    .summary = "renormalised density gradient (Antuono's delta-SPH term)",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(RHO_C) | SPH_BIT(RHO) | SPH_RES_LISTS,
    .writes = SPH_BIT(GRAD_RHO),
    .group = SPH_GROUP_DENSITY,
    .highlight = NULL,
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
