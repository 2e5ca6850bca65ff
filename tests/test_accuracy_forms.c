/* Monaghan's artificial viscosity (viscosity_form = artificial, and beside
 * Morris's laminar term in morris-artificial) and the
 * start-up ramps ([physics] gravity_ramp, damping_time; src/core/sph_start.h).
 * Each test compares against the same scene without the feature, so it
 * would fail if the feature did nothing. (On GL:
 * gl_backend/passes_match_cpu_artificial_viscosity_ramps.) */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_walls.h"
#include "test_util.h"

/* Two blocks 0.2 m wide side by side in zero gravity, moving along x at
 * +-speed (speed > 0: towards each other), jittered. */
static const char *const BLOCKS =
    "[scene]\ndimension=2\neffects=%s\njitter=0.1\n"
    "[domain]\nmin=-1 -1\nmax=1 1\n"
    "[fluid left]\nmin=-0.2 0\nmax=0 0.2\nspacing=0.01\nvelocity=%g 0\n"
    "[fluid right]\nmin=0 0\nmax=0.2 0.2\nspacing=0.01\nvelocity=%g 0\n"
    "[physics]\nstiffness=400\nnegative_pressure=clamp\nviscosity_form=%s\nalpha=%g\ngravity=0 0 0\n"
    "[kernels]\nh=0.02\n[time]\ndt=0.0005\ncfl=0.3\n";

static sph_sim *blocks(const char *effects, double speed, const char *form, double alpha)
{
    char ini[1024];
    snprintf(ini, sizeof ini, BLOCKS, effects, speed, -speed, form, alpha);
    return test_sim(ini, 2);
}

static double acc_v_scale(const sph_sim *sim)
{
    double s = 0;
    for (uint32_t i = 0; i < sim->n; i++) s = fmax(s, hypot(sim->P.acc_v[0][i], sim->P.acc_v[1][i]));
    return s;
}

/* Pairwise equal and opposite: the viscous accelerations carry no net momentum. */
Test(artificial_viscosity, conserves_momentum)
{
    sph_sim *sim = blocks("pressure viscosity", 1.0, "artificial", 0.5);
    for (int s = 0; s < 20; s++) sph_sim_step(sim);
    const sph_particles *P = &sim->P;
    for (int d = 0; d < 2; d++) {
        double net = 0, scale = 0;
        for (uint32_t i = 0; i < sim->n; i++) {
            net += P->mass[i] * P->acc_v[d][i];
            scale += P->mass[i] * fabs(P->acc_v[d][i]);
        }
        cr_assert_gt(scale, 0.0, "no viscous force at all");
        cr_assert(fabs(net) < 1e-5 * scale, "axis %d: net %g of %g", d, net, scale);
    }
    sph_sim_destroy(sim);
}

/* Blocks that separate: every pair is receding (across the gap) or at rest
 * relative to each other (within a block), so Monaghan's form gives exactly
 * nothing, where the Laplacian form does act across the gap; approaching
 * blocks do feel the artificial form. */
Test(artificial_viscosity, no_force_between_receding_pairs)
{
    sph_sim *apart = blocks("viscosity", -1.0, "artificial", 0.5);
    sph_sim_step(apart);
    cr_assert_eq(acc_v_scale(apart), 0.0, "receding pairs got a force of up to %g m/s^2", acc_v_scale(apart));
    sph_sim_destroy(apart);

    const char *forms[] = {"laplacian", "artificial"};
    const double speeds[] = {-1.0, 1.0};
    for (int k = 0; k < 2; k++) {
        sph_sim *sim = blocks("viscosity", speeds[k], forms[k], 0.5);
        sph_sim_step(sim);
        cr_assert_gt(acc_v_scale(sim), 1.0, "%s form, speed %g: no force (%g)", forms[k], speeds[k],
                     acc_v_scale(sim));
        sph_sim_destroy(sim);
    }
}

/* A head-on collision of two blocks at 1 m/s: kinetic plus compression
 * energy after 0.1 s, with alpha = 0.5 and with alpha = 0 (the form with no
 * viscosity at all). The viscosity must dissipate a good share of it. */
