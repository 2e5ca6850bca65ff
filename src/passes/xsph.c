/* Pass: xsph, velocity smoothing after Monaghan 1989 ("On the problem of
 * penetration in particle methods", J. Comput. Phys. 82:1, eq. 2.6: XSPH
 * moves a particle with v_i + epsilon sum_j m_j / rho_ij (v_j - v_i) W_ij,
 * rho_ij = (rho_i + rho_j) / 2). Here the correction is applied to the
 * velocity itself, as an acceleration over the step (as SPlisHSPlasH's XSPH
 * does), so integration, the pressure solvers and the watchdog see it like
 * any force:
 *
 *   a_i = (epsilon / dt) sum_j m_j / rho_ij (v_j - v_i) W_ij
 *
 * A step then moves v_i a share epsilon of the way to its neighbours'
 * kernel average. m_i a_i and m_j a_j of a pair are equal and opposite (the
 * symmetric rho_ij), so momentum is conserved; it damps relative motion, not
 * a uniform flow or a rigid translation. The kernel is the density's. Wall
 * particles neither get nor give any. */
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return def->xsph > 0 ? NULL : "xsph is 0";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "Monaghan 1989, epsilon %g, %s kernel", def->xsph, sph_kernel_names[def->kernel_density]);
}

static inline void xsph_one(const sph_sim *sim, const sph_kernel *k, float s, int i, const int dim, const bool dbl,
                            const bool periodic)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    const float rho_i = P->rho[i];
    float xi[3], vi[3], af[3] = {0, 0, 0};
    double ad[3] = {0, 0, 0};
    if (sph_is_wall(P, i)) {
        for (int d = 0; d < dim; d++) P->acc_x[d][i] = 0.0f;
        return;
    }
    for (int d = 0; d < dim; d++) {
        xi[d] = P->pred[d][i];
        vi[d] = P->vel[d][i];
    }
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        if (j == (uint32_t)i || sph_is_wall(P, j)) continue;
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = xi[d] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        float c = 2.0f * P->mass[j] / (rho_i + P->rho[j]) * sph_kernel_w(k, sqrtf(r2));
        for (int d = 0; d < dim; d++) {
            float t = c * (P->vel[d][j] - vi[d]);
            if (dbl) ad[d] += t;
            else af[d] += t;
        }
    }
    for (int d = 0; d < dim; d++) P->acc_x[d][i] = s * (dbl ? (float)ad[d] : af[d]);
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
    const float s = sim->dt > 0 ? sim->def.xsph / sim->dt : 0.0f; /* epsilon / dt [1/s] */
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, xsph_one, sim, &k, s, i);
}

const sph_pass sph_pass_xsph = {
    .name = "xsph",
    .summary = "XSPH velocity smoothing (acceleration)",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(RHO) | SPH_BIT(VEL) | SPH_RES_LISTS,
    .writes = SPH_BIT(ACC_X),
    .group = SPH_GROUP_FORCES,
    .highlight = "xsph-acc",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
