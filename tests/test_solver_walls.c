/* The pressure solvers (pressure_solver = pcisph, dfsph) with wall particles
 * ([domain] wall_model = particles) and obstacles: the wall particles are
 * neighbours with no pressure of their own, held still (pcisph.c, dfsph.c).
 * Checked: every step's solve ends within its tolerance, the wall particles
 * do not move, water at rest on an obstacle weighs on it with its weight
 * (the obstacle force's solver term, sph_obstacle_force.c), and a dam break
 * stays out of the obstacle it hits. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_obstacles.h"
#include "sph_pass.h"
#include "sph_walls.h"
#include "test_util.h"

#define TOL 0.001 /* solver_tolerance of the scenes below */

/* The wall particles' positions, to see that nothing moves them. */
static float *wall_positions(const sph_sim *sim)
{
    float *x = malloc(sizeof *x * 3 * sim->n);
    cr_assert(x);
    for (uint32_t i = 0; i < sim->n; i++) {
        cr_assert_lt(sim->P.id[i], sim->n);
        for (int d = 0; d < 3; d++) x[3 * (size_t)sim->P.id[i] + (size_t)d] = d < sim->dim ? sim->P.pos[d][i] : 0.0f;
    }
    return x;
}

/* Every wall particle where it was (by id: the reorder moves the slots). */
static void walls_still(const sph_sim *sim, const float *x0, const char *what)
{
    for (uint32_t i = 0; i < sim->n; i++) {
        if (!sph_is_wall(&sim->P, i)) continue;
        const uint32_t id = sim->P.id[i];
        for (int d = 0; d < sim->dim; d++)
            cr_assert_eq(sim->P.pos[d][i], x0[3 * id + d], "%s: wall particle %u moved along %d: %g -> %g", what,
                         id, d, x0[3 * id + d], sim->P.pos[d][i]);
    }
}

/* The step just made: its solve converged within the tolerance. */
static void step_held(const sph_sim *sim, const char *what)
{
    cr_assert_leq(sim->solver.density_error, TOL * (1 + 1e-6), "%s: step %llu ended at %g", what,
                  (unsigned long long)sim->step, sim->solver.density_error);
    cr_assert_eq(sim->solver.capped, 0, "%s: step %llu: a solve reached the iteration cap", what,
                 (unsigned long long)sim->step);
    cr_assert_eq(sim->solver.stopped, 0, "%s: step %llu: a solve was stopped rising", what,
                 (unsigned long long)sim->step);
}

/* A layer of water (0.2 m wide, 0.2 m deep) at rest on an obstacle as wide as
 * the box, 0.1 m above the box's floor: over t = 0.5 .. 0.8 s the mean force on
 * the obstacle is the water's weight. The box's side walls hold the water
 * sideways (their pressure is horizontal), so the obstacle carries it all, up
 * to the water's change of momentum, 2 M v_max / T at most. */
