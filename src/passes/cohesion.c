/* Pass: cohesion, the attraction between fluid particles that makes a
 * surface contract (the cohesion term of Akinci, Akinci & Teschner 2013,
 * "Versatile surface tension and adhesion for SPH fluids", eq. 1 and 2):
 *
 *   a_i = -gamma sum_j K_ij m_j C(r_ij) x_ij / r_ij,   K_ij = 2 rho0 / (rho_i + rho_j)
 *
 * with x_ij = x_i - x_j and their spline C, attracting for h/2 < r < h and
 * mildly repelling below, so particles cluster at the spacing, not onto each
 * other. K_ij amplifies the force where a particle has fewer neighbours than
 * inside: at the surface. Each pair's terms are equal and opposite (K_ij and
 * C are symmetric), so the pass conserves momentum.
 *
 * C(r) = sigma f(r / h) / h^(dim + 6) ... the paper's 3D constant is
 * sigma = 32 / pi; in 2D the paper gives none: sigma = 25280 / (627 pi) makes
 * the integral of C over the plane equal the 3D integral over space (79/336),
 * so one gamma means the same in both (docs/scene-format.md, tests/test_cohesion.c).
 *
 * The pass is also the cohesion term of [physics] surface_tension = akinci,
 * whose curvature term is the curvature pass (normals.c, curvature.c); gamma
 * is then surface_tension_coefficient (the scene refuses both at once). */
#include "sph_search.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (def->surface_tension == SPH_STENSION_AKINCI) return NULL;
    return (def->effects & SPH_EFFECT(COHESION)) ? NULL : "effects do not list cohesion and surface_tension is none";
}

static float sph_cohesion_gamma(const sph_scene_def *def)
{
    return def->surface_tension == SPH_STENSION_AKINCI ? def->surface_tension_coefficient : def->cohesion;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "Akinci 2013 cohesion%s, gamma %g m^4/(kg s^2)",
             def->surface_tension == SPH_STENSION_AKINCI ? " (surface_tension = akinci)" : "", sph_cohesion_gamma(def));
}

/* The spline's shape at q = r / h (Akinci 2013, eq. 2, with h = 1). */
static inline float cohesion_shape(float q)
{
    if (q >= 1.0f || q <= 0.0f) return 0.0f;
    float u = 1.0f - q, s = u * u * u * q * q * q;
    return 2.0f * q > 1.0f ? s : 2.0f * s - 1.0f / 64.0f;
}

float sph_cohesion_c(int dim, float h, float r)
{
    const float pi = 3.14159265358979f;
    const float sigma = dim == 3 ? 32.0f / pi : 25280.0f / (627.0f * pi);
    float hd = dim == 3 ? h * h * h : h * h; /* C ~ 1 / h^dim, as a kernel */
    return sigma / hd * cohesion_shape(r / h);
}

/* The cohesion acceleration of one particle; dim and dbl are constants. */
static inline void cohesion_one(const sph_sim *sim, int i, const int dim, const bool dbl, const bool periodic)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    const float h = sim->def.h, rho0 = sim->def.rest_density, rho_i = P->rho[i];
    const float r_min = SPH_KERNEL_R_MIN * h;
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
        if (r2 < r_min * r_min) continue; /* coincident: no direction to pull along */
        float r = sqrtf(r2);
        float k_ij = 2.0f * rho0 / (rho_i + P->rho[j]);
        float coef = k_ij * P->mass[j] * sph_cohesion_c(dim, h, r) / r;
        for (int d = 0; d < dim; d++) {
            float t = coef * dx[d];
            if (dbl) ad[d] += t;
            else af[d] += t;
        }
    }
    const float gamma = sph_cohesion_gamma(&sim->def);
    for (int d = 0; d < dim; d++) P->acc_c[d][i] = -gamma * (dbl ? (float)ad[d] : af[d]);
}

static void run(sph_sim *sim)
{
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, cohesion_one, sim, i);
}

const sph_pass sph_pass_cohesion = {
    .name = "cohesion",
    .summary = "cohesion force (surface tension, acceleration)",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(RHO) | SPH_RES_LISTS,
    .writes = SPH_BIT(ACC_C),
    .group = SPH_GROUP_FORCES,
    .highlight = "cohesion-acc",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
