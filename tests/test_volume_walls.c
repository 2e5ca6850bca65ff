/* Walls of the volume model ([domain] wall_model = volume; src/core/sph_walls.h,
 * sph_kernel_wall_lattice): the space behind a wall counts as the fluid's
 * lattice continued, so the first row of a lattice block reads the interior's
 * density for every kernel (2D and 3D, h = 2 spacings); a box full of fluid
 * without gravity, with each wall model. The figures are in
 * docs/accuracy.md, sections 2 and 6 (`--verbose` prints them). */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_walls.h"
#include "test_util.h"

static const char *const KERNELS[] = {"poly6", "spiky", "viscosity", "cubic", "wendland"};
enum { N_KERNELS = 5 };

static void run_through(sph_sim *sim, sph_pass_id last)
{
    for (int guard = 0; guard < 2 * SPH_PASS_COUNT; guard++)
        if (sph_sim_step_pass(sim) == last) return;
    cr_assert_fail("pass %s never ran", sph_passes[last]->name);
}

/* First density pass of a block filling a box's lower part, lattice spacing
 * 0.01 m, h = 0.02 m: the mean density of the row on the floor and of the
 * interior (at least 3 h from every wall and from the surface), both away
 * from the side walls by 3 h. */
static void first_row(int dim, const char *model, const char *kernel, double *row, double *inner)
{
    char ini[1024];
    if (dim == 2)
        snprintf(ini, sizeof ini,
                 "[scene]\ndimension=2\neffects=gravity pressure walls\n[domain]\nmin=0 0\nmax=0.4 0.5\n"
                 "wall_model=%s\n[fluid water]\nmin=0 0\nmax=0.4 0.3\nspacing=0.01\n[kernels]\nh=0.02\n"
                 "density=%s\npressure=%s\n",
                 model, kernel, kernel);
    else
        snprintf(ini, sizeof ini,
                 "[scene]\ndimension=3\neffects=gravity pressure walls\n[domain]\nmin=0 0 0\nmax=0.2 0.3 0.2\n"
                 "wall_model=%s\n[fluid water]\nmin=0 0 0\nmax=0.2 0.2 0.2\nspacing=0.01\n[kernels]\nh=0.02\n"
                 "density=%s\npressure=%s\n",
                 model, kernel, kernel);
    sph_sim *sim = test_sim(ini, 2);
    run_through(sim, SPH_PASS_DENSITY);
    const float lo = 0.06f, hi = dim == 2 ? 0.34f : 0.14f, top = dim == 2 ? 0.24f : 0.14f;
    double sr = 0, si = 0;
    int nr = 0, ni = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (sph_is_wall(&sim->P, i)) continue;
        float x = sim->P.pos[0][i], y = sim->P.pos[1][i], z = dim == 3 ? sim->P.pos[2][i] : 0.5f * (lo + hi);
        if (x < lo || x > hi || z < lo || z > hi) continue;
        if (y < 0.01f) {
            sr += sim->P.rho[i];
            nr++;
        } else if (y > 0.06f && y < top) {
            si += sim->P.rho[i];
            ni++;
        }
    }
    cr_assert(nr > 0 && ni > 0);
    *row = sr / nr;
    *inner = si / ni;
    sph_sim_destroy(sim);
}

static void first_row_within(int dim)
{
    for (int k = 0; k < N_KERNELS; k++) {
        double row, inner;
        first_row(dim, "volume", KERNELS[k], &row, &inner);
        cr_log_info("%dD %s, h = 2 spacings: first row / interior %.4f (interior / rho0 %.4f)", dim, KERNELS[k],
                    row / inner, inner / 1000.0);
        /* the walls issue's target: within 0.5 %; the integral psi(d) gave
         * +1.5 % (poly6) to +3.9 % (Wendland) in 2D */
        cr_assert(fabs(row / inner - 1.0) < 0.005, "%dD %s: first row %.2f, interior %.2f", dim, KERNELS[k], row,
                  inner);
    }
}

