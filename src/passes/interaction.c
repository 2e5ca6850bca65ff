/* Pass: interaction, the mouse's push or pull. Particles within the radius of
 * the point get an acceleration towards it (pull) or away from it (push),
 * strongest at the point and fading linearly to 0 at the radius, minus their
 * own velocity's share so a pulled blob settles instead of orbiting. Active
 * only while the window's button is down (sim->interaction_active). */
#include "sph_sim.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

static const char *skip_reason(const sph_scene_def *def)
{
    return (def->effects & SPH_EFFECT(INTERACTION)) ? NULL : "effects do not list interaction";
}

static void describe(const sph_scene_def *def, char *out, int n)
{
    snprintf(out, (size_t)n, "push/pull within %g m, %g m/s^2 at the point", def->interaction_radius,
             def->interaction_strength);
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n, dim = sim->dim;
    if (!sim->interaction_active) {
        for (int d = 0; d < dim; d++) memset(P->acc_i[d], 0, (size_t)n * sizeof(float));
        return;
    }
    const float R = sim->def.interaction_radius, R2 = R * R;
    const float s = sim->def.interaction_strength * sim->interaction_sign;
    const float *c = sim->interaction_point;
    float *const *x = P->pred[0] ? P->pred : P->pos;
#pragma omp parallel for schedule(static) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        float dx[3] = {0, 0, 0}, r2 = 0;
        for (int d = 0; d < dim; d++) {
            dx[d] = c[d] - x[d][i];
            r2 += dx[d] * dx[d];
        }
        float a[3] = {0, 0, 0};
        if (r2 < R2) {
            float r = sqrtf(r2);
            float fall = 1.0f - r / R;
            float toward = r > 0 ? s * fall / r : 0.0f;
            for (int d = 0; d < dim; d++) a[d] = toward * dx[d] - fall * P->vel[d][i];
        }
        for (int d = 0; d < dim; d++) P->acc_i[d][i] = a[d];
    }
}

/* the speed a particle pulled from the edge of the radius reaches at the point */
static double speed_scale(const sph_scene_def *def)
{
    return sqrt(2.0 * fabs(def->interaction_strength) * def->interaction_radius);
}

static bool does_work(const sph_sim *sim) { return sim->interaction_active; }

const sph_pass sph_pass_interaction = {
    .name = "interaction",
    .summary = "push or pull around the mouse",
    .reads = SPH_BIT(PRED) | SPH_BIT(VEL),
    .writes = SPH_BIT(ACC_I),
    .group = SPH_GROUP_FORCES,
    .highlight = NULL,
    .skip_reason = skip_reason,
    .describe = describe,
    .run = run,
    .speed_scale = speed_scale,
    .does_work = does_work,
};
