/* Pass: curvature, the second term of [physics] surface_tension = akinci
 * (Akinci, Akinci & Teschner 2013, eq. 4 and 5), per unit mass:
 *
 *   a_i = -gamma sum_j K_ij (n_i - n_j),   K_ij = 2 rho0 / (rho_i + rho_j)
 *
 * with the normals of the normals pass (eq. 3, pointing into the fluid,
 * ~0 inside). It vanishes where neighbours' normals are equal (inside, and
 * along a flat surface); a surface particle, whose n is larger than its
 * inner neighbours', is pushed out along -n_i and they in, which
 * counteracts the cohesion term's crowding of the surface layer. Each pair's
 * terms are equal and opposite for equal masses (K_ij is symmetric), so
 * momentum is conserved. The cohesion term (eq. 1-2) is the cohesion pass,
 * with the same gamma (surface_tension_coefficient). As in the paper, gamma
 * multiplies a dimensionless difference here, so this term reads gamma as
 * m/s^2 where the cohesion term reads it as m^4/(kg s^2): the share of the
 * two terms depends on rho0 and the units (docs/accuracy.md, the drop).
 * Wall particles get none. */
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return def->surface_tension == SPH_STENSION_AKINCI ? NULL : "surface_tension is not akinci";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "Akinci 2013 eq. 4-5, gamma %g", def->surface_tension_coefficient);
}

static inline void curvature_one(const sph_sim *sim, int i, const int dim, const bool dbl, const bool periodic)
{
    (void)periodic; /* the neighbour list already holds the periodic images' owners */
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float rho0 = sim->def.rest_density, rho_i = P->rho[i];
    float ni[3], af[3] = {0, 0, 0};
    double ad[3] = {0, 0, 0};
    if (sph_is_wall(P, i)) {
        for (int d = 0; d < dim; d++) P->acc_k[d][i] = 0.0f;
        return;
    }
    for (int d = 0; d < dim; d++) ni[d] = P->normal[d][i];
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        if (j == (uint32_t)i || sph_is_wall(P, j)) continue;
        float k_ij = 2.0f * rho0 / (rho_i + P->rho[j]);
        for (int d = 0; d < dim; d++) {
            float t = k_ij * (ni[d] - P->normal[d][j]);
            if (dbl) ad[d] += t;
            else af[d] += t;
        }
    }
    const float gamma = sim->def.surface_tension_coefficient;
    for (int d = 0; d < dim; d++) P->acc_k[d][i] = -gamma * (dbl ? (float)ad[d] : af[d]);
}

static void run(sph_sim *sim)
{
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, curvature_one, sim, i);
}

const sph_pass sph_pass_curvature = {
    .name = "curvature",
    .summary = "curvature force of Akinci's surface tension (acceleration)",
    .reads = SPH_BIT(NORMAL) | SPH_BIT(RHO) | SPH_RES_LISTS,
    .writes = SPH_BIT(ACC_K),
    .group = SPH_GROUP_FORCES,
    .highlight = "curvature-acc",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