Test(volume_walls, first_row_reads_the_interior_2d) { first_row_within(2); }
Test(volume_walls, first_row_reads_the_interior_3d) { first_row_within(3); }

/* The tables: the lattice share tends to the integral psi as the spacing
 * shrinks, and its slope table is its derivative. */
Test(volume_walls, lattice_share_tends_to_the_integral)
{
    for (int dim = 2; dim <= 3; dim++)
        for (int kind = 0; kind < SPH_KERNEL_COUNT; kind++) {
            sph_kernel k = sph_kernel_make((sph_kernel_kind)kind, dim, 1.0f);
            double err[2];
            const float spacing[2] = {0.5f, 0.05f};
            for (int s = 0; s < 2; s++) {
                sph_kernel_wall_lattice(&k, spacing[s]);
                err[s] = 0;
                for (int i = 0; i <= SPH_WALL_TABLE; i++) err[s] = fmax(err[s], fabs(k.wall_lat_psi[i] - k.wall_psi[i]));
            }
            cr_assert_lt(err[1], 0.01, "%dD %s: |lattice - integral| %g at s = h/20", dim, sph_kernel_names[kind],
                         err[1]);
            if (kind != SPH_KERNEL_VISCOSITY) /* its shape is almost flat: close at both spacings */
                cr_assert_lt(err[1], err[0], "%dD %s", dim, sph_kernel_names[kind]);
            /* slope = -d psi / dd, by central differences of the table (h / 128 apart) */
            sph_kernel_wall_lattice(&k, 0.25f);
            for (int i = 8; i < SPH_WALL_TABLE - 8; i += 8) {
                double slope = -(k.wall_lat_psi[i + 1] - k.wall_lat_psi[i - 1]) * SPH_WALL_TABLE / 2.0;
                cr_assert(fabs(slope - k.wall_lat_area[i]) <= 0.05 * k.wall_lat_area[0] + 1e-3,
                          "%dD %s at %d: slope %g, table %g", dim, sph_kernel_names[kind], i, slope,
                          k.wall_lat_area[i]);
            }
        }
}

static const char *const MODELS[] = {"volume", "particles", "reflect"};

/* A box full of fluid, no gravity: every particle's support is full (with
 * the walls' share), the lattice's density is the same everywhere and so is
 * the pressure. With wall particles nothing moves. */
Test(volume_walls, full_box_without_gravity_stays_at_rest)
{
    int fails = 0;
    for (int m = 0; m < 3; m++)
        for (int k = 0; k < N_KERNELS; k += 3) { /* poly6 and cubic */
            char ini[1024];
            snprintf(ini, sizeof ini,
                     "[scene]\ndimension=2\neffects=pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.2 0.2\n"
                     "wall_model=%s\nwall_force=ghost\n[fluid a]\nmin=0 0\nmax=0.2 0.2\nspacing=0.01\n[physics]\nstiffness=400\n"
                     "viscosity_form=morris\n[kernels]\nh=0.02\ndensity=%s\npressure=cubic\nviscosity=cubic\n"
                     "[time]\ncfl=0.25\n",
                     MODELS[m], KERNELS[k]);
            sph_sim *sim = test_sim(ini, 2);
            for (int s = 0; s < 300; s++) sph_sim_step(sim);
            sph_stats st;
            sph_sim_stats(sim, &st);
            cr_assert(!sim->alarm.raised);
            cr_log_info("full box, %s walls, density %s, 300 steps: max speed %.3g m/s (c = 20 m/s)", MODELS[m],
                        KERNELS[k], st.max_speed);
            /* wall particles: at rest (measured 6.6e-5, 7.4e-5 m/s). Volume
             * walls, wall_force = ghost: the hidden lattice pushes as ghost particles in the pair
             * term, so the lattice's own overpressure is held as by wall
             * particles (measured 8.0e-5, 7.2e-5 m/s; the energy form
             * -(p/rho^2) grad(rho0 H), half that pair term, gave 0.32 and
             * 0.012 m/s). Reflecting walls: the rows at the walls miss
             * support, nothing holds them (0.27, 0.018 m/s). */
            const double bound = m < 2 ? 1e-4 : INFINITY;
            fails += st.max_speed >= bound;
            sph_sim_destroy(sim);
        }
    cr_assert_eq(fails, 0);
}


