/* Pass: integration, symplectic Euler: v += dt (the sum of every acceleration
 * field of the registry: pressure, viscosity, interaction, ...),
 * then x += dt v with the new v (gravity was added to v by the external
 * pass); positions on periodic axes are wrapped back into the domain. Also measures the largest speed and acceleration, which the CFL
 * time step of the next step needs. */
#include "sph_search.h"
#include "sph_walls.h"

#include <math.h>
#include <stdio.h>

static const char *skip_reason(const sph_scene_def *def)
{
    (void)def;
    return NULL;
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    if (def->cfl > 0)
        snprintf(out, (size_t)n, "symplectic Euler, adaptive dt (CFL %g, dt <= %g s)", def->cfl, def->dt);
    else
        snprintf(out, (size_t)n, "symplectic Euler, fixed dt %g s", def->dt);
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n, dim = sim->dim;
    const float dt = sim->dt;
    const bool gravity = sim->def.effects & SPH_EFFECT(GRAVITY);
    float g2 = 0;
    for (int d = 0; d < dim; d++) g2 += gravity ? sim->def.gravity[d] * sim->def.gravity[d] : 0.0f;
    /* the acceleration fields this scene has, in registry order */
    const float *acc[SPH_FIELD_COUNT][3];
    int n_acc = 0;
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if ((SPH_MASK_ACCELERATIONS & SPH_FIELD_BIT(f)) && P->field[f][0]) {
            for (int d = 0; d < 3; d++) acc[n_acc][d] = P->field[f][d];
            n_acc++;
        }
    float vmax2 = 0, amax2 = 0;
#pragma omp parallel for schedule(static) reduction(max : vmax2, amax2) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        if (sph_is_wall(P, i)) continue; /* wall particles never move */
        float v2 = 0, a2 = 0;
        for (int d = 0; d < dim; d++) {
            float a = 0.0f;
            for (int k = 0; k < n_acc; k++) a += acc[k][d][i];
            float v = P->vel[d][i] + dt * a;
            P->vel[d][i] = v;
            P->pos[d][i] += dt * v;
            v2 += v * v;
            a2 += a * a;
        }
        vmax2 = fmaxf(vmax2, v2);
        amax2 = fmaxf(amax2, a2);
    }
    for (int d = 0; d < dim; d++) /* periodic axes: back into the domain */
        if (sim->period[d] > 0) {
            const float lo = sim->def.domain_min[d], per = sim->period[d], iper = sim->inv_period[d];
            float *restrict x = P->pos[d];
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
            for (int i = 0; i < n; i++) x[i] = sph_wrap(x[i], lo, per, iper);
        }
    sim->max_speed = sqrtf(vmax2);
    sim->max_acc = sqrtf(amax2) + sqrtf(g2);
}

const sph_pass sph_pass_integrate = {
    .name = "integrate",
    .summary = "symplectic Euler: velocities, then positions",
    .reads = SPH_BIT(VEL) | SPH_MASK_ACCELERATIONS,
    .writes = SPH_BIT(VEL) | SPH_BIT(POS),
    .group = SPH_GROUP_INTEGRATE,
    .highlight = "speed",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
