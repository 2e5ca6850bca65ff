/* Pass: pressure force, as an acceleration a = F / (rho dV).
 *   symmetric: a_i = - sum_j m_j (p_i / rho_i^2 + p_j / rho_j^2) grad W_ij
 *              (from the Lagrangian; the pair terms are equal and opposite,
 *              so total momentum is conserved exactly up to round-off)
 *   shared:    a_i = - (1 / rho_i) sum_j (m_j / rho_j) (p_i + p_j) / 2 grad W_ij
 *              (the seed's form, Mueller 2003; m_i a_i != -m_j a_j when the
 *              densities differ, so momentum drifts)
 * grad W_ij = W'(r) (x_i - x_j) / r. Coincident particles get a direction
 * (see below), else they would never separate. */
#include "sph_search.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return (def->effects & SPH_EFFECT(PRESSURE)) ? NULL : "effects do not list pressure";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "%s form, gradient of the %s kernel%s", sph_pressure_form_names[def->pressure_form],
             sph_kernel_names[def->kernel_pressure], sph_scene_wall_volume(def) ? ", walls push back" : "");
}

/* The force on one particle; dim and dbl are constants (SPH_SPECIALISE). */
static inline void pressure_one(const sph_sim *sim, const sph_kernel *k, int i, const int dim, const bool dbl)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const bool symmetric = sim->def.pressure_form == SPH_PFORM_SYMMETRIC;
    const float r_min = SPH_KERNEL_R_MIN * k->h; /* below this, particles count as coincident */
    const float *per = sim->period, *iper = sim->inv_period;
    const float rho_i = P->rho[i], p_i = P->p[i];
    const float pi_over = p_i / (rho_i * rho_i);
    float xi[3], af[3] = {0, 0, 0};
    double ad[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) xi[d] = P->pred[d][i];
    for (uint32_t e = S->nbr_start[i]; e < S->nbr_start[i + 1]; e++) {
        uint32_t j = S->nbr[e];
        float dx[3], r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = sph_min_image(xi[d] - P->pred[d][j], per[d], iper[d]);
            r2 += dx[d] * dx[d];
        }
        float r;
        if (r2 < r_min * r_min) {
            /* Coincident (or nearly): the gradient has no direction. Push the
             * pair apart along x, in opposite senses for i and j so the pair
             * force stays equal and opposite (momentum kept). */
            dx[0] = (uint32_t)i < j ? -r_min : r_min;
            for (int d = 1; d < dim; d++) dx[d] = 0.0f;
            r = r_min;
        } else {
            r = sqrtf(r2);
        }
        float dw_over_r = sph_kernel_dw(k, r) / r;
        float rho_j = P->rho[j];
        float coef = symmetric ? P->mass[j] * (pi_over + P->p[j] / (rho_j * rho_j))
                               : P->mass[j] / rho_j * 0.5f * (p_i + P->p[j]) / rho_i;
        for (int d = 0; d < dim; d++) {
            float t = coef * dw_over_r * dx[d];
            if (dbl) ad[d] -= t;
            else af[d] -= t;
        }
    }
    float a[3];
    for (int d = 0; d < dim; d++) a[d] = dbl ? (float)ad[d] : af[d];
    if (sph_sim_wall_volume(sim)) {
        /* The force that makes the walls' density term conservative:
         * a = -(p_i / rho_i^2) grad(rho0 * hidden share), with the density
         * kernel, so walls neither add nor remove energy. */
        float grad[3];
        sph_wall_hidden(sim, &sim->k_density, i, grad);
        for (int d = 0; d < dim; d++) a[d] -= sim->def.rest_density * pi_over * grad[d];
    }
    for (int d = 0; d < dim; d++) P->acc_p[d][i] = a[d];
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_pressure;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE(dim, dbl, pressure_one, sim, &k, i);
}

const sph_pass sph_pass_pressure_force = {
    "pressure_force", "pressure force (acceleration)", "pred mass rho p nbr", "acc_p", skip_reason, describe, run,
};