/* Far beyond 16 spacings per h the tables are the integral's (summing the
 * lattice there costs (h/s)^dim per point); at 16 they agree within 6e-4. */
Test(volume_walls, fine_lattice_tables_are_the_integral)
{
    for (int dim = 2; dim <= 3; dim++) {
        sph_kernel k = sph_kernel_make(SPH_KERNEL_CUBIC, dim, 1.0f);
        sph_kernel fine = k;
        sph_kernel_wall_lattice(&fine, 1.0f / 300.0f);
        cr_expect_eq(fine.wall_lat_full, 1.0f, "%dD", dim);
        for (int i = 0; i <= SPH_WALL_TABLE; i++)
            cr_expect_eq(fine.wall_lat_psi[i], k.wall_psi[i], "%dD, point %d", dim, i);
        sph_kernel at16 = k;
        sph_kernel_wall_lattice(&at16, 1.0f / SPH_WALL_LATTICE_MAX);
        for (int i = 0; i <= SPH_WALL_TABLE; i++)
            cr_expect_leq(fabsf(at16.wall_lat_psi[i] / at16.wall_lat_full - k.wall_psi[i]), 6e-4f, "%dD, point %d", dim,
                          i);
    }
}

/* A lattice block at rest on the floor of a box (0.3 m wide, 0.3 m deep,
 * spacing 0.015 m, h = 2 spacings, k = 400 m²/s², Morris nu = 0.05 m²/s,
 * gravity ramped in over 0.3 s; the density kernel as given, pressure and
 * viscosity cubic). *row0: first row / interior density at t = 0 (first
 * density pass); returns the largest fluid speed between 1.0 and 1.2 s as a
 * share of sqrt(g H), or INFINITY if the watchdog stopped it. */
static double block_at_rest(const char *model, const char *kernel, const char *eos_rest, const char *extra,
                            double *row0)
{
    char ini[1600];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n"
             "[domain]\nmin=0 0\nmax=0.3 0.5\nwall_model=%s\nwall_force=ghost\n"
             "[fluid water]\nmin=0 0\nmax=0.3 0.3\nspacing=0.015\n"
             "[physics]\nrest_density=1000\neos=linear\nstiffness=400\nnegative_pressure=clamp\n"
             "viscosity_form=morris\nviscosity=0.05\ngravity_ramp=0.3\neos_rest=%s\n"
             "%s[kernels]\nh=0.03\ndensity=%s\npressure=cubic\nviscosity=cubic\n[time]\ncfl=0.25\ndt=0.001\n",
             model, eos_rest, extra, kernel);
    sph_sim *sim = test_sim(ini, 2);
    double sr = 0, si = 0;
    int nr = 0, ni = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (sph_is_wall(&sim->P, i)) continue;
        const float x = sim->P.pos[0][i], y = sim->P.pos[1][i];
        if (x < 0.09f || x > 0.21f) continue;
        if (y < 0.015f) sr += sim->P.rho[i], nr++;
        else if (y > 0.09f && y < 0.21f) si += sim->P.rho[i], ni++;
    }
    cr_assert(nr > 0 && ni > 0);
    *row0 = (sr / nr) / (si / ni);
    double worst = 0;
    const double t_end = getenv("T_END") ? atof(getenv("T_END")) : 1.2;
    double wmax = 0; int win = 0;
    while (sim->t < t_end && !sim->alarm.raised) {
        sph_sim_step(sim);
        if (getenv("T_END")) {
            double m = 0;
            for (uint32_t i = 0; i < sim->n; i++) m = fmax(m, hypot(sim->P.vel[0][i], sim->P.vel[1][i]));
            wmax = fmax(wmax, m);
            if ((int)(sim->t / 0.2) != win) { cr_log_info("  t %.1f max %.3g", sim->t, wmax / sqrt(9.81*0.3)); wmax = 0; win = (int)(sim->t / 0.2); }
        }
        if (sim->t < t_end - 0.2) continue;
        for (uint32_t i = 0; i < sim->n; i++) {
            if (sph_is_wall(&sim->P, i)) continue;
            worst = fmax(worst, hypot(sim->P.vel[0][i], sim->P.vel[1][i]));
        }
    }
    const bool stopped = sim->alarm.raised;
    sph_sim_destroy(sim);
    return stopped ? INFINITY : worst / sqrt(9.81 * 0.3);
}