static void check_resting(const char *solver, const char *walls)
{
    char ini[2048];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.2 0.4\n"
             "wall_model=particles\n[fluid w]\nmin=0 0.1\nmax=0.2 0.3\nspacing=0.01\n[obstacle floor]\nmin=0 0\n"
             "max=0.2 0.1\n[physics]\npressure_solver=%s\nsolver_tolerance=%g\nsolver_max_iterations=500\n"
             "solver_wall_pressure=%s\nviscosity=0.05\nviscosity_form=morris\n[kernels]\nh=0.02\ndensity=cubic\n"
             "pressure=cubic\nviscosity=cubic\n[time]\ncfl=0.25\ndt=0.001\n",
             solver, TOL, walls);
    sph_sim *sim = test_sim(ini, 2);
    float *x0 = wall_positions(sim);
    double M = 0;
    for (uint32_t i = 0; i < sim->n; i++)
        if (!sph_is_wall(&sim->P, i)) M += sim->P.mass[i];
    const double W = M * 9.81;
    while (sim->t < 0.5) {
        sph_sim_step(sim);
        step_held(sim, solver);
    }
    double impulse[2] = {0, 0}, t0 = sim->t, vmax = 0;
    while (sim->t < 0.8) {
        sph_sim_step(sim);
        step_held(sim, solver);
        double f[SPH_MAX_OBSTACLES][3];
        cr_assert_eq(sph_obstacle_forces(sim, f), 1);
        for (int d = 0; d < 2; d++) impulse[d] += f[0][d] * sim->dt;
        sph_stats st;
        sph_sim_stats(sim, &st);
        vmax = fmax(vmax, st.max_speed);
    }
    /* with the wall particles' pressure extrapolated, the side walls' particles hold the hydrostatic gradient
     * too, and the pairs across their rows carry 1.6 % of the weight up (the equation of state's walls, which
     * extrapolate the same way: 1.8 % in `sphlab validate obstacle`, docs/accuracy.md) */
    const double share = strcmp(walls, "extrapolated") == 0 ? 0.025 : 0.01;
    const double T = sim->t - t0, Fy = impulse[1] / T, tol = 2 * M * vmax / T + share * W;
    cr_log_info("%s: weight %g N/m, mean force on the obstacle (%g, %g) N/m, off by %.3g%% (tolerance %.3g%%), "
                "v_max %g m/s",
                solver, W, impulse[0] / T, Fy, 100 * fabs(Fy + W) / W, 100 * tol / W, vmax);
    cr_assert_lt(vmax, 0.02, "%s: the water should stay at rest (v_max %g m/s)", solver, vmax);
    cr_assert_lt(fabs(Fy + W), tol, "%s: mean force %g N/m against the weight %g N/m", solver, Fy, W);
    cr_assert_lt(fabs(impulse[0] / T), tol, "%s: no sideways force on a layer at rest", solver);
    walls_still(sim, x0, solver);
    /* The row on the obstacle against the rows above it: the mean pressure of each of the first six rows, a
     * line fitted through rows 2 to 6 by least squares, and the first row's distance from that line's value at
     * its height, over rho0 g H. With the wall particles' pressure extrapolated the pair term at the wall is
     * the interior's, and the row continues the interior's profile; with none they push with the row's
     * pressure alone, and it reads about twice its pressure. (The profile's slope, 8,300 Pa/m here, is under
     * rho0 g = 9,810: each step's solve starts from p = 0 and stops at the first iteration within the
     * tolerance; a tighter tolerance brings the column's pressure nearer, docs/accuracy.md, "hydrostatic".) */
    double py[6] = {0}, yy[6] = {0};
    int ny[6] = {0};
    for (uint32_t i = 0; i < sim->n; i++) {
        const double y = sim->P.pos[1][i];
        const int r = (int)floor((y - 0.1) / 0.01);
        if (sph_is_wall(&sim->P, i) || r < 0 || r >= 6) continue;
        py[r] += sph_sim_pressure(sim, i), yy[r] += y, ny[r]++;
    }
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (int r = 0; r < 6; r++) {
        cr_assert_gt(ny[r], 10, "row %d holds %d particles", r, ny[r]);
        py[r] /= ny[r], yy[r] /= ny[r];
        if (r == 0) continue;
        sx += yy[r], sy += py[r], sxx += yy[r] * yy[r], sxy += yy[r] * py[r];
    }
    const double slope = (5 * sxy - sx * sy) / (5 * sxx - sx * sx), icpt = (sy - slope * sx) / 5;
    const double rgH = 1000.0 * 9.81 * 0.2, jump = (py[0] - (icpt + slope * yy[0])) / rgH;
    cr_log_info("%s, solver_wall_pressure = %s: the row on the obstacle reads %g Pa, the rows above continue to "
                "%g Pa there (%+.1f%% of rho0 g H); slope %g Pa/m (rho0 g = 9810), rho_r %g kg/m^2",
                solver, walls, py[0], icpt + slope * yy[0], 100 * jump, -slope, (double)sim->solver.rho_rest);
    if (strcmp(walls, "extrapolated") == 0)
        cr_assert_lt(fabs(jump), 0.03, "%s: the row on the obstacle reads %g Pa, %+.1f%% of rho0 g H off the rows "
                     "above", solver, py[0], 100 * jump);
    else
        cr_assert_gt(jump, 0.5, "%s, none: the row on the obstacle should read about twice its pressure (%g Pa)",
                     solver, py[0]);
    free(x0);
    sph_sim_destroy(sim);
}

