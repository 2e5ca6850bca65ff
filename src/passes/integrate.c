/* Pass: integration, symplectic Euler: v += dt (the sum of every acceleration
 * field of the registry: pressure, viscosity, interaction, ...),
 * then x += dt v with the new v (gravity was added to v by the external
 * pass); positions on periodic axes are wrapped back into the domain. Also measures the largest speed and acceleration, which the CFL
 * time step of the next step needs.
 * With position_sum = compensated the sum x += dt v is Kahan's (Kahan 1965, Comm. ACM 8:40; Higham 2002, sec.
 * 4.3): pos_r keeps what the float x could not hold of the moves and adds it to the next one (and the external
 * pass to the predicted position). Without it a settled fluid's moves, 1e-9 to 1e-8 m a step, fall under half a
 * float spacing of x near 0.15 m (1.5e-8 m / 2) and are rounded away, so the positions stop following the
 * velocity the continuity equation integrates (docs/accuracy.md, "hydrostatic"). */
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
    const char *sum = def->position_sum == SPH_POSSUM_COMPENSATED ? ", compensated positions" : "";
    if (def->cfl > 0)
        snprintf(out, (size_t)n, "symplectic Euler, adaptive dt (CFL %g, dt <= %g s)%s", def->cfl, def->dt, sum);
    else
        snprintf(out, (size_t)n, "symplectic Euler, fixed dt %g s%s", def->dt, sum);
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
    float *const *pos_r = P->pos_r[0] ? P->pos_r : NULL; /* position_sum = compensated */
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
            if (pos_r) { /* x + r holds the sum of the moves dt v to a float's precision of r */
                const float y = dt * v + pos_r[d][i], x = P->pos[d][i], t = x + y;
                pos_r[d][i] = y - (t - x);
                P->pos[d][i] = t;
            } else {
                P->pos[d][i] += dt * v;
            }
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
    /* and pos_r with position_sum = compensated: read and written when present, not listed in reads (a
     * pass's reads exist in every scene that runs it) */
    .reads = SPH_BIT(VEL) | SPH_MASK_ACCELERATIONS,
    .writes = SPH_BIT(VEL) | SPH_BIT(POS) | SPH_BIT(POS_R),
    .group = SPH_GROUP_INTEGRATE,
    .highlight = "speed",
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
};
