/* Pass: external forces and predicted positions (the seed's first pass).
 * v += g dt for each particle, then pred = x + v dt: neighbours and forces are
 * evaluated where the particle is about to be, which keeps stiff pressure
 * stable at larger time steps. Each particle touches only its own data.
 * At start-up (sph_start.h), g may be ramped in (gravity_ramp) and the
 * velocities damped first (damping_time): v = zeta_d v + zeta_g g dt. */
#include "sph_search.h"
#include "sph_start.h"
#include "sph_walls.h"

#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!(def->effects & SPH_EFFECT(GRAVITY)) && !sph_scene_needs_neighbours(def) && !(def->damping_time > 0))
        return "no gravity, no damping_time, and no effect needs predicted positions";
    return NULL;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    bool g = def->effects & SPH_EFFECT(GRAVITY), pred = sph_scene_needs_neighbours(def);
    char ramp[48] = "", damp[48] = "";
    if (g && def->gravity_ramp > 0) snprintf(ramp, sizeof ramp, " (ramped in over %g s)", def->gravity_ramp);
    if (def->damping_time > 0) snprintf(damp, sizeof damp, "%sdamping over %g s", g || pred ? " + " : "",
                                        def->damping_time);
    snprintf(out, (size_t)n, "%s%s%s%s%s", g ? "gravity" : "", ramp, g && pred ? " + " : "",
             pred ? "predicted positions" : "", damp);
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n;
    const float dt = sim->dt;
    const bool gravity = sim->def.effects & SPH_EFFECT(GRAVITY);
    const float gscale = sph_start_gravity_scale(sim), damp = sph_start_damping(sim);
    for (int d = 0; d < sim->dim; d++) {
        float *restrict v = P->vel[d];
        const float gdt = gravity ? sim->def.gravity[d] * gscale * dt : 0.0f;
        if (damp != 1.0f) {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++) v[i] *= damp;
        }
        if (gdt != 0.0f) {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++)
                if (!sph_is_wall(P, i)) v[i] += gdt; /* wall particles stand still */
        }
        if (P->pred[d]) {
            const float *restrict x = P->pos[d];
            float *restrict xp = P->pred[d];
            if (P->pos_r[d]) { /* position_sum = compensated: plus what x could not hold (integrate.c) */
                const float *restrict r = P->pos_r[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
                for (int i = 0; i < n; i++) xp[i] = x[i] + (v[i] * dt + r[i]);
            } else {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
                for (int i = 0; i < n; i++) xp[i] = x[i] + v[i] * dt;
            }
            if (sim->period[d] > 0) {
                const float lo = sim->def.domain_min[d], per = sim->period[d], iper = sim->inv_period[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
                for (int i = 0; i < n; i++) xp[i] = sph_wrap(xp[i], lo, per, iper);
            }
        }
    }
}

const sph_pass sph_pass_external = {
    .name = "external",
    .summary = "external forces and predicted positions",
    .reads = SPH_BIT(POS) | SPH_BIT(VEL), /* and pos_r when present (position_sum = compensated) */
    .writes = SPH_BIT(VEL) | SPH_BIT(PRED),
    .group = SPH_GROUP_FORCES_EXTERNAL,
    .highlight = "speed",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
