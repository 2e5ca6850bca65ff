/* Pass: normals, the surface normal of [physics] surface_tension = akinci
 * (Akinci, Akinci & Teschner 2013, "Versatile surface tension and adhesion
 * for SPH fluids", ACM TOG 32(6), eq. 3):
 *
 *   n_i = h sum_j (m_j / rho_j) grad_i W_ij = h sum_j V_j W'(r) x_ij / r,   x_ij = x_i - x_j
 *
 * h times the gradient of the colour field (1 in the fluid, 0 outside), so
 * it points into the fluid. Inside a full neighbourhood the terms cancel
 * (n ~ 0); at a flat surface |n| is h times the kernel's integral over the
 * plane, of order 1 whatever the resolution: that is why Akinci scale it by
 * h. The sign is the paper's (and SPlisHSPlasH's, which sums the same
 * gradient): with the curvature term -gamma (n_i - n_j) it pushes a surface
 * particle out from the particles below it, against the cohesion term's
 * crowding of the surface layer. The opposite sign (pointing out) made a 2D
 * drop of R = 10 spacings fly apart within 1.5 s of its damping ending (R/20:
 * the watchdog stopped it), where this sign keeps it round
 * (docs/accuracy.md, the drop). The kernel is the density's, so the colour
 * field is the one the density sum sees. Wall particles are left out of the
 * sum and get n = 0: the model's adhesion to walls is not implemented.
 * surface_tension = csf reads the same field as h times the colour
 * gradient (csf.c), summed with the volumes m_j / rho0 instead: with
 * m_j / rho_j the outermost row's larger volumes (rho ~ 0.72 rho0 there)
 * turn the second row's normal outwards (a disc of R = 20 spacings, cubic
 * kernel at h = 3 spacings: |n| 1.27, 0.07 pointing out, 0.14 in), and the
 * divergence of the unit normals across those rows read 30 times the
 * disc's curvature. With m_j / rho0 |n| grows monotonically to the surface. */
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return def->surface_tension != SPH_STENSION_NONE ? NULL : "surface_tension is none";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "Akinci 2013 eq. 3, %s kernel's gradient", sph_kernel_names[def->kernel_density]);
}

/* The normal of one particle; dim and periodic are constants. */
static inline void normal_one(const sph_sim *sim, const sph_kernel *k, int i, const int dim, const bool dbl,
                              const bool periodic)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const float *per = sim->period, *iper = sim->inv_period;
    float xi[3], nf[3] = {0, 0, 0};
    double nd[3] = {0, 0, 0};
    const bool csf = sim->def.surface_tension == SPH_STENSION_CSF || sim->def.surface_tension == SPH_STENSION_STRESS;
    const float inv_rho0 = 1.0f / sim->def.rest_density;
    if (sph_is_wall(P, i)) {
        for (int d = 0; d < dim; d++) P->normal[d][i] = 0.0f;
        return;
    }
    for (int d = 0; d < dim; d++) xi[d] = P->pred[d][i];
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
        if (!(r2 > 0)) continue; /* coincident: no direction */
        float r = sqrtf(r2);
        float c = (csf ? P->mass[j] * inv_rho0 : P->vol[j]) * sph_kernel_dw(k, r) / r;
        for (int d = 0; d < dim; d++) {
            if (dbl) nd[d] += c * dx[d];
            else nf[d] += c * dx[d];
        }
    }
    for (int d = 0; d < dim; d++) P->normal[d][i] = k->h * (dbl ? (float)nd[d] : nf[d]);
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
    const bool periodic = sph_sim_periodic(sim);
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE_P(dim, dbl, periodic, normal_one, sim, &k, i);
}

const sph_pass sph_pass_normals = {
    .name = "normals",
    .summary = "surface normals of surface tension, h grad c (dimensionless)",
    .reads = SPH_BIT(PRED) | SPH_BIT(VOL) | SPH_BIT(MASS) | SPH_RES_LISTS,
    .writes = SPH_BIT(NORMAL),
    .group = SPH_GROUP_FORCES,
    .highlight = "normal",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