Test(artificial_viscosity, dissipates_energy_in_a_collision)
{
    double e[2], e0 = 0;
    const double alphas[] = {0.0, 0.5};
    for (int k = 0; k < 2; k++) {
        sph_sim *sim = blocks("pressure viscosity", 1.0, "artificial", alphas[k]);
        sph_stats s;
        sph_sim_stats(sim, &s);
        e0 = s.ekin;
        while (sim->t < 0.1 && !sim->alarm.raised) sph_sim_step(sim);
        cr_assert(!sim->alarm.raised, "alpha %g: the watchdog stopped the run", alphas[k]);
        sph_sim_stats(sim, &s);
        e[k] = s.ekin + s.eint;
        sph_sim_destroy(sim);
    }
    cr_assert_gt(e0, 0.0);
    cr_assert_lt(e[1], 0.8 * e[0], "energy at 0.1 s: %g with alpha 0.5, %g without (start %g)", e[1], e[0], e0);
    cr_assert_lt(e[1], 0.8 * e0, "energy at 0.1 s: %g with alpha 0.5, start %g", e[1], e0);
}

/* ---- morris-artificial: Morris's laminar term and Monaghan's together ---- */

/* The approaching blocks above with the wendland kernel for the viscosity
 * (morris needs W'(0) = 0) and nu given: the first step in each form. */
static sph_sim *blocks_nu(const char *form, double nu)
{
    char ini[1200], with[1300];
    snprintf(ini, sizeof ini, BLOCKS, "viscosity", 1.0, -1.0, form, 0.5);
    const char *k = strstr(ini, "[kernels]\n");
    cr_assert_not_null(k);
    snprintf(with, sizeof with, "%.*s[kernels]\nviscosity=wendland\n%s", (int)(k - ini), ini, k + strlen("[kernels]\n"));
    sph_scene_def def = test_scene(with);
    char set[64];
    snprintf(set, sizeof set, "physics.viscosity=%g", nu);
    sph_error err;
    cr_assert_eq(sph_scene_set(&def, set, &err), SPH_ERR_OK, "%s", err.msg);
    sph_sim *sim = NULL;
    cr_assert_eq(sph_sim_create(&def, 2, &sim, &err), SPH_ERR_OK, "%s", err.msg);
    sph_sim_step(sim);
    return sim;
}

/* The combined form is the sum of the two forms it names, particle by
 * particle, and both parts are large enough to be seen in the sum. */
Test(morris_artificial, is_the_sum_of_morris_and_artificial)
{
    sph_sim *m = blocks_nu("morris", 0.05), *a = blocks_nu("artificial", 0.05);
    sph_sim *both = blocks_nu("morris-artificial", 0.05);
    double sm = acc_v_scale(m), sa = acc_v_scale(a), worst = 0;
    cr_assert_gt(sm, 1e-2 * sa, "the morris part is too small to be seen: %g against %g", sm, sa);
    cr_assert_gt(sa, 1e-2 * sm, "the artificial part is too small to be seen: %g against %g", sa, sm);
    cr_assert_eq(both->n, m->n);
    for (uint32_t i = 0; i < both->n; i++)
        for (int d = 0; d < 2; d++)
            worst = fmax(worst, fabs(both->P.acc_v[d][i] - (m->P.acc_v[d][i] + a->P.acc_v[d][i])));
    cr_assert_lt(worst, 1e-5 * (sm + sa), "off the sum by up to %g m/s^2 (scales %g, %g)", worst, sm, sa);
    sph_sim_destroy(m);
    sph_sim_destroy(a);
    sph_sim_destroy(both);
}

/* A layer sliding at 1 m/s over a no-slip floor of wall particles (which
 * need the pressure effect), in zero gravity: Morris's term, fed the walls' mirrored velocity, brakes the row
 * next to the floor; Monaghan's alone brakes it far less. */
static double floor_drag(const char *form)
{
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=pressure viscosity walls\n"
             "[domain]\nmin=0 0\nmax=1 0.5\nwall_model=particles\nwall_slip=no\n"
             "[fluid layer]\nmin=0.3 0\nmax=0.7 0.1\nspacing=0.01\nvelocity=1 0\n"
             "[physics]\nstiffness=400\nviscosity=0.001\nviscosity_form=%s\nalpha=0.1\ngravity=0 0 0\n"
             "[kernels]\nh=0.03\nviscosity=wendland\npressure=wendland\ndensity=wendland\n[time]\ndt=0.0002\n",
             form);
    sph_sim *sim = test_sim(ini, 2);
    sph_sim_step(sim);
    double sum = 0;
    int n = 0;
    for (uint32_t i = 0; i < sim->n; i++) /* the bottom row, away from the layer's ends */
        if (!sph_is_wall(&sim->P, i) && sim->P.pos[1][i] < 0.01 && fabs(sim->P.pos[0][i] - 0.5) < 0.1) {
            sum += sim->P.acc_v[0][i];
            n++;
        }
    sph_sim_destroy(sim);
    cr_assert_gt(n, 5, "%s: no bottom row found", form);
    return sum / n; /* [m/s^2] mean, negative brakes */
}

