/* The time step: fixed, or chosen by the CFL conditions from the latest
 * maxima of speed and acceleration (which integration measures). Here, in
 * the core, because the step loop chooses dt before the first pass runs. */
#include <math.h>
#include <stdio.h>

#include "sph_sim.h"

/* The CFL conditions, with h_s = h / 2 the smoothing length:
 *   sound and flow:  dt <= cfl h_s / (c + |v|max)   (c = sqrt(k) with pressure and
 *                    pressure_solver = eos; c = 0 with pcisph or dfsph)
 *   forces:          dt <= cfl sqrt(h_s / |a|max)
 *   viscosity:       dt <= cfl h_s^2 / nu   (a form that reads nu: not artificial)
 *   capillary:       dt <= cfl sqrt(rho0 h_s^3 / (2 pi sigma))   (surface_tension = csf)
 * An explicit step longer than these lets a signal cross more than a particle
 * spacing in one step, and the scheme blows up. */
float sph_time_step_limit(const sph_sim *sim, float cfl, const char **which)
{
    const sph_scene_def *def = &sim->def;
    double hs = 0.5 * def->h, dt = INFINITY;
    const char *w = "none";
    /* an incompressible solver (pcisph, dfsph) has no speed of sound: the flow alone limits dt */
    const bool eos = def->pressure_solver == SPH_PSOLVER_EOS;
    double c = (def->effects & SPH_EFFECT(PRESSURE)) && eos ? sqrt(def->stiffness) : 0.0;
    double speed = c + sim->max_speed;
    if (speed > 0) {
        dt = cfl * hs / speed;
        w = eos ? "sound and flow: dt <= cfl (h/2) / (c + |v|max)"
                : "flow (incompressible solver, no sound speed): dt <= cfl (h/2) / |v|max";
    }
    if (sim->max_acc > 0 && cfl * sqrt(hs / sim->max_acc) < dt) {
        dt = cfl * sqrt(hs / sim->max_acc);
        w = "forces: dt <= cfl sqrt((h/2) / |a|max)";
    }
    /* not under viscosity_form = artificial, which reads alpha, not nu (a nu left in such a scene shortened the
     * step of a run it did not otherwise touch) */
    if ((def->effects & SPH_EFFECT(VISCOSITY)) && def->viscosity_form != SPH_VFORM_ARTIFICIAL && def->viscosity > 0 &&
        cfl * hs * hs / def->viscosity < dt) {
        dt = cfl * hs * hs / def->viscosity;
        w = "viscosity: dt <= cfl (h/2)^2 / nu";
    }
    /* capillary waves as short as h_s (Brackbill, Kothe & Zemach 1992, eq. 61): their speed
     * grows as 1/sqrt(wavelength), so no other condition bounds them */
    if ((def->surface_tension == SPH_STENSION_CSF || def->surface_tension == SPH_STENSION_STRESS) && def->sigma > 0) {
        double cap = cfl * sqrt(def->rest_density * hs * hs * hs / (2.0 * 3.14159265358979 * def->sigma));
        if (cap < dt) dt = cap, w = "capillary: dt <= cfl sqrt(rho0 (h/2)^3 / (2 pi sigma))";
    }
    if (which) *which = w;
    return (float)dt;
}

/* The step: fixed with cfl = 0; otherwise the CFL limit, within [dt_min, dt]. */
float sph_time_step_choose(const sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    float dt = def->dt;
    if (def->cfl > 0) {
        dt = fminf(def->dt, sph_time_step_limit(sim, def->cfl, NULL));
        if (!(dt >= def->dt_min)) dt = def->dt_min; /* also catches NaN from a blown-up state */
    }
    /* A run by time ends on its end: the last step is stretched by at most 0.1 % to reach it (a float dt
     * such as 0.0002 is a little short, so N steps of it end 2.5e-9 s before N dt and left a sliver of a step),
     * and a remainder between one and two steps is split into two equal ones, so no step is a sliver. */
    double left = sim->t_end - sim->t;
    if (sim->t_end > 0 && left > 0) {
        if (left <= (double)dt * (1.0 + 1e-3))
            dt = (float)left;
        else if (left < 2.0 * (double)dt)
            dt = (float)(0.5 * left);
    }
    return dt;
}

void sph_sim_end_at(sph_sim *sim, double t_end)
{
    sim->t_end = t_end > 0 ? t_end : 0.0;
    if (sim->next_pass == 0) sim->dt = sph_time_step_choose(sim); /* the coming step may be the last */
}

bool sph_sim_reached(const sph_sim *sim, double t_end)
{
    return sim->t >= t_end - 1e-12;
}

const char *sph_sim_dt_warning(const sph_sim *sim, char *buf, size_t n)
{
    const float ref = 0.4f;
    const char *which;
    if (sim->def.cfl > 0) {
        /* The adaptive step never goes below dt_min: where the CFL limit is
         * lower, each step is longer than the scheme allows (a block at 1e6 m/s
         * moved 2.5 h a step with nothing said). */
        float limit = sph_time_step_limit(sim, sim->def.cfl, &which);
        if (!(limit < sim->def.dt_min)) return NULL;
        snprintf(buf, n,
                 "the adaptive step is held at dt_min = %g s, above the CFL condition of %s with cfl = %g at step "
                 "%llu, which allows about %.3g s: lower [time] dt_min",
                 sim->def.dt_min, which, sim->def.cfl, (unsigned long long)sim->step, limit);
        return buf;
    }
    float limit = sph_time_step_limit(sim, ref, &which);
    if (!(sim->def.dt > limit)) return NULL;
    snprintf(buf, n,
             "fixed dt = %g s breaks the CFL condition of %s with cfl = %g at step %llu; the largest stable dt is "
             "about %.3g s: lower [time] dt, or set [time] cfl = 0.4 for an adaptive step",
             sim->def.dt, which, ref, (unsigned long long)sim->step, limit);
    return buf;
}

const char *sph_sim_length_warning(const sph_sim *sim, double until, char *buf, size_t n)
{
    if (!(until >= 0 && sim->dt > 0 && (until - sim->t) / sim->dt > 1e9)) return NULL;
    snprintf(buf, n, "at the first time step (dt = %.3g s) reaching t = %g s takes about %.3g steps", sim->dt, until,
             (until - sim->t) / sim->dt);
    return buf;
}

const char *sph_time_step_reason(const sph_sim *sim, char *buf, size_t n)
{
    const sph_scene_def *def = &sim->def;
    if (def->cfl <= 0) {
        snprintf(buf, n, "fixed ([time] cfl = 0)");
        return buf;
    }
    const char *which;
    float limit = sph_time_step_limit(sim, def->cfl, &which);
    if (!(limit < def->dt))
        snprintf(buf, n, "the cap [time] dt = %g s (CFL allows %.3g s: %s)", def->dt, limit, which);
    else if (!(limit >= def->dt_min))
        snprintf(buf, n, "the floor [time] dt_min = %g s", def->dt_min);
    else
        snprintf(buf, n, "CFL %g, %s", def->cfl, which);
    return buf;
}