Test(solver_walls, pcisph_resting_water_weighs_on_obstacle, .timeout = 300) { check_resting("pcisph", "none"); }
Test(solver_walls, dfsph_resting_water_weighs_on_obstacle, .timeout = 300) { check_resting("dfsph", "none"); }
Test(solver_walls, pcisph_extrapolated_walls_row_reads_its_pressure, .timeout = 300)
{
    check_resting("pcisph", "extrapolated");
}
Test(solver_walls, dfsph_extrapolated_walls_row_reads_its_pressure, .timeout = 300)
{
    check_resting("dfsph", "extrapolated");
}

/* The dam break of `sphlab validate obstacle` (scenes/validate/obstacle.ini:
 * a column 0.1 m wide and 0.2 m high, a box obstacle from x = 0.2 m) with a
 * solver, to t = 0.3 s, past the impact (about 0.12 s): every solve within its
 * tolerance, the walls still, no fluid particle past the obstacle's first
 * row of wall particles (half a spacing inside it; the solvers let the front
 * reach 0.1 spacing past the face, 0.2005 m). */
static void check_dam(const char *solver, const char *walls)
{
    char ini[2048];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.25 0.3\n"
             "wall_model=particles\nwall_slip=free\n[fluid column]\nmin=0 0\nmax=0.1 0.2\nspacing=0.005\n"
             "[obstacle wall]\nshape=box\nmin=0.2 0\nmax=0.25 0.3\nslip=free\n[physics]\npressure_solver=%s\n"
             "solver_tolerance=%g\nsolver_max_iterations=500\nsolver_wall_pressure=%s\nnegative_pressure=clamp\n"
             "viscosity_form=artificial\n"
             "viscosity=0.000001\n[kernels]\nh=0.015\ndensity=wendland\npressure=wendland\nviscosity=wendland\n"
             "[time]\ncfl=0.4\ndt=0.001\n",
             solver, TOL, walls);
    sph_sim *sim = test_sim(ini, 2);
    float *x0 = wall_positions(sim);
    double front = 0;
    long iterations = 0;
    while (sim->t < 0.3) {
        sph_sim_step(sim);
        step_held(sim, solver);
        iterations += sim->solver.iterations;
        for (uint32_t i = 0; i < sim->n; i++)
            if (!sph_is_wall(&sim->P, i)) front = fmax(front, sim->P.pos[0][i]);
    }
    cr_log_info("%s: %llu steps, %.1f density iterations per step, the front's furthest x %.5f m", solver,
                (unsigned long long)sim->step, (double)iterations / (double)sim->step, front);
    cr_assert_gt(front, 0.19, "%s: the front should reach the obstacle by t = 0.3 s (furthest x %g m)", solver,
                 front);
    /* the obstacle's first row of wall particles is at x = 0.2 + s/2: past it, the fluid leaks */
    cr_assert_lt(front, 0.2 + 0.5 * 0.005, "%s: a fluid particle went past the obstacle's first row (x = %g m)", solver,
                 front);
    walls_still(sim, x0, solver);
    free(x0);
    sph_sim_destroy(sim);
}

Test(solver_walls, pcisph_dam_break_on_obstacle, .timeout = 300) { check_dam("pcisph", "none"); }
Test(solver_walls, dfsph_dam_break_on_obstacle, .timeout = 300) { check_dam("dfsph", "none"); }
Test(solver_walls, pcisph_extrapolated_dam_break_on_obstacle, .timeout = 300) { check_dam("pcisph", "extrapolated"); }
Test(solver_walls, dfsph_extrapolated_dam_break_on_obstacle, .timeout = 300) { check_dam("dfsph", "extrapolated"); }

/* `sphlab check` says which wall pressure the solvers use: the pcisph and
 * dfsph passes' descriptions differ between solver_wall_pressure = none and
 * extrapolated, and wall_state's says it gives the velocity only under a
 * solver (it makes no pressure there). */