Test(morris_artificial, brakes_a_layer_on_a_no_slip_floor)
{
    double art = floor_drag("artificial"), both = floor_drag("morris-artificial"), mor = floor_drag("morris");
    cr_assert_lt(mor, 0.0, "morris alone does not brake the bottom row: %g m/s^2", mor);
    cr_assert_lt(both, art + 0.5 * mor, "morris-artificial %g m/s^2, artificial %g, morris %g", both, art, mor);
    if (getenv("SPH_TEST_VERBOSE")) fprintf(stderr, "bottom row: artificial %g, morris %g, both %g m/s^2\n", art, mor, both);
}

/* ---- start-up ramps ---- */

/* One free particle under gravity, fixed dt = 1 ms. */
static const char *const FALL = "[scene]\ndimension=2\neffects=gravity\n"
                                "[domain]\nmin=0 0\nmax=1 100\n"
                                "[fluid a]\nmin=0.5 90\nmax=0.51 90.01\nspacing=0.01\n"
                                "[physics]\ngravity_ramp=%g\n[time]\ndt=0.001\n";

/* The ramp (taken at mid-step) adds almost nothing in the first step, half
 * of g dt in the step centred on T/2, and from T on exactly g dt per step, as
 * without a ramp; by then the particle has lost g T / 2 of speed to it. */
Test(start_ramps, gravity_ramp_reaches_exactly_g)
{
    char ini[512];
    snprintf(ini, sizeof ini, FALL, 0.021); /* T = 21 steps: the 11th is centred on T/2 */
    sph_sim *ramp = test_sim(ini, 1);
    snprintf(ini, sizeof ini, FALL, 0.0);
    sph_sim *full = test_sim(ini, 1);
    cr_assert_eq(ramp->n, 1u);
    const float g = -9.81f, dt = 0.001f;
    sph_sim_step(ramp);
    sph_sim_step(full);
    cr_assert(fabsf(ramp->P.vel[1][0]) < 0.01f * fabsf(g) * dt, "first step of the ramp: v = %g",
              ramp->P.vel[1][0]);
    while (ramp->t < 0.0099) { /* up to the step centred on T/2 */
        sph_sim_step(ramp);
        sph_sim_step(full);
    }
    float v0 = ramp->P.vel[1][0];
    sph_sim_step(ramp);
    sph_sim_step(full);
    float dv_mid = ramp->P.vel[1][0] - v0;
    cr_assert(fabsf(dv_mid - 0.5f * g * dt) < 1e-3f * fabsf(g) * dt, "dv at T/2: %g, want %g", dv_mid,
              0.5 * g * dt);
    while (ramp->t < 0.021) {
        sph_sim_step(ramp);
        sph_sim_step(full);
    }
    cr_assert(fabs(ramp->t - full->t) < 1e-9);
    float lost = ramp->P.vel[1][0] - full->P.vel[1][0];
    cr_assert(fabsf(lost + 0.5f * g * 0.021f) < 0.01f * fabsf(g * dt), "speed lost to the ramp %g, want %g", lost,
              -0.5 * g * 0.021);
    /* from the same state, both now step bit for bit alike */
    for (int d = 0; d < 2; d++) {
        ramp->P.vel[d][0] = full->P.vel[d][0];
        ramp->P.pos[d][0] = full->P.pos[d][0];
    }
    for (int s = 0; s < 5; s++) {
        sph_sim_step(ramp);
        sph_sim_step(full);
        cr_assert(ramp->P.vel[1][0] == full->P.vel[1][0] && ramp->P.pos[1][0] == full->P.pos[1][0],
                  "after T: v %.9g, without ramp %.9g", ramp->P.vel[1][0], full->P.vel[1][0]);
    }
    sph_sim_destroy(ramp);
    sph_sim_destroy(full);
}

