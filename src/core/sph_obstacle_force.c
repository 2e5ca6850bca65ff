/* The force the fluid exerts on each obstacle (sph_obstacles.h).
 *
 * The pressure_force and viscosity passes give every fluid particle f the
 * pair terms of its wall neighbours w; each pair force is equal and opposite
 * (both passes' forms are antisymmetric in f and w), so by Newton's third law
 * the fluid pushes obstacle k with
 *   F_k = - sum_{w in k} sum_{f fluid} m_f a_{f <- w},
 * the same pair terms evaluated here from the wall particles' side with the
 * passes' formulas (pressure_force.c, viscosity.c): symmetric or shared
 * pressure, laplacian, smoothing, morris or artificial viscosity; with a
 * pressure solver, its pair term (pcisph.c, dfsph.c: the wall particle's own
 * pressure 0, or the fluid's with solver_wall_pressure = extrapolated). It reads
 * the state the latest step's force passes read (predicted positions,
 * density, pressure, vel_visc); the fluid's velocity, which integration has
 * advanced since, is taken back to what the viscosity pass saw, v - dt a
 * (each step's gravity, g dt, is in it: at rest, no-slip walls resist that
 * much motion, 0.6% of the weight in the resting test). */
#include "sph_obstacles.h"

#include <math.h>
#include <string.h>

#include "sph_search.h"
#include "sph_walls.h"

/* m_f a_{f <- w}: the force wall particle w exerts on fluid particle f [N or N/m]. */
static void pair_force(const sph_sim *sim, uint32_t f, uint32_t w, const float vf[3], double out[3])
{
    const sph_particles *P = &sim->P;
    const sph_scene_def *def = &sim->def;
    const int dim = sim->dim;
    float dx[3] = {0, 0, 0}, r2 = 0; /* x_f - x_w */
    for (int d = 0; d < dim; d++) {
        dx[d] = P->pred[d][f] - P->pred[d][w];
        if (sim->period[d] > 0) dx[d] = sph_min_image(dx[d], sim->period[d], sim->inv_period[d]);
        r2 += dx[d] * dx[d];
    }
    const float r = sqrtf(r2), mf = P->mass[f];
    double a[3] = {0, 0, 0};
    const float rho_r = sim->solver.rho_rest;
    if (def->pressure_solver != SPH_PSOLVER_EOS && rho_r > 0 && r > SPH_KERNEL_R_MIN * def->h) {
        /* the solvers' pair term (pcisph.c, dfsph.c): the wall particle's own p or kappa is 0, or with
         * solver_wall_pressure = extrapolated the fluid's (solver_walls.c) */
        const float g = sph_kernel_dw(&sim->k_pressure, r) / r;
        float coef = 0.0f;
        if (def->pressure_solver == SPH_PSOLVER_PCISPH && P->p_pci)
            coef = P->mass[w] * (P->p_pci[f] + P->p_pci[w]) / (rho_r * rho_r);
        else if (def->pressure_solver == SPH_PSOLVER_DFSPH && P->kappa && P->kappa_v)
            coef = P->mass[w] * (P->kappa_v[f] + P->kappa[f] + P->kappa_v[w] + P->kappa[w]) / rho_r;
        for (int d = 0; d < dim; d++) a[d] -= (double)coef * g * dx[d];
    } else if (P->acc_p[0] && r > SPH_KERNEL_R_MIN * def->h) { /* pressure_force.c */
        const float g = sph_kernel_dw(&sim->k_pressure, r) / r;
        const float coef = def->pressure_form == SPH_PFORM_SYMMETRIC
                               ? P->mass[w] * (P->p_rho2[f] + P->p_rho2[w])
                               : P->vol[w] * 0.5f * (P->p[f] + P->p[w]) / P->rho[f];
        for (int d = 0; d < dim; d++) a[d] -= (double)coef * g * dx[d];
    }
    if (P->acc_v[0]) { /* viscosity.c */
        const sph_kernel *k = &sim->k_viscosity;
        const float nu = def->viscosity, rho_f = P->rho[f];
        const bool both = def->viscosity_form == SPH_VFORM_MORRIS_ARTIFICIAL;
        if (def->viscosity_form == SPH_VFORM_ARTIFICIAL || both) {
            const float hs = 0.5f * k->h, ach = def->alpha * sqrtf(def->stiffness) * hs, eps2 = 0.01f * hs * hs;
            float vx = 0;
            for (int d = 0; d < dim; d++) vx += (vf[d] - P->vel[d][w]) * dx[d];
            if (vx < 0.0f && r > 0.0f) {
                float pi_ij = -ach * vx / (0.5f * (rho_f + P->rho[w]) * (r2 + eps2));
                float c = -P->mass[w] * pi_ij * sph_kernel_dw(&sim->k_pressure, r) / r;
                for (int d = 0; d < dim; d++) a[d] += (double)c * dx[d];
            }
        }
        if (def->viscosity_form != SPH_VFORM_ARTIFICIAL) {
            float coef;
            if (def->viscosity_form == SPH_VFORM_MORRIS || both)
                coef = nu * -P->mass[w] * (rho_f + P->rho[w]) / (rho_f * P->rho[w]) * r * sph_kernel_dw(k, r) /
                       (r2 + 1e-4f * k->h * k->h);
            else if (def->viscosity_form == SPH_VFORM_LAPLACIAN)
                coef = nu * def->rest_density / rho_f * P->vol[w] * sph_kernel_lap(k, r);
            else
                coef = nu * 2.0f * (float)dim / k->m2 * P->vol[w] * sph_kernel_w(k, r);
            for (int d = 0; d < dim; d++) a[d] += (double)coef * (P->vel_visc[d][w] - vf[d]);
        }
    }
    for (int d = 0; d < 3; d++) out[d] = (double)mf * a[d];
}

int sph_obstacle_forces(const sph_sim *sim, double force[][3])
{
    const int no = sim->def.n_obstacles;
    for (int k = 0; k < no; k++) force[k][0] = force[k][1] = force[k][2] = 0.0;
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    if (!P->obstacle || !S->nbr_start) return no;
    sph_sim_sync(sim, SPH_SYNC_ALL);
    /* has integration run since the forces were computed? */
    const bool undo = sim->step > 0 && sim->in_pipeline[SPH_PASS_INTEGRATE] && sim->enabled[SPH_PASS_INTEGRATE] &&
                      (sim->next_pass == 0 || sim->next_pass > SPH_PASS_INTEGRATE);
    for (uint32_t w = 0; w < sim->n; w++) {
        int k = (int)P->obstacle[w] - 1;
        if (k < 0 || k >= no) continue;
        const sph_nbr_row row = sph_nbr_row_of(S, (uint32_t)(w));
        for (uint32_t e = 0; e < row.n; e++) {
            uint32_t f = sph_nbr_at(&row, e);
            if (sph_is_wall(P, f)) continue; /* walls do not push walls */
            float vf[3] = {0, 0, 0};
            for (int d = 0; d < sim->dim; d++) {
                float a = 0;
                for (int q = 0; undo && q < SPH_FIELD_COUNT; q++) /* as integrate sums them */
                    if ((SPH_MASK_ACCELERATIONS & SPH_FIELD_BIT(q)) && P->field[q][0]) a += P->field[q][d][f];
                vf[d] = P->vel[d][f] - sim->dt * a;
            }
            double on_f[3];
            pair_force(sim, f, w, vf, on_f);
            for (int d = 0; d < 3; d++) force[k][d] -= on_f[d];
        }
    }
    return no;
}
