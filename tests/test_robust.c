/* Wrong answers that used to exit 0 (issue 17): the first time step, coincident
 * particles, the defaults, and the watchdog's bounds. Each test failed on the
 * code before its fix. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "test_util.h"

/* A block at 1000 m/s: the first adaptive step must already obey the sound
 * and flow condition with |v|max = 1000 m/s (it used to be chosen with
 * |v|max = 0: dt = 4e-4 s, so the block moved 20 h in one step). */
Test(robust, first_step_sees_initial_velocity)
{
    sph_sim *sim = test_sim("[scene]\neffects=pressure viscosity walls\n[domain]\nmin=0 0\nmax=1 1\n"
                            "[fluid a]\nmin=0.4 0.4\nmax=0.6 0.6\nspacing=0.02\nvelocity=1000 0\n"
                            "[kernels]\nh=0.04\n[physics]\nstiffness=400\n[time]\ncfl=0.4\ndt=0.002\n",
                            1);
    const double limit = 0.4 * 0.02 / (20.0 + 1000.0); /* cfl (h/2) / (c + |v|) = 7.8e-6 s */
    cr_assert(sim->max_speed >= 999.0f, "initial max speed %g m/s, want 1000", sim->max_speed);
    float x0 = sim->P.pos[0][0];
    uint32_t id0 = sim->P.id[0];
    sph_sim_step(sim);
    cr_assert(sim->t <= limit * 1.001, "first dt %g s above the CFL limit %g s", sim->t, limit);
    for (uint32_t i = 0; i < sim->n; i++)
        if (sim->P.id[i] == id0)
            cr_assert(fabsf(sim->P.pos[0][i] - x0) < 0.5f * 0.04f, "moved %g m (h = 0.04 m) in the first step",
                      sim->P.pos[0][i] - x0);
    sph_sim_destroy(sim);
}

/* A run by time ends on its end: `run --time 0.005` stopped at the first step
 * past it (t = 0.0051 s in the stats' last row). The step that would pass it is
 * shortened, with the adaptive step and with a fixed one alike. */
static void check_run_ends_on(double cfl, double dt, double end, long want_steps)
{
    char ini[512];
    snprintf(ini, sizeof ini,
             "[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=1 1\n"
             "[fluid a]\nmin=0 0\nmax=0.4 0.4\nspacing=0.02\n[kernels]\nh=0.04\n[physics]\nstiffness=400\n"
             "[time]\ncfl=%g\ndt=%g\n",
             cfl, dt);
    sph_sim *sim = test_sim(ini, 1);
    sph_sim_end_at(sim, end);
    float longest = 0, last = 0, shortest = INFINITY;
    while (!sph_sim_reached(sim, end) && sim->step < 100000) {
        sph_sim_step(sim);
        last = sim->dt;
        shortest = fminf(shortest, last);
        if (!sph_sim_reached(sim, end)) longest = fmaxf(longest, last);
    }
    cr_assert(sim->t == end, "cfl %g: the run ended at t = %.12g s, not on %g s", cfl, sim->t, end);
    cr_assert(last <= longest * 1.001f, "cfl %g: the last step %g s is longer than the others (%g s)", cfl, last,
              longest);
    /* no sliver of a step: a float dt of 0.0002 s is a little short, and 500 of them ended 2.5e-9 s before
     * 0.1 s, which a 501st step of 2.5e-9 s made up */
    if (cfl == 0) cr_assert(shortest >= 0.4999f * (float)dt, "fixed dt %g: a step of %g s", dt, shortest);
    if (want_steps) cr_assert_eq((long)sim->step, want_steps, "fixed dt: %ld steps", (long)sim->step);
    sph_sim_destroy(sim);
}

Test(robust, run_by_time_ends_on_its_end)
{
    check_run_ends_on(0.4, 0.002, 0.005, 0); /* the adaptive step: about 0.25 ms each here */
    check_run_ends_on(0, 0.002, 0.005, 3);   /* 2, then the 3 ms left as 1.5 and 1.5 */
    check_run_ends_on(0, 0.001, 0.004, 4);   /* a whole number of steps: none shortened */
    check_run_ends_on(0, 0.0002, 0.1, 500);  /* 500 float steps of 0.0002 s, the last stretched by 2.5e-9 s */
}

