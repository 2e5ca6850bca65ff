/* Pass: external forces and predicted positions (the seed's first pass).
 * v += g dt for each particle, then pred = x + v dt: neighbours and forces are
 * evaluated where the particle is about to be, which keeps stiff pressure
 * stable at larger time steps. Each particle touches only its own data. */
#include "sph_search.h"
#include "sph_walls.h"

#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    if (!(def->effects & SPH_EFFECT(GRAVITY)) && !sph_scene_needs_neighbours(def))
        return "no gravity, and no effect needs predicted positions";
    return NULL;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    bool g = def->effects & SPH_EFFECT(GRAVITY), pred = sph_scene_needs_neighbours(def);
    snprintf(out, (size_t)n, "%s%s%s", g ? "gravity" : "", g && pred ? " + " : "",
             pred ? "predicted positions" : "");
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n;
    const float dt = sim->dt;
    const bool gravity = sim->def.effects & SPH_EFFECT(GRAVITY);
    for (int d = 0; d < sim->dim; d++) {
        float *restrict v = P->vel[d];
        const float gdt = gravity ? sim->def.gravity[d] * dt : 0.0f;
        if (gdt != 0.0f) {
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++)
                if (!sph_is_wall(P, i)) v[i] += gdt; /* wall particles stand still */
        }
        if (P->pred[d]) {
            const float *restrict x = P->pos[d];
            float *restrict xp = P->pred[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++) xp[i] = x[i] + v[i] * dt;
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
    .reads = SPH_BIT(POS) | SPH_BIT(VEL),
    .writes = SPH_BIT(VEL) | SPH_BIT(PRED),
    .group = SPH_GROUP_FORCES_EXTERNAL,
    .highlight = "speed",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