/* A column of water at rest on the floor, periodic across, loaded by
 * gravity. The block is lifted 0.2 spacings so that at g = 0 it stays at
 * rest (max speed 0.02 m/s over 0.5 s): on the floor itself the volume wall
 * model over-counts the first row's density and the column jumps even
 * without gravity. With g switched on at once the column falls onto its own
 * compression and rings (max speed 0.3 m/s within 0.03 s, gH/c = 0.15 m/s);
 * with g ramped in over T = 0.2 s it is loaded quasi-statically. Compared
 * over the ramp itself, 0 <= t <= T: peak speed and peak kinetic energy.
 * (After T both columns move at 0.1-0.3 m/s, from the walls' density
 * errors, issue 13, not from the loading.) */
static void loading(double ramp, double *vmax, double *ekin_max)
{
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n"
             "[domain]\nmin=0 0\nmax=0.4 0.6\nperiodic=x\n"
             "[fluid water]\nmin=0 0.004\nmax=0.4 0.3\nspacing=0.02\n"
             "[physics]\nstiffness=400\nviscosity=0.01\nnegative_pressure=clamp\ngravity_ramp=%g\n"
             "[kernels]\nh=0.04\ndensity=cubic\npressure=cubic\nviscosity=cubic\n[time]\ndt=0.002\ncfl=0.4\n",
             ramp);
    sph_sim *sim = test_sim(ini, 2);
    *vmax = *ekin_max = 0;
    while (sim->t < 0.2 && !sim->alarm.raised) {
        sph_sim_step(sim);
        sph_stats s;
        sph_sim_stats(sim, &s);
        *vmax = fmax(*vmax, sim->max_speed);
        *ekin_max = fmax(*ekin_max, s.ekin);
    }
    cr_assert(!sim->alarm.raised, "ramp %g: the watchdog stopped the run", ramp);
    sph_sim_destroy(sim);
}

Test(start_ramps, gravity_ramp_loads_a_column_gently)
{
    double v_sudden, e_sudden, v_ramp, e_ramp;
    loading(0.0, &v_sudden, &e_sudden);
    loading(0.2, &v_ramp, &e_ramp);
    cr_assert_lt(v_ramp, 0.6 * v_sudden, "max speed while loading: %g m/s ramped, %g m/s sudden", v_ramp, v_sudden);
    cr_assert_lt(e_ramp, 0.3 * e_sudden, "peak kinetic energy while loading: %g J/m ramped, %g J/m sudden", e_ramp,
                 e_sudden);
}

/* A jittered block thrown at 0.5 m/s into a box: with damping_time = 0.05 s
 * its kinetic energy falls step by step at first and is near zero at 0.05 s;
 * without damping it keeps most of it. */
Test(start_ramps, damping_removes_kinetic_energy)
{
    const double times[] = {0.0, 0.05};
    double ekin[2], e0 = 0;
    for (int k = 0; k < 2; k++) {
        char ini[1024];
        snprintf(ini, sizeof ini,
                 "[scene]\ndimension=2\neffects=pressure viscosity walls\njitter=0.1\n"
                 "[domain]\nmin=0 0\nmax=1 1\n"
                 "[fluid a]\nmin=0.3 0.3\nmax=0.5 0.5\nspacing=0.01\nvelocity=0.5 0.2\n"
                 "[physics]\nstiffness=400\nnegative_pressure=clamp\ndamping_time=%g\n"
                 "[kernels]\nh=0.02\n[time]\ndt=0.001\ncfl=0.4\n",
                 times[k]);
        sph_sim *sim = test_sim(ini, 2);
        sph_stats s;
        sph_sim_stats(sim, &s);
        e0 = s.ekin;
        double prev = e0;
        int steps = 0;
        while (sim->t < 0.05 && !sim->alarm.raised) {
            sph_sim_step(sim);
            sph_sim_stats(sim, &s);
            if (k == 1 && steps < 10)
                cr_assert_lt(s.ekin, prev, "step %d: ekin %g, before %g", steps, s.ekin, prev);
            prev = s.ekin;
            steps++;
        }
        cr_assert(!sim->alarm.raised);
        ekin[k] = s.ekin;
        sph_sim_destroy(sim);
    }
    cr_assert_gt(ekin[0], 0.5 * e0, "without damping: ekin %g of %g", ekin[0], e0);
    cr_assert_lt(ekin[1], 0.01 * e0, "with damping: ekin %g of %g at T", ekin[1], e0);
}
