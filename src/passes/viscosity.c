/* Pass: viscosity, as an acceleration approximating nu lap v.
 *   laplacian: a_i = (nu rho0 / rho_i) sum_j m_j (v_j - v_i) / rho_j lap W_ij
 *              (Mueller 2003 with mu = nu rho0; pairwise equal and opposite)
 *   smoothing: a_i = nu (2 dim / M2) sum_j (m_j / rho_j) (v_j - v_i) W_ij
 *              (the seed's velocity smoothing; a kernel average differs from
 *              the centre value by (M2 / 2 dim) lap v, M2 = int r^2 W dV, so
 *              the factor makes both forms mean the same nu)
 * It reads vel and writes acc_v only: the seed's shader added the result to
 * the velocities it was still reading for other particles, so its outcome
 * depended on the order threads ran in. */
#include "sph_search.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return (def->effects & SPH_EFFECT(VISCOSITY)) ? NULL : "effects do not list viscosity";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "%s form, %s kernel, nu %g m^2/s", sph_viscosity_form_names[def->viscosity_form],
             sph_kernel_names[def->kernel_viscosity], def->viscosity);
}

/* The viscous acceleration of one particle; dim and dbl are constants. */
static inline void viscosity_one(const sph_sim *sim, const sph_kernel *k, int i, const int dim, const bool dbl)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const bool laplacian = sim->def.viscosity_form == SPH_VFORM_LAPLACIAN;
    const float nu = sim->def.viscosity;
    const float *per = sim->period, *iper = sim->inv_period;
    float xi[3], vi[3], af[3] = {0, 0, 0};
    double ad[3] = {0, 0, 0};
    for (int d = 0; d < dim; d++) {
        xi[d] = P->pred[d][i];
        vi[d] = P->vel[d][i];
    }
    for (uint32_t e = S->nbr_start[i]; e < S->nbr_start[i + 1]; e++) {
        uint32_t j = S->nbr[e];
        float r2 = 0;
        for (int d = 0; d < dim; d++) {
            float dx = sph_min_image(xi[d] - P->pred[d][j], per[d], iper[d]);
            r2 += dx * dx;
        }
        float r = sqrtf(r2);
        float w = laplacian ? sph_kernel_lap(k, r) : sph_kernel_w(k, r);
        float coef = P->mass[j] / P->rho[j] * w;
        for (int d = 0; d < dim; d++) {
            float t = coef * (P->vel[d][j] - vi[d]);
            if (dbl) ad[d] += t;
            else af[d] += t;
        }
    }
    float s = laplacian ? nu * sim->def.rest_density / P->rho[i] : nu * 2.0f * (float)dim / k->m2;
    for (int d = 0; d < dim; d++) P->acc_v[d][i] = s * (dbl ? (float)ad[d] : af[d]);
}

static void run(sph_sim *sim)
{
    const sph_kernel k = sim->k_viscosity;
    const int n = (int)sim->n, dim = sim->dim;
    const bool dbl = sim->def.accumulate == SPH_ACC_DOUBLE;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) SPH_SPECIALISE(dim, dbl, viscosity_one, sim, &k, i);
}

const sph_pass sph_pass_viscosity = {
    "viscosity", "viscous force (acceleration)", "pred mass rho vel nbr", "acc_v", skip_reason, describe, run,
};
