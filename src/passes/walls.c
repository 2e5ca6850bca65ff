/* Pass: walls. The domain box reflects particles: a particle past a wall is
 * put back on it and its normal velocity is reversed and scaled by
 * wall_damping (the seed's damped reflection). Clamping the position, rather
 * than mirroring it, keeps every particle inside however fast it moved. */
#include "sph_walls.h"

#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return (def->effects & SPH_EFFECT(WALLS)) ? NULL : "effects do not list walls";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "damped reflection, keeps %g of the normal speed", def->wall_damping);
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n;
    const float damp = sim->def.wall_damping;
    for (int d = 0; d < sim->dim; d++) {
        if (sim->period[d] > 0) continue; /* a periodic axis has no walls */
        float *restrict x = P->pos[d], *restrict v = P->vel[d];
        const float lo = sim->def.domain_min[d], hi = sim->def.domain_max[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
        for (int i = 0; i < n; i++) {
            if (sph_is_wall(P, i)) continue; /* boundary particles live outside the box */
            if (x[i] < lo) {
                x[i] = lo;
                if (v[i] < 0) v[i] = -damp * v[i];
            } else if (x[i] > hi) {
                x[i] = hi;
                if (v[i] > 0) v[i] = -damp * v[i];
            }
        }
    }
}

const sph_pass sph_pass_walls = {
    .name = "walls",
    .summary = "domain walls: damped reflection",
    .reads = SPH_BIT(POS) | SPH_BIT(VEL),
    .writes = SPH_BIT(POS) | SPH_BIT(VEL),
    .group = SPH_GROUP_BOUNDARY,
    .highlight = "speed",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
