/* Pass: integration, symplectic Euler: v += dt (a_pressure + a_viscosity + a_interaction),
 * then x += dt v with the new v (gravity was added to v by the external
 * pass); positions on periodic axes are wrapped back into the domain. Also measures the largest speed and acceleration, which the CFL
 * time step of the next step needs. */
#include "sph_search.h"

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

/* The CFL conditions, with h_s = h / 2 the smoothing length:
 *   sound and flow:  dt <= cfl h_s / (c + |v|max)   (c = sqrt(k) with pressure)
 *   forces:          dt <= cfl sqrt(h_s / |a|max)
 *   viscosity:       dt <= cfl h_s^2 / nu
 * An explicit step longer than these lets a signal cross more than a particle
 * spacing in one step, and the scheme blows up. */
float sph_time_step_limit(const sph_sim *sim, float cfl, const char **which)
{
    const sph_scene_def *def = &sim->def;
    double hs = 0.5 * def->h, dt = INFINITY;
    const char *w = "none";
    double c = (def->effects & SPH_EFFECT(PRESSURE)) ? sqrt(def->stiffness) : 0.0;
    double speed = c + sim->max_speed;
    if (speed > 0) {
        dt = cfl * hs / speed;
        w = "sound and flow: dt <= cfl (h/2) / (c + |v|max)";
    }
    if (sim->max_acc > 0 && cfl * sqrt(hs / sim->max_acc) < dt) {
        dt = cfl * sqrt(hs / sim->max_acc);
        w = "forces: dt <= cfl sqrt((h/2) / |a|max)";
    }
    if ((def->effects & SPH_EFFECT(VISCOSITY)) && def->viscosity > 0 && cfl * hs * hs / def->viscosity < dt) {
        dt = cfl * hs * hs / def->viscosity;
        w = "viscosity: dt <= cfl (h/2)^2 / nu";
    }
    if (which) *which = w;
    return (float)dt;
}

/* The step: fixed with cfl = 0; otherwise the CFL limit, within [dt_min, dt]. */
float sph_time_step_choose(const sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    if (def->cfl <= 0) return def->dt;
    float dt = fminf(def->dt, sph_time_step_limit(sim, def->cfl, NULL));
    if (!(dt >= def->dt_min)) dt = def->dt_min; /* also catches NaN from a blown-up state */
    return dt;
}

const char *sph_sim_dt_warning(const sph_sim *sim, char *buf, size_t n)
{
    const float ref = 0.4f;
    if (sim->def.cfl > 0) return NULL;
    const char *which;
    float limit = sph_time_step_limit(sim, ref, &which);
    if (!(sim->def.dt > limit)) return NULL;
    snprintf(buf, n,
             "fixed dt = %g s breaks the CFL condition of %s with cfl = %g at step %llu; the largest stable dt is "
             "about %.3g s: lower [time] dt, or set [time] cfl = 0.4 for an adaptive step",
             sim->def.dt, which, ref, (unsigned long long)sim->step, limit);
    return buf;
}

static void run(sph_sim *sim)
{
    sph_particles *P = &sim->P;
    const int n = (int)sim->n, dim = sim->dim;
    const float dt = sim->dt;
    const bool gravity = sim->def.effects & SPH_EFFECT(GRAVITY);
    float g2 = 0;
    for (int d = 0; d < dim; d++) g2 += gravity ? sim->def.gravity[d] * sim->def.gravity[d] : 0.0f;
    float vmax2 = 0, amax2 = 0;
#pragma omp parallel for schedule(static) reduction(max : vmax2, amax2) if (n > SPH_PARALLEL_MIN)
    for (int i = 0; i < n; i++) {
        float v2 = 0, a2 = 0;
        for (int d = 0; d < dim; d++) {
            float a = (P->acc_p[d] ? P->acc_p[d][i] : 0.0f) + (P->acc_v[d] ? P->acc_v[d][i] : 0.0f) +
                      (P->acc_i[d] ? P->acc_i[d][i] : 0.0f);
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
    "integrate", "symplectic Euler: velocities, then positions", "vel acc_p acc_v acc_i", "vel pos", skip_reason,
    describe, run,
};