/* The fixed-dt warning at step 0 must state the limit that the initial speed sets. */
Test(robust, fixed_dt_warning_states_the_initial_limit)
{
    sph_sim *sim = test_sim("[scene]\neffects=pressure viscosity walls\n[domain]\nmin=0 0\nmax=1 1\n"
                            "[fluid a]\nmin=0.4 0.4\nmax=0.6 0.6\nspacing=0.02\nvelocity=1000 0\n"
                            "[kernels]\nh=0.04\n[physics]\nstiffness=400\n[time]\ncfl=0\ndt=0.0001\n",
                            1);
    char buf[512];
    const char *w = sph_sim_dt_warning(sim, buf, sizeof buf);
    cr_assert(w != NULL, "dt = 1e-4 s is 13 times the limit 7.8e-6 s: a warning is due");
    cr_assert(strstr(w, "7.84e-06") != NULL, "warning states another limit: %s", w);
    sph_sim_destroy(sim);
}

/* The adaptive step is floored at dt_min: a block at 1e6 m/s needs
 * cfl (h/2) / (c + |v|) = 8e-9 s, below the default dt_min of 1e-7 s, so each
 * step moves it 2.5 h. That must be said (it used to run on silently); the
 * same block at 1000 m/s is within the floor and gets no warning. */
Test(robust, adaptive_step_held_at_dt_min_is_warned)
{
    const char *scene = "[scene]\neffects=pressure viscosity\n[domain]\nmin=0 0\nmax=4 1\n"
                        "[fluid a]\nmin=0.2 0.4\nmax=0.4 0.6\nspacing=0.02\nvelocity=%s 0\n"
                        "[kernels]\nh=0.04\n[physics]\nstiffness=400\n[time]\ncfl=0.4\n";
    char ini[512], buf[512];
    snprintf(ini, sizeof ini, scene, "1000000");
    sph_sim *sim = test_sim(ini, 1);
    const char *w = sph_sim_dt_warning(sim, buf, sizeof buf);
    cr_assert(w != NULL, "a CFL limit of 8e-9 s under dt_min = 1e-7 s: a warning is due");
    cr_assert(strstr(w, "dt_min = 1e-07") && strstr(w, "8e-09"), "warning names neither the floor nor the limit: %s", w);
    sph_sim_destroy(sim);
    snprintf(ini, sizeof ini, scene, "1000");
    sim = test_sim(ini, 1);
    w = sph_sim_dt_warning(sim, buf, sizeof buf);
    cr_assert(w == NULL, "the CFL limit 7.8e-6 s is above dt_min, yet: %s", w);
    sph_sim_destroy(sim);
}

/* Forces at rest: two blocks overlapping at half a spacing start at twice
 * rho0, so the pressure force is large from step 0. The first step must obey
 * the force condition with that acceleration, not with |a|max = 0. */
Test(robust, first_step_sees_initial_forces)
{
    sph_sim *sim = test_sim("[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=1 1\n"
                            "[fluid a]\nmin=0.4 0.4\nmax=0.6 0.6\nspacing=0.02\n"
                            "[fluid b]\nmin=0.41 0.41\nmax=0.61 0.61\nspacing=0.02\n"
                            "[kernels]\nh=0.04\n[physics]\nstiffness=100\n[time]\ncfl=0.4\ndt=0.01\n",
                            1);
    cr_assert(sim->max_acc >= 9.8f, "initial |a|max %g m/s^2 below gravity", sim->max_acc);
    cr_assert(sim->max_acc > 1000.0f, "initial |a|max %g m/s^2: the pressure force of a doubled density is missing",
              sim->max_acc);
    const float want = 0.4f * sqrtf(0.02f / sim->max_acc);
    cr_assert(sim->dt <= want * 1.001f, "first dt %g s above the force limit %g s", sim->dt, want);
    sph_sim_destroy(sim);
}

