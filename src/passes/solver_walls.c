/* The wall particles' pressure under the solvers, [physics]
 * solver_wall_pressure = extrapolated (solver.h). With none, wall particles
 * hold no pressure and push back with the fluid particle's alone (the
 * energy's form, pcisph.c): the row next to a wall then holds the fluid up
 * with half the pair term and reads twice its pressure (96 to 101 % of
 * rho0 g H off at the floor of the hydrostatic tank, docs/accuracy.md).
 * Extrapolated: after each iteration's correction every wall particle w
 * takes Adami, Hu & Adams 2012's (J. Comput. Phys. 231:7057, eq. 27)
 *   q_w = (sum_f q_f W_wf + c g . sum_f r_wf W_wf) / sum_f W_wf,  r_wf = x_w - x_f,
 * over its fluid neighbours f at the step's predicted positions (the
 * solvers' sums are there), g the gravity of the step (ramped as the
 * fluid's), c = rho_rest for a pressure (PCISPH's p) and 1 for DFSPH's
 * kappa = p / rho_rest; the pair term (q_i + q_w) is then the interior's.
 * A wall particle with no fluid in reach holds 0. */
#include "solver.h"
#include "sph_start.h"

void sph_solver_wall_extrapolate(sph_sim *sim, float *q, float c, float floor)
{
    sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const int n = (int)sim->n, dim = sim->dim;
    const float gs = (sim->def.effects & SPH_EFFECT(GRAVITY)) ? c * sph_start_gravity_scale(sim) : 0.0f;
    float g[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) g[d] = gs * sim->def.gravity[d];
    /* reads q of fluid particles only, writes it for wall particles only: no particle reads a value written in
     * the same sweep */
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int w = 0; w < n; w++) {
        if (!sph_is_wall(P, w)) continue;
        double sw = 0, sq = 0;
        const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)w);
        for (uint32_t e = 0; e < row.n; e++) {
            const uint32_t f = sph_nbr_at(&row, e);
            if (sph_is_wall(P, f)) continue;
            float dx[3] = {0, 0, 0}, r2 = 0;
            double gr = 0;
            for (int d = 0; d < dim; d++) {
                dx[d] = sph_solver_dx(sim, P->pred[d][w] - P->pred[d][f], d);
                r2 += dx[d] * dx[d];
                gr += (double)g[d] * dx[d];
            }
            const double W = sph_kernel_w(&sim->k_density, sqrtf(r2));
            sw += W;
            sq += ((double)q[f] + gr) * W;
        }
        q[w] = sw > 0 ? fmaxf(floor, (float)(sq / sw)) : 0.0f;
    }
}
