/* Pass: the transport velocity of Adami, Hu & Adams 2013 (J. Comput. Phys.
 * 241:292-307; [physics] shifting = tvf). A weakly compressible fluid whose
 * pressure falls below the others' (near the stagnation points of a vortex,
 * where the pressure is lowest) pulls its particles into clumps and lines:
 * the tensile instability. Adami et al. move every particle with a transport
 * velocity v~ = v + (dt/2) a_b instead of v, where a_b is the acceleration a
 * constant background pressure p_b would give (their eq. 13):
 *
 *   a_b,i = -(p_b / m_i) sum_j (V_i^2 + V_j^2) grad_i W_ij,   V = m / rho.
 *
 * A constant pressure exerts no net force on a uniform particle distribution,
 * so a_b vanishes on a regular lattice and pushes particles out of clumps into
 * voids wherever the distribution is not uniform. After symplectic Euler's
 * x += dt v this pass adds the rest of their drift, dt (dt/2) a_b (their
 * kick-drift-kick scheme, section 3), at the positions the forces saw.
 *
 * p_b = rho0 c^2 = rho0 k, their choice for the Taylor-Green vortex (section
 * 4.2, p_b = p0 = rho0 c0^2; PySPH's taylor_green example likewise). Its
 * size is the fluid's own stiffness, not a tuned constant.
 *
 * Left out: the momentum equation's extra stress A = rho v (v~ - v) of their
 * eq. 8, which is of order dt |a_b| |v| and whose divergence accounts for the
 * particle not moving with v; this pass is then a shift by a background
 * pressure, with no correction of the carried velocity. Particles near a
 * free surface would be pulled outward (the support is cut off there), so
 * it is meant for flows that fill their domain (periodic boxes, closed
 * tanks). Wall particles count in the sum (they fill the support at a wall)
 * and never move. */
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (def->shifting != SPH_SHIFT_TVF) return "[physics] shifting is not tvf";
    /* p_b = rho0 c^2 presumes the acoustic step dt <= cfl (h/2) / c, which only the pressure effect imposes */
    if (!(def->effects & SPH_EFFECT(PRESSURE)) || def->pressure_solver != SPH_PSOLVER_EOS)
        return "shifting = tvf needs the pressure effect with pressure_solver = eos (its background pressure is "
               "rho0 c^2, its step the acoustic one)";
    return sph_scene_needs_neighbours(def) ? NULL : "no effect of the scene needs density (the neighbour search)";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "Adami et al. 2013: x += dt (dt/2) a_b, background pressure p_b = rho0 c^2 = %g Pa",
             (double)def->rest_density * def->stiffness);
}

/* dx_i = dt (dt/2) a_b,i into P->drift (applied after the sweep, so every
 * particle's sum sees the positions the forces saw). */
static inline void drift_one(sph_sim *sim, const sph_kernel *k, float c_i, int i, const int dim, const bool periodic)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    for (int d = 0; d < dim; d++) P->drift[d][i] = 0.0f;
    if (sph_is_wall(P, i)) return;
    const float *per = sim->period, *iper = sim->inv_period;
    const float r_min = SPH_KERNEL_R_MIN * k->h;
    const float vi = P->mass[i] / P->rho[i];
    float g[3] = {0, 0, 0};
    const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)i);
    for (uint32_t e = 0; e < row.n; e++) {
        uint32_t j = sph_nbr_at(&row, e);
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = P->pred[d][i] - P->pred[d][j];
            if (periodic) dx[d] = sph_min_image(dx[d], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        if (r2 < r_min * r_min) continue;
        const float r = sqrtf(r2), vj = P->mass[j] / P->rho[j];
        const float f = (vi * vi + vj * vj) * sph_kernel_dw(k, r) / r; /* grad_i W = W'(r) x_ij / r */
        for (int d = 0; d < dim; d++) g[d] += f * dx[d];
    }
    const float s = -c_i / P->mass[i]; /* c_i = dt (dt/2) p_b */
    for (int d = 0; d < dim; d++) P->drift[d][i] = s * g[d];
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_pressure;
    const int n = (int)sim->n, dim = sim->dim;
    const bool periodic = sph_sim_periodic(sim);
    const float p_b = sim->def.rest_density * sim->def.stiffness; /* [Pa] */
    const float c = sim->dt * 0.5f * sim->dt * p_b;
    sph_particles *P = &sim->P;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (periodic) dim == 2 ? drift_one(sim, &k, c, i, 2, true) : drift_one(sim, &k, c, i, 3, true);
        else dim == 2 ? drift_one(sim, &k, c, i, 2, false) : drift_one(sim, &k, c, i, 3, false);
    }
    for (int d = 0; d < dim; d++) {
        float *restrict x = P->pos[d];
        const float *restrict s = P->drift[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) x[i] += s[i];
        if (sim->period[d] > 0) { /* periodic axes: back into the domain */
            const float lo = sim->def.domain_min[d], per = sim->period[d], iper = sim->inv_period[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++) x[i] = sph_wrap(x[i], lo, per, iper);
        }
    }
}

const sph_pass sph_pass_transport = {
    .name = "transport",
    .summary = "transport velocity: the drift of a background pressure (Adami, Hu & Adams 2013)",
    .reads = SPH_BIT(PRED) | SPH_BIT(MASS) | SPH_BIT(RHO) | SPH_RES_LISTS,
    .writes = SPH_BIT(POS) | SPH_BIT(DRIFT),
    .group = SPH_GROUP_INTEGRATE,
    .highlight = NULL,
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