/* Two particles at one point, at rest, alone (so below rho0: with
 * negative_pressure = keep they attract). The pair has no direction; whatever
 * the code does, it must not make a fast pair out of nothing: the speed stays
 * far below the sound speed, and total energy (from step 0) does not grow.
 * They used to leave at 17 m/s (2D) and 57 m/s (3D) with c = 20 m/s. */
static void check_coincident_pair(int dim)
{
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=%d\neffects=pressure viscosity walls\n[domain]\nmin=0 0 0\nmax=1 1 1\n"
             "[fluid a]\nmin=0.5 0.5 0.5\nmax=0.52 0.52 0.52\nspacing=0.02\n"
             "[fluid b]\nmin=0.5 0.5 0.5\nmax=0.52 0.52 0.52\nspacing=0.02\n"
             "[kernels]\nh=0.04\n[physics]\nstiffness=400\nnegative_pressure=keep\n[time]\ncfl=0.4\ndt=0.002\n",
             dim);
    sph_sim *sim = test_sim(ini, 1);
    cr_assert_eq(sim->n, 2u);
    const double c = 20.0;
    sph_stats s;
    sph_sim_stats(sim, &s);
    const double e0 = sph_stats_energy(&s);
    double vmax = 0, emax = e0;
    for (int k = 0; k < 2000 && !sim->alarm.raised; k++) {
        sph_sim_step(sim);
        sph_sim_stats(sim, &s);
        vmax = fmax(vmax, s.max_speed);
        emax = fmax(emax, sph_stats_energy(&s));
    }
    cr_assert(!sim->alarm.raised, "%dD: the watchdog stopped a coincident pair", dim);
    cr_assert(vmax <= 0.1 * c, "%dD: coincident pair at rest reached %g m/s (sound speed %g m/s)", dim, vmax, c);
    cr_assert(emax - e0 <= 1e-3 * fabs(e0) + 1e-9, "%dD: energy grew from %g to %g J", dim, e0, emax);
    sph_sim_destroy(sim);
}

Test(robust, coincident_pair_at_rest_2d) { check_coincident_pair(2); }
Test(robust, coincident_pair_at_rest_3d) { check_coincident_pair(3); }

/* One extra particle on an interior node of a pool: a compressed coincident
 * pair, which must repel. The release is bounded by the internal energy of
 * the overdensity: the pair must not leave faster than the sound speed, and
 * the total energy (from step 0) must not grow. One kernel for density and
 * pressure, no tensile pressure and cfl = 0.1, so that the scheme itself
 * conserves energy (within 0.7%; at cfl = 0.4 the time integration alone
 * gains 10% of this release) and any gain is the pair's. A guard: the
 * repulsion was already bounded; the tensile pair (above) was not. */
static void check_coincident_in_fluid(int dim)
{
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=%d\neffects=pressure viscosity walls\n[domain]\nmin=0 0 0\nmax=1 1 1\n"
             "[fluid a]\nmin=0.3 0.3 0.3\nmax=0.5 0.5 0.5\nspacing=0.02\n"
             "[fluid b]\nmin=0.4 0.4 0.4\nmax=0.42 0.42 0.42\nspacing=0.02\n"
             "[kernels]\nh=0.04\ndensity=cubic\npressure=cubic\n"
             "[physics]\nstiffness=400\nnegative_pressure=clamp\n[time]\ncfl=0.1\ndt=0.002\n",
             dim);
    sph_sim *sim = test_sim(ini, 1);
    const double c = 20.0;
    sph_stats s;
    sph_sim_stats(sim, &s);
    const double e0 = sph_stats_energy(&s);
    double vmax = 0, emax = e0;
    for (int k = 0; k < 600 && !sim->alarm.raised; k++) {
        sph_sim_step(sim);
        sph_sim_stats(sim, &s);
        vmax = fmax(vmax, s.max_speed);
        emax = fmax(emax, sph_stats_energy(&s));
    }
    cr_assert(!sim->alarm.raised, "%dD: the watchdog stopped the run", dim);
    cr_log_info("%dD: coincident pair in a pool: max speed %g m/s, energy %g -> max %g J", dim, vmax, e0, emax);
    cr_assert(vmax <= c, "%dD: the pair left at %g m/s (sound speed %g m/s)", dim, vmax, c);
    cr_assert(emax - e0 <= 0.02 * fabs(e0), "%dD: energy grew from %g to %g J", dim, e0, emax);
    sph_sim_destroy(sim);
}

