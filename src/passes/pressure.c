/* Pass: pressure from the equation of state.
 *   linear (the seeds): p = k (rho - rho0)
 *   tait:               p = (k rho0 / gamma) ((rho / rho0)^gamma - 1)
 * Both have the speed of sound c = sqrt(k) at rest density. With
 * negative_pressure = clamp, p < 0 is set to 0: no attraction between
 * particles below rest density (at a free surface), so no tensile clumping.
 * rho0 is sim->eos_rho0: rest_density, or with eos_rest = lattice the density
 * the finest lattice sums to at rest, so a block on the lattice starts at p = 0. */
#include "sph_sim.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!(def->effects & SPH_EFFECT(PRESSURE))) return "effects do not list pressure";
    return def->pressure_solver != SPH_PSOLVER_EOS ? "pressure_solver is not eos: its own pass makes the pressure"
                                                   : NULL;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    const char *rest = def->eos_rest == SPH_EOSREST_LATTICE ? ", rho0 the lattice's" : "";
    if (def->eos == SPH_EOS_TAIT)
        snprintf(out, (size_t)n, "tait, gamma %g, k %g m^2/s^2%s%s", def->tait_gamma, def->stiffness,
                 def->negative_pressure == SPH_NEGP_CLAMP ? ", p >= 0" : "", rest);
    else
        snprintf(out, (size_t)n, "linear, k %g m^2/s^2%s%s", def->stiffness,
                 def->negative_pressure == SPH_NEGP_CLAMP ? ", p >= 0" : "", rest);
}

static void run(sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    const float *restrict rho = sim->P.rho;
    float *restrict p = sim->P.p;
    const int n = (int)sim->n;
    const float k = def->stiffness, rho0 = sim->eos_rho0, inv_rho0 = 1.0f / rho0; /* rest_density or the lattice's */
    const float clamp = def->negative_pressure == SPH_NEGP_CLAMP ? 0.0f : -INFINITY;
    if (def->eos == SPH_EOS_TAIT) {
        const float gamma = def->tait_gamma, B = k * rho0 / gamma;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) p[i] = fmaxf(clamp, B * (powf(rho[i] * inv_rho0, gamma) - 1.0f));
    } else {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) p[i] = fmaxf(clamp, k * (rho[i] - rho0));
    }
    float *restrict q = sim->P.p_rho2;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) q[i] = p[i] / (rho[i] * rho[i]);
}

const sph_pass sph_pass_pressure = {
    .name = "pressure",
    .summary = "pressure from the equation of state",
    .reads = SPH_BIT(RHO),
    .writes = SPH_BIT(P) | SPH_BIT(PRHO2),
    .group = SPH_GROUP_DENSITY,
    .highlight = "pressure",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