/* The table of docs/accuracy.md, section 6 ("A block at rest, every wall
 * model"): minutes on 2 cores, so it runs only when SPHLAB_TABLES is set.
 * TABLE_MODEL=NAME runs one wall model, CONT=1 carries the density by the
 * continuity equation with Fourtakas's diffusion, T_END=T moves the window
 * to [T - 0.2, T] s and prints the largest speed every 0.2 s. */
Test(volume_walls, block_at_rest_table, .timeout = 900)
{
    if (!getenv("SPHLAB_TABLES")) cr_skip_test("set SPHLAB_TABLES=1 to print the table");
    const char *only = getenv("TABLE_MODEL");
    for (int m = 0; m < 3; m++)
        if (!only || !strcmp(only, MODELS[m]))
        for (int r = 0; r < 2; r++)
            for (int k = 0; k < N_KERNELS; k++) {
                const char *rest = r ? "lattice" : "rest_density";
                const char *cont = getenv("CONT") ? "density_method=continuity\ndelta=0.1\ndelta_form=fourtakas\n" : "";
                double row0, v = block_at_rest(MODELS[m], KERNELS[k], rest, cont, &row0);
                cr_log_info("block at rest: %-9s %-12s %-9s first row / interior %.4f, max speed 1-1.2 s %.3g sqrt(gH)",
                            MODELS[m], rest, KERNELS[k], row0, v);
            }
}

/* The target "a lattice block at rest stays at rest (max speed below
 * 1e-3 sqrt(g H) after settling)" with volume walls (wall_force = ghost): the block above with the
 * density carried by the continuity equation and Fourtakas et al. 2019's
 * diffusion (as `sphlab validate hydrostatic`), h = 2 spacings, for the
 * density kernels that read the lattice's density within 4 % (poly6, cubic,
 * Wendland; spiky and viscosity read 1.27 and 3.6 rho0, section 2). Measured
 * 5.2e-4, 5.8e-4 and 5.3e-4 sqrt(g H) between 1.0 and 1.2 s; before (the
 * energy form of the wall force, and the continuity's wall term blind to the
 * step's gravity kick) the row at the floor sank and the tank circulated. */
Test(volume_walls, block_at_rest_stays_at_rest, .timeout = 300)
{
    const char *kernels[] = {"poly6", "cubic", "wendland"};
    for (int k = 0; k < 3; k++) {
        double row0, v = block_at_rest("volume", kernels[k], "rest_density",
                                       "density_method=continuity\ndelta=0.1\ndelta_form=fourtakas\n", &row0);
        cr_log_info("volume walls, %s: max speed 1.0-1.2 s %.3g sqrt(gH)", kernels[k], v);
        /* v: the fluid's largest speed over simulated t = 1.0-1.2 s as a share of sqrt(g H), a physical
         * result of the run, the same on any machine (not a timing) */
        cr_expect_lt(v, 1e-3, "volume walls, %s: max speed %.3g sqrt(gH) after settling", kernels[k], v);
    }
}