Test(robust, coincident_pair_in_fluid_2d) { check_coincident_in_fluid(2); }
Test(robust, coincident_pair_in_fluid_3d) { check_coincident_in_fluid(3); }

/* Every default and one block of fluid: the run must be stable. In the
 * default 1 m box a fall reaches at most sqrt(2 g 1 m) = 4.4 m/s; the jet a
 * collapsing column throws up a wall may go faster (a dam break's run-up),
 * so the bound is twice that: 5.4 m/s with the AVX-512 loops, 7.2 m/s with
 * the scalar ones (the sanitizer build). The defaults' old fixed dt (twice the
 * sound speed's CFL limit) took it to 220 m/s. */
Test(robust, defaults_give_a_stable_run)
{
    sph_sim *sim = test_sim("[fluid a]\nmin=0 0\nmax=0.3 0.5\n", 1);
    const double fall = sqrt(2 * 9.81 * 1.0);
    double vmax = 0;
    sph_stats s;
    while (sim->t < 0.5 && !sim->alarm.raised) {
        sph_sim_step(sim);
        if (sim->step % 20 == 0) {
            sph_sim_stats(sim, &s);
            vmax = fmax(vmax, s.max_speed);
        }
    }
    char buf[4096];
    sph_sim_alarm_report(sim, buf, sizeof buf);
    cr_assert(!sim->alarm.raised, "the defaults were stopped by the watchdog: %s", buf);
    cr_assert(vmax <= 2.0 * fall, "the defaults reached %g m/s; a fall in the box reaches %g m/s", vmax, fall);
    sph_sim_destroy(sim);
}

/* A column at rest with stiffness 4e6 (c = 2000 m/s): the lattice's 1.5%
 * summation error is then a 60 kPa overpressure, twenty times the
 * hydrostatic pressure, and it launches the column (at k = 1e6, 24-28 m/s in
 * 15 ms with the integral volume walls, whose first row read 3 % more; under
 * the 18.7 m/s bound with the lattice's), while a fall in the box
 * reaches 4.4 m/s. The watchdog's speed bound once grew with the stiffness
 * (20 c), so it never fired; it must stop this, naming speed. */
Test(robust, watchdog_stops_a_stiff_pool_launched_by_its_lattice)
{
    sph_sim *sim = test_sim("[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=1 1\n"
                            "[fluid column]\nmin=0 0\nmax=0.2 0.3\nspacing=0.02\n[kernels]\nh=0.04\n"
                            "[physics]\nstiffness=4e6\nviscosity=0.002\nnegative_pressure=clamp\n[time]\ncfl=0.4\n",
                            1);
    for (int k = 0; k < 2000 && !sim->alarm.raised; k++) sph_sim_step(sim);
    cr_assert(sim->alarm.raised, "a column at rest reached %g m/s in %g s and ran on", sim->max_speed, sim->t);
    cr_assert(strstr(sim->alarm.what, "speed") != NULL, "the report does not name the speed: %s", sim->alarm.what);
    cr_assert(strstr(sim->alarm.what, "fall") != NULL, "the report does not name the scale: %s", sim->alarm.what);
    sph_sim_destroy(sim);
}

/* Energy that comes from nowhere: a pool at rest is given 3 m/s upwards in
 * step 10 (below any speed bound: a fall in the box reaches 4.4 m/s). Its
 * total energy, measured from step 0, then grows by far more than its own
 * scale; the watchdog must say so. */
Test(robust, watchdog_stops_energy_from_nowhere)
{
    sph_sim *sim = test_sim("[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=1 1\n"
                            "[fluid pool]\nmin=0 0\nmax=1 0.2\nspacing=0.02\n[kernels]\nh=0.04\n"
                            "[physics]\nstiffness=400\nviscosity=0.01\n",
                            1);
    for (int k = 0; k < 10; k++) sph_sim_step(sim);
    cr_assert(!sim->alarm.raised, "%s", sim->alarm.what);
    for (uint32_t i = 0; i < sim->n; i++) sim->P.vel[1][i] += 3.0f;
    for (int k = 0; k < 5 && !sim->alarm.raised; k++) sph_sim_step(sim);
    cr_assert(sim->alarm.raised, "energy grew from nothing and the run went on");
    cr_assert(strstr(sim->alarm.what, "energy") != NULL, "the report does not name energy: %s", sim->alarm.what);
    sph_sim_destroy(sim);
}