Test(solver_walls, describe_says_the_wall_pressure)
{
    const char *solvers[] = {"pcisph", "dfsph"};
    const sph_pass_id pass[] = {SPH_PASS_PCISPH, SPH_PASS_DFSPH};
    for (int k = 0; k < 2; k++) {
        char ini[512], a[512], b[512], w[512]; /* as check's buffer (cmd_check.c) */
        const char *fmt = "[scene]\neffects=gravity pressure walls\n[domain]\nmax=0.2 0.2\nwall_model=particles\n"
                          "[fluid a]\nmax=0.1 0.1\nspacing=0.01\n[physics]\npressure_solver=%s\n"
                          "solver_wall_pressure=%s\n[kernels]\nh=0.02\n";
        snprintf(ini, sizeof ini, fmt, solvers[k], "none");
        sph_scene_def def = test_scene(ini);
        sph_passes[pass[k]]->describe(&def, a, sizeof a);
        sph_passes[SPH_PASS_WALL_STATE]->describe(&def, w, sizeof w);
        snprintf(ini, sizeof ini, fmt, solvers[k], "extrapolated");
        def = test_scene(ini);
        sph_passes[pass[k]]->describe(&def, b, sizeof b);
        cr_expect(strstr(a, "push back with the fluid particle's own pressure") != NULL, "%s none: %s", solvers[k], a);
        cr_expect(strstr(b, "hold the fluid's pressure (extrapolated)") != NULL, "%s extrapolated: %s", solvers[k], b);
        cr_expect(strstr(w, "wall pressure from the fluid") == NULL && strstr(w, "velocity only") != NULL,
                  "%s: wall_state: %s", solvers[k], w);
    }
    /* under the equation of state wall_state still makes the walls' pressure */
    char w[256];
    sph_scene_def def = test_scene("[scene]\neffects=gravity pressure walls\n[domain]\nmax=0.2 0.2\n"
                                   "wall_model=particles\n[fluid a]\nmax=0.1 0.1\nspacing=0.01\n[kernels]\nh=0.02\n");
    sph_passes[SPH_PASS_WALL_STATE]->describe(&def, w, sizeof w);
    cr_expect(strstr(w, "wall pressure from the fluid") != NULL, "eos: wall_state: %s", w);
}

/* A 2D dam break hitting a box on the floor at about 3.8 m/s, DFSPH with the wall particles' pressure extrapolated
 * (a user's scene: h = 2 spacings, the default kernels): the density solve's factor must count the walls' part of
 * its gradient twice, since the wall particles take the fluid's kappa (dfsph.c, factors). Counted once, the Jacobi
 * step overshot at the impact and the watchdog stopped the run at 21 m/s (t = 0.44 s). A fall from the column's
 * 0.6 m reaches 3.4 m/s; the splash at the impact 6.8 to 8.0 m/s with the equation of state, PCISPH, or DFSPH
 * with walls that hold no pressure. */
Test(solver_walls, dfsph_extrapolated_impact_on_a_box, .timeout = 300)
{
    const char *ini = "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=3 1.2\n"
                      "wall_model=particles\n[fluid column]\nmin=0 0\nmax=0.8 0.6\nspacing=0.02\n"
                      "[obstacle rock]\nshape=box\nmin=1.8 0\nmax=2.0 0.3\nslip=no\n"
                      "[obstacle ball]\nshape=circle\ncentre=2.5 0.6\nradius=0.12\n"
                      "[physics]\npressure_solver=dfsph\nsolver_wall_pressure=extrapolated\nstiffness=1500\n"
                      "viscosity=0.002\n[kernels]\nh=0.04\n[time]\ndt=0.001\ncfl=0.4\n";
    sph_sim *sim = test_sim(ini, 2);
    double vmax = 0;
    while (sim->t < 0.5 && !sim->alarm.raised) {
        sph_sim_step(sim);
        vmax = fmax(vmax, sim->max_speed);
    }
    char why[8192] = "";
    if (sim->alarm.raised) sph_sim_alarm_report(sim, why, sizeof why);
    cr_log_info("dfsph, extrapolated walls, a box hit at 3.8 m/s: %llu steps, fastest %.3g m/s",
                (unsigned long long)sim->step, vmax);
    cr_assert(!sim->alarm.raised, "the watchdog stopped the run at t = %g s: %.400s", sim->t, why);
    cr_assert_lt(vmax, 10.0, "the impact threw a particle at %g m/s (the other settings' splash: 6.8 to 8.0 m/s)",
                 vmax);
    sph_sim_destroy(sim);
}
