/* [physics] eos_rest: the density the equation of state holds. With lattice,
 * the density the scene's finest lattice sums to at rest (the pressure
 * solvers' rho_rest), so a block placed on the lattice starts at p = 0 and
 * stays still; with rest_density (the default) it starts compressed by the
 * summation's excess e (+1.46 % for poly6 at h = 2 s in 2D) and its free
 * surfaces burst outward. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <string.h>

#include "../src/core/sph_sim.h"
#include "test_util.h"

/* A 2D block of 25 x 25 particles in the middle of a domain four times its
 * size: no gravity, no walls within reach of the fluid in the steps run. */
#define BLOCK_2D                                                                                                  \
    "[scene]\ndimension = 2\neffects = pressure\n[domain]\nmin = 0 0\nmax = 2 2\n[fluid a]\nmin = 0.75 0.75\n"   \
    "max = 1.25 1.25\nspacing = 0.02\n[kernels]\nh = 0.04\n[physics]\nstiffness = 1000\n"

static sph_sim *block(const char *eos, const char *rest)
{
    char ini[1024];
    snprintf(ini, sizeof ini, BLOCK_2D "eos = %s\neos_rest = %s\n", eos, rest);
    return test_sim(ini, 1);
}

static double max_abs_pressure(const sph_sim *sim)
{
    double mx = 0;
    for (uint32_t i = 0; i < sim->n; i++) mx = fmax(mx, fabs(sim->P.p[i]));
    return mx;
}

/* The reference is the solvers' lattice density, above rho0 by e. 2D poly6,
 * W = 4 / (pi h^8) (h^2 - r^2)^3, at h = 2 s: the node itself, 4 at s and 4
 * at sqrt(2) s (those at 2 s = h add nothing) sum to (1 + 4 (3/4)^3 + 4 / 8)
 * / pi = 3.1875 / pi of rho0, e = +1.46 %. */
Test(eos_rest, lattice_reference_is_the_solvers)
{
    sph_sim *a = block("linear", "lattice"), *b = block("linear", "rest_density");
    const float lat = sph_sim_lattice_rest_density(a);
    cr_assert_eq(a->eos_rho0, lat, "eos_rho0 %g, lattice density %g", a->eos_rho0, lat);
    cr_assert_eq(b->eos_rho0, b->def.rest_density, "default: eos_rho0 %g, rest_density %g", b->eos_rho0,
                 b->def.rest_density);
    const double e = lat / a->def.rest_density - 1.0;
    const double want = 3.1875 / 3.141592653589793 - 1.0;
    cr_assert_float_eq(e, want, 1e-5, "lattice excess %g, want %g", e, want);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* At t = 0 (sph_sim_create has run the passes once) the lattice case reads
 * p = 0 within float rounding of the density sum; the default reads k e rho0. */
static void check_start(const char *eos)
{
    sph_sim *a = block(eos, "lattice"), *b = block(eos, "rest_density");
    const double k_rho = a->def.stiffness * a->def.rest_density; /* [Pa] */
    const double pa = max_abs_pressure(a), pb = max_abs_pressure(b);
    const double bound = 1e-5 * k_rho; /* float sums: a relative error of about 1e-6 of rho */
    cr_assert_leq(pa, bound, "%s, lattice: |p| up to %g Pa at t = 0 (bound %g)", eos, pa, bound);
    cr_assert_gt(pb, 100 * bound, "%s, rest_density: |p| up to %g Pa at t = 0, expected about k e rho0", eos, pb);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(eos_rest, zero_pressure_at_start_linear) { check_start("linear"); }
Test(eos_rest, zero_pressure_at_start_tait) { check_start("tait"); }

/* A block at rest stays still for 200 steps with lattice; with rest_density
 * its surface rows burst outward (about c e = 1 m/s at k = 1000). */
static void check_still(const char *eos)
{
    sph_sim *a = block(eos, "lattice"), *b = block(eos, "rest_density");
    for (int s = 0; s < 200; s++) {
        sph_sim_step(a);
        sph_sim_step(b);
    }
    cr_assert(!a->alarm.raised && !b->alarm.raised, "%s: the watchdog stopped a run", eos);
    sph_stats sa, sb;
    sph_sim_stats(a, &sa);
    sph_sim_stats(b, &sb);
    const double bound = 1e-3; /* [m/s] */
    cr_assert_leq(sa.max_speed, bound, "%s, lattice: max speed %g m/s after %g s", eos, sa.max_speed, a->t);
    cr_assert_gt(sb.max_speed, bound * 10, "%s, rest_density: max speed %g m/s, expected the block to burst", eos,
                 sb.max_speed);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

Test(eos_rest, block_stays_still_linear) { check_still("linear"); }
Test(eos_rest, block_stays_still_tait) { check_still("tait"); }

/* The internal energy is measured from the same reference: the block at
 * rest holds none with lattice (p = 0 everywhere), some with rest_density. */
Test(eos_rest, internal_energy_from_the_same_reference)
{
    sph_sim *a = block("linear", "lattice"), *b = block("linear", "rest_density");
    sph_stats sa, sb;
    sph_sim_stats(a, &sa);
    sph_sim_stats(b, &sb);
    cr_assert_gt(sb.eint, 0.0, "rest_density: internal energy %g J/m at rest", sb.eint);
    cr_assert_leq(fabs(sa.eint), 1e-6 * sb.eint, "lattice: internal energy %g J/m, rest_density's %g", sa.eint,
                  sb.eint);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* initial_pressure = hydrostatic with wall particles: the masses, the walls'
 * inverse equation of state and the pressure share the reference, so a
 * column started at its hydrostatic pressure moves far less with lattice
 * (measured: 0.031 m/s after 300 steps) than with rest_density (0.18 m/s),
 * whose bulk starts e above its reference. */
Test(eos_rest, hydrostatic_column_with_wall_particles)
{
    double v[2];
    for (int k = 0; k < 2; k++) {
        char ini[1024];
        snprintf(ini, sizeof ini,
                 "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\n"
                 "max = 0.5 0.6\nwall_model = particles\n[fluid a]\nmin = 0 0\nmax = 0.5 0.4\nspacing = 0.01\n"
                 "initial_pressure = hydrostatic\n[kernels]\nh = 0.02\n[physics]\nstiffness = 400\n"
                 "viscosity = 0.001\neos_rest = %s\n",
                 k ? "rest_density" : "lattice");
        sph_sim *sim = test_sim(ini, 1);
        for (int s = 0; s < 300; s++) sph_sim_step(sim);
        cr_assert(!sim->alarm.raised, "the watchdog stopped the run");
        sph_stats st;
        sph_sim_stats(sim, &st);
        v[k] = st.max_speed;
        sph_sim_destroy(sim);
    }
    cr_assert_leq(v[0], 0.5 * v[1], "max speed %g m/s with lattice, %g with rest_density", v[0], v[1]);
}

Test(eos_rest, bad_value_refused_naming_file_line_value)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    const char *text = "[scene]\ndimension = 2\n[physics]\neos_rest = latice\n";
    sph_error_code c = sph_scene_load_string(text, "x.ini", &def, &err);
    cr_assert_neq(c, SPH_ERR_OK, "eos_rest = latice accepted");
    cr_assert(strstr(err.msg, "x.ini:4") != NULL, "should name x.ini line 4: %s", err.msg);
    cr_assert(strstr(err.msg, "latice") != NULL, "should name the value: %s", err.msg);
    cr_assert(strstr(err.msg, "eos_rest") != NULL, "should name the key: %s", err.msg);
}