/* The speed alarm names the fastest particle past the bound, not the first in
 * memory order (a user who looked found others faster than the one named). */
Test(robust, watchdog_names_the_fastest_particle)
{
    sph_sim *sim = test_sim("[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=1 1\n"
                            "[fluid pool]\nmin=0 0\nmax=1 0.2\nspacing=0.02\n[kernels]\nh=0.04\n"
                            "[physics]\nstiffness=400\nviscosity=0.01\n",
                            1);
    sph_sim_step(sim);
    cr_assert(!sim->alarm.raised, "%s", sim->alarm.what);
    const float bound = sim->speed_bound;
    sim->P.vel[0][3] = 1.5f * bound;  /* past the bound, first in memory */
    sim->P.vel[0][40] = 3.0f * bound; /* the fastest */
    sim->P.vel[1][90] = 2.0f * bound;
    sph_watchdog_check(sim, SPH_PASS_INTEGRATE);
    cr_assert(sim->alarm.raised, "speeds of 3 times the bound were not seen");
    cr_assert_eq(sim->alarm.particle, 40u, "named particle %u at %g m/s, not the fastest (40, %g m/s)",
                 sim->alarm.particle, sim->alarm.value, 3.0f * bound);
    cr_assert_float_eq(sim->alarm.value, 3.0f * bound, 1e-3f * bound, "value %g", sim->alarm.value);
    sph_sim_destroy(sim);
}

/* A force from outside the fluid tells the watchdog what it needs through its pass (sph_pass.speed_scale,
 * .does_work), so that such a force is one file: the mouse's push raises the speed bound by its own scale,
 * sqrt(2 |strength| radius), and while its button is down it is the pass that does work. */
Test(robust, a_force_from_outside_is_declared_by_its_pass)
{
    const char *base = "[scene]\neffects=gravity pressure viscosity walls%s\n[domain]\nmin=0 0\nmax=1 1\n"
                       "[fluid pool]\nmin=0 0\nmax=1 0.2\nspacing=0.02\n[kernels]\nh=0.04\n"
                       "[physics]\nstiffness=400\nviscosity=0.01\n[interaction]\nstrength=40\nradius=0.2\n";
    char ini[1024];
    snprintf(ini, sizeof ini, base, "");
    sph_sim *plain = test_sim(ini, 1);
    snprintf(ini, sizeof ini, base, " interaction");
    sph_sim *mouse = test_sim(ini, 1);
    const double scale = sqrt(2.0 * 40.0 * 0.2); /* 4 m/s */
    cr_assert_float_eq(mouse->speed_scale - plain->speed_scale, scale, 1e-4, "the mouse adds %g m/s, want %g",
                       mouse->speed_scale - plain->speed_scale, scale);
    cr_assert_null(sph_sim_work_done_by(plain));
    cr_assert_null(sph_sim_work_done_by(mouse), "the button is up: no work");
    mouse->interaction_active = true;
    cr_assert(sph_sim_work_done_by(mouse) && strcmp(sph_sim_work_done_by(mouse), "interaction") == 0);
    mouse->enabled[SPH_PASS_INTERACTION] = false; /* switched off in the window: its force is gone */
    cr_assert_null(sph_sim_work_done_by(mouse));
    sph_sim_destroy(plain);
    sph_sim_destroy(mouse);
}

/* A DFSPH dam break whose solves cannot reach their tolerance (2 iterations, a 10 ms step): each step leaves its
 * density error to the next until the watchdog stops the run. The report must say that the solves ended short
 * of their tolerance, and how often: the usual causes alone sent a user looking at dt, where a 240,000-particle
 * 3D dam break had capped every solve from its third step. */
