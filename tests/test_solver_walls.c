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
static void check_resting(const char *solver)
{
    char ini[2048];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.2 0.4\n"
             "wall_model=particles\n[fluid w]\nmin=0 0.1\nmax=0.2 0.3\nspacing=0.01\n[obstacle floor]\nmin=0 0\n"
             "max=0.2 0.1\n[physics]\npressure_solver=%s\nsolver_tolerance=%g\nsolver_max_iterations=500\n"
             "viscosity=0.05\nviscosity_form=morris\n[kernels]\nh=0.02\ndensity=cubic\npressure=cubic\n"
             "viscosity=cubic\n[time]\ncfl=0.25\ndt=0.001\n",
             solver, TOL);
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
    const double T = sim->t - t0, Fy = impulse[1] / T, tol = 2 * M * vmax / T + 0.01 * W;
    cr_log_info("%s: weight %g N/m, mean force on the obstacle (%g, %g) N/m, off by %.3g%% (tolerance %.3g%%), "
                "v_max %g m/s",
                solver, W, impulse[0] / T, Fy, 100 * fabs(Fy + W) / W, 100 * tol / W, vmax);
    cr_assert_lt(vmax, 0.02, "%s: the water should stay at rest (v_max %g m/s)", solver, vmax);
    cr_assert_lt(fabs(Fy + W), tol, "%s: mean force %g N/m against the weight %g N/m", solver, Fy, W);
    cr_assert_lt(fabs(impulse[0] / T), tol, "%s: no sideways force on a layer at rest", solver);
    walls_still(sim, x0, solver);
    free(x0);
    sph_sim_destroy(sim);
}

Test(solver_walls, pcisph_resting_water_weighs_on_obstacle, .timeout = 300) { check_resting("pcisph"); }
Test(solver_walls, dfsph_resting_water_weighs_on_obstacle, .timeout = 300) { check_resting("dfsph"); }

/* The dam break of `sphlab validate obstacle` (scenes/validate/obstacle.ini:
 * a column 0.1 m wide and 0.2 m high, a box obstacle from x = 0.2 m) with a
 * solver, to t = 0.3 s, past the impact (about 0.12 s): every solve within its
 * tolerance, the walls still, no fluid particle past the obstacle's first
 * row of wall particles (half a spacing inside it; the solvers let the front
 * reach 0.1 spacing past the face, 0.2005 m). */
static void check_dam(const char *solver)
{
    char ini[2048];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.25 0.3\n"
             "wall_model=particles\nwall_slip=free\n[fluid column]\nmin=0 0\nmax=0.1 0.2\nspacing=0.005\n"
             "[obstacle wall]\nshape=box\nmin=0.2 0\nmax=0.25 0.3\nslip=free\n[physics]\npressure_solver=%s\n"
             "solver_tolerance=%g\nsolver_max_iterations=500\nnegative_pressure=clamp\nviscosity_form=artificial\n"
             "viscosity=0.000001\n[kernels]\nh=0.015\ndensity=wendland\npressure=wendland\nviscosity=wendland\n"
             "[time]\ncfl=0.4\ndt=0.001\n",
             solver, TOL);
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

Test(solver_walls, pcisph_dam_break_on_obstacle, .timeout = 300) { check_dam("pcisph"); }
Test(solver_walls, dfsph_dam_break_on_obstacle, .timeout = 300) { check_dam("dfsph"); }
