/* Pass: density by summation, rho_i = sum_j m_j W(|x_i - x_j|, h), the
 * particle itself included (its W(0) term is most of the sum at low
 * neighbour counts). */
#include "sph_sim.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return sph_scene_needs_density(def) ? NULL : "no effect needs density (density, pressure, viscosity)";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "summation with the %s kernel", sph_kernel_names[def->kernel_density]);
}

static void run(sph_sim *sim)
{
    const sph_particles *P = &sim->P;
    const sph_search_data *S = &sim->S;
    const sph_kernel k = sim->k_density;
    const int n = (int)sim->n, dim = sim->dim;
    const float w0 = sph_kernel_w(&k, 0.0f);
    float *restrict rho = P->rho;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        float sum = P->mass[i] * w0;
        for (uint32_t e = S->nbr_start[i]; e < S->nbr_start[i + 1]; e++) {
            uint32_t j = S->nbr[e];
            float r2 = 0;
            for (int d = 0; d < dim; d++) {
                float dx = P->pred[d][i] - P->pred[d][j];
                r2 += dx * dx;
            }
            sum += P->mass[j] * sph_kernel_w(&k, sqrtf(r2));
        }
        rho[i] = sum;
    }
}

const sph_pass sph_pass_density = {
    "density", "density by kernel summation", "pred mass nbr", "rho", skip_reason, describe, run,
};