/* The 2D dam break of lessons/scenes/dam-break-2d.ini with a pressure solver's keys and a time step that make it
 * run away, stepped until the watchdog stops it (or max_steps). */
static sph_sim *solver_dam_to_alarm(const char *physics, const char *time, int max_steps)
{
    char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=3 1.5\n"
             "[fluid column]\nmin=0 0\nmax=1 1\nspacing=0.02\n[kernels]\nh=0.04\n[physics]\n%sviscosity=0.002\n"
             "[time]\n%s",
             physics, time);
    sph_sim *sim = test_sim(ini, 1);
    for (int k = 0; k < max_steps && !sim->alarm.raised; k++) sph_sim_step(sim);
    return sim;
}

Test(robust, watchdog_says_the_solves_ended_short)
{
    sph_sim *sim = solver_dam_to_alarm("pressure_solver=dfsph\nsolver_max_iterations=2\n", "dt=0.01\ncfl=1\n", 200);
    cr_assert(sim->alarm.raised, "2 iterations a 10 ms step ran %g s without the watchdog", sim->t);
    cr_assert(sim->solver.capped > 0, "no solve was capped");
    char buf[8192], want[64];
    sph_sim_alarm_report(sim, buf, sizeof buf);
    snprintf(want, sizeof want, "%llu at solver_max_iterations = 2", (unsigned long long)sim->solver.capped);
    cr_assert(strstr(buf, "ended short of their tolerance") && strstr(buf, want),
              "the report does not say the solves were capped (want \"%s\"): %s", want, buf);
    sph_sim_destroy(sim);
}

/* The watchdog's speed scale counts the surface tension's pull as it counts cohesion's: a still square under csf,
 * with no gravity and no velocity, had a scale of 0 and a bound of 1 m/s ("4 times what the scene can make: 0
 * m/s"), which its corners' first rounding can pass. */
Test(robust, speed_scale_counts_surface_tension)
{
    const char *ini = "[scene]\neffects=pressure viscosity\n[domain]\nmin=-0.1 -0.1\nmax=0.1 0.1\n"
                      "[fluid drop]\nmin=-0.04 -0.04\nmax=0.04 0.04\nspacing=0.005\n[kernels]\nh=0.015\ndensity=cubic\n"
                      "pressure=cubic\nviscosity=cubic\n[physics]\nstiffness=100\nviscosity=0.001\n";
    char with[1024];
    snprintf(with, sizeof with, "%ssurface_tension=csf\nsigma=0.0728\n", ini);
    sph_sim *still = test_sim(ini, 1), *tense = test_sim(with, 1);
    cr_expect(still->speed_scale == 0.0f, "no force, no velocity: scale %g m/s", still->speed_scale);
    cr_expect(tense->speed_scale > 0.0f, "csf's pull not counted: scale %g m/s, bound %g m/s", tense->speed_scale,
              tense->speed_bound);
    sph_sim_destroy(still);
    sph_sim_destroy(tense);
}

/* A solver's run the watchdog stops with no solve short of its tolerance gets the solvers' usual causes once: the
 * equation of state's ("a stiffness too high for dt") was printed after them, as the else of the new paragraph on
 * capped solves (a review of the change). */
Test(robust, watchdog_gives_one_set_of_usual_causes)
{
    sph_sim *sim = solver_dam_to_alarm("pressure_solver=pcisph\nsolver_tolerance=1\n", "dt=0.02\ncfl=0.4\n", 300);
    cr_assert(sim->alarm.raised, "a 100 %% tolerance at dt = 0.02 s ran %g s", sim->t);
    char buf[8192];
    sph_sim_alarm_report(sim, buf, sizeof buf);
    int n = 0;
    for (const char *p = buf; (p = strstr(p, "Usual causes")); p++) n++;
    cr_expect_eq(n, 1, "%d sets of usual causes (capped %llu, stopped %llu): %s", n,
                 (unsigned long long)sim->solver.capped, (unsigned long long)sim->solver.stopped, buf);
    cr_expect(strstr(buf, "Usual causes with pressure_solver = pcisph"), "not the solver's causes: %s", buf);
    sph_sim_destroy(sim);
}
