/* sphlab validate: the published numbers and exact solutions it measures
 * against (src/validate/validate_ref.c), the moving top wall the Couette
 * problem needs, and the command's outputs, verdicts and refusals. */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <math.h>
#include <stdio.h>
#include <string.h>
#include <sys/stat.h>

#include "sph_walls.h"
#include "test_util.h"
#include "validate.h"

#define PI 3.14159265358979323846

/* ---- reference data ------------------------------------------------------- */

Test(validate, surge_data_are_the_published_numbers)
{
    cr_assert_eq(VAL_SURGE_CURVES, 3);
    /* a value from each curve, as read from the papers (validate_ref.c names the sources) */
    cr_assert_float_eq(val_surge[0].y[2], 1.884, 1e-12, "Martin & Moyce, a = 1.125 in, T = 1.602");
    cr_assert_float_eq(val_surge[1].x[2], 1.997, 1e-12);
    cr_assert_float_eq(val_surge[1].y[2], 2.292, 1e-12, "Martin & Moyce, a = 2.25 in, T = 1.997");
    cr_assert_float_eq(val_surge[2].y[0], 1.0, 1e-12, "Koshizuka & Oka start at the column's width");
    cr_assert_eq(val_surge[0].n, 10);
    cr_assert_eq(val_surge[1].n, 15);
    cr_assert_eq(val_surge[2].n, 9);
    for (int k = 0; k < VAL_SURGE_CURVES; k++)
        for (int i = 1; i < val_surge[k].n; i++) {
            cr_assert_gt(val_surge[k].x[i], val_surge[k].x[i - 1], "curve %d: T increasing", k);
            cr_assert_gt(val_surge[k].y[i], val_surge[k].y[i - 1], "curve %d: the front only advances", k);
        }
}

Test(validate, surge_table_2_is_quarter_inches_of_the_2_25_in_column)
{
    const val_curve *c = &val_surge_table2;
    cr_assert_eq(c->n, 15);
    cr_assert_float_eq(c->x[1], 0.84, 1e-12);
    cr_assert_float_eq(c->y[1], 1.22, 1e-12);
    for (int i = 0; i < c->n; i++) {
        /* the front read in quarter inches over a = 2.25 in: Z = 1 + k/9 */
        double k = (c->y[i] - 1.0) * 9.0;
        cr_assert_float_eq(k, round(k), 0.06, "T = %.2f: Z = %.2f is not 1 + k/9", c->x[i], c->y[i]);
        if (i) cr_assert_gt(c->x[i], c->x[i - 1]);
        /* the same column as the Figure 3 curve val_surge[1], within 3 %
         * (at most 0.09 in Z: the figure's points, joined by straight
         * lines, are sparser than the table's) */
        double f3 = val_curve_at(&val_surge[1], c->x[i]);
        if (isfinite(f3))
            cr_assert_lt(fabs(c->y[i] / f3 - 1), 0.03, "T = %.2f: %.3f vs Figure 3 %.3f", c->x[i], c->y[i], f3);
    }
}

Test(validate, column_height_data_are_martin_and_moyce_table_6)
{
    const val_curve *c = &val_column;
    cr_assert_eq(c->n, 17);
    cr_assert_float_eq(c->x[0], 0.56, 1e-12, "tau = t sqrt(g/a) of the first row");
    cr_assert_float_eq(c->y[0], 0.94, 1e-12);
    cr_assert_float_eq(c->x[8], 2.00, 1e-12);
    cr_assert_float_eq(c->y[8], 0.50, 1e-12, "half the column left at tau = 2");
    cr_assert_float_eq(c->x[16], 7.40, 1e-12);
    cr_assert_float_eq(c->y[16], 0.06, 1e-12);
    for (int i = 0; i < c->n; i++) {
        /* whole quarter inches over 2a = 4.5 in, as read off a scale */
        cr_assert_float_eq(c->y[i] * 18.0, round(c->y[i] * 18.0), 0.1, "row %d: H = %g is not k/18", i, c->y[i]);
        /* the top cannot fall faster than free fall: H >= 1 - tau^2/4 */
        cr_assert_geq(c->y[i], 1.0 - 0.25 * c->x[i] * c->x[i], "row %d falls faster than free fall", i);
        if (i) {
            cr_assert_gt(c->x[i], c->x[i - 1], "row %d: tau increasing", i);
            cr_assert_lt(c->y[i], c->y[i - 1], "row %d: the column only falls", i);
        }
    }
}

/* The drop's period from the crossings through the mean (val_drop.c), on a damped sine of known period
 * sampled as the run samples D_x - D_y: over 3.3 periods the mean sits off the centre line and the half
 * periods alternate short and long; counting an even number of them gives the period within 0.5 %. Over
 * every crossing (5 half periods at 3.3 periods) the earlier count read it 1.0 % long. */
Test(validate, drop_period_from_crossings_of_a_damped_sine)
{
    const double T = 2.5, decay = 0.04;
    for (int run = 0; run < 3; run++) {
        const double span = (3.1 + 0.2 * run) * T, phase = 0.3 * run;
        static double x[5000], y[5000];
        size_t n = 0;
        for (double t = 0; t < span && n < 5000; t += 0.002, n++)
            x[n] = t, y[n] = 0.007 * exp(-decay * t) * sin(2 * PI * t / T + phase) + 0.001;
        int k = 0;
        double got = val_period_crossings(x, y, n, &k);
        cr_assert_geq(k, 6, "%d crossings over %.2f periods", k, span / T);
        cr_assert(fabs(got / T - 1) < 0.005, "span %.2f periods: period %.5f s for %.5f s", span / T, got, T);
    }
    double x[100], y[100]; /* too short to tell: one crossing */
    for (int i = 0; i < 100; i++) x[i] = 0.006 * T * i, y[i] = sin(2 * PI * x[i] / T + 1);
    int k = 0;
    cr_assert(isnan(val_period_crossings(x, y, 100, &k)), "%d crossings", k);
}

/* The half periods (val_drop.c's verdict). A kicked drop's D_x - D_y is a sine from its centre; through the
 * record's mean its half periods alternate short and long by at most val_half_period_bound (0.27 at 1.5
 * periods, 0.135 at 3): damped sines of the 2D and 3D drops' decay over 1.5 and 3 periods stay within it. The
 * 3D R/10 drop's record (crossings at 0.99, 2.37 and 3.17 s: half periods 1.38 and 0.80 s over 1.5 periods of
 * 2.197 s) is no steady period and must be beyond it, though its full period read -1.1 %. The decay widens
 * the bound by the ratio of the first half period's amplitude to the last's (val_amplitude_ratio). */
Test(validate, drop_half_periods_tell_a_steady_period)
{
    cr_assert_float_eq(val_half_period_bound(1.5, 1.0), 4 * asin(1 / (1.5 * PI)) / PI, 1e-12);
    static double x[5000], y[5000];
    const double T = 2.4;
    for (int run = 0; run < 4; run++) {
        const double span = (run % 2 ? 3.0 : 1.5) * T, zeta = run < 2 ? 0.0133 : 0.063, w = 2 * PI / T;
        size_t n = 0;
        for (double t = 0; t < span && n < 5000; t += 0.01, n++)
            x[n] = t, y[n] = 0.007 * exp(-zeta * w * t) * sin(w * t) + 0.001;
        double c[16];
        int k = val_crossing_times(x, y, n, c, 16);
        double spread = val_half_period_spread(c, k),
               bound = val_half_period_bound(span / T, val_amplitude_ratio(x, y, n, c, k));
        cr_log_info("%.1f periods, zeta %.3g: %d crossings, spread %.3f, bound %.3f\n", span / T, zeta, k, spread,
                    bound);
        cr_assert_geq(k, 3);
        cr_assert_leq(spread, bound, "%.1f periods: spread %.3f above %.3f", span / T, spread, bound);
    }
    /* the 3D R/10 drop's record: a sine whose phase runs at pi / 1.38 s, then pi / 0.80 s from 2.37 s */
    const double T3 = 2.197, span = 1.5 * T3;
    size_t n = 0;
    for (double t = 0; t < span && n < 5000; t += 0.01, n++) {
        double ph = t < 2.37 ? PI * (t - 0.99) / 1.38 : PI + PI * (t - 2.37) / 0.80;
        x[n] = t, y[n] = 0.004 * sin(ph);
    }
    double c[16];
    int k = val_crossing_times(x, y, n, c, 16);
    double spread = val_half_period_spread(c, k),
           bound = val_half_period_bound(span / T3, val_amplitude_ratio(x, y, n, c, k));
    cr_log_info("3D R/10's record: %d crossings, spread %.3f, bound %.3f\n", k, spread, bound);
    cr_assert_eq(k, 3, "%d crossings", k);
    cr_assert_gt(spread, bound, "half periods %.3f and %.3f s: spread %.3f within %.3f", c[1] - c[0], c[2] - c[1],
                 spread, bound);
}

Test(validate, curve_interpolates_inside_and_is_nan_outside)
{
    const val_curve *c = &val_surge[2];
    cr_assert_float_eq(val_curve_at(c, c->x[3]), c->y[3], 1e-12);
    double mid = 0.5 * (c->x[3] + c->x[4]);
    cr_assert_float_eq(val_curve_at(c, mid), 0.5 * (c->y[3] + c->y[4]), 1e-12);
    cr_assert(isnan(val_curve_at(c, -0.1)));
    cr_assert(isnan(val_curve_at(c, c->x[c->n - 1] + 0.1)));
}

/* ---- exact solutions -------------------------------------------------------- */

/* The column at rest of a weakly compressible fluid: the floor carries the
 * weight, the linear equation of state has the closed form, the mass is
 * rho0 H0 per unit area, and the incompressible column is the limit. */
/* The main body's front: a 10 x 5 block of spacing s with a lone particle
 * 2.5 s ahead of it on the floor and a two-particle drop 6 s ahead; the
 * rightmost particle of all is the drop's. */
Test(validate, front_of_the_main_body_leaves_out_what_is_thrown_ahead)
{
    double x[64], y[64], s = 0.01;
    size_t n = 0, body = 0;
    for (int j = 0; j < 5; j++)
        for (int i = 0; i < 10; i++) x[n] = i * s, y[n++] = j * s;
    x[n] = 9 * s + 2.5 * s, y[n++] = 0;         /* the lone particle */
    x[n] = 9 * s + 6 * s, y[n++] = 2 * s;       /* the drop */
    x[n] = 9 * s + 6.8 * s, y[n++] = 2.2 * s;
    cr_assert_float_eq(val_front_connected(x, y, n, 1.5 * s, &body), 9 * s, 1e-12, "links < 1.5 s: the block's edge");
    cr_assert_eq(body, 50);
    /* links < 3 s reach the lone particle (2.5 s away), not the drop (4.03 s from it) */
    cr_assert_float_eq(val_front_connected(x, y, n, 3 * s, &body), 11.5 * s, 1e-12);
    cr_assert_eq(body, 51);
    /* links < 4.5 s join everything: the front is the drop's far particle */
    cr_assert_float_eq(val_front_connected(x, y, n, 4.5 * s, &body), 15.8 * s, 1e-12);
    cr_assert_eq(body, 53);
    /* a larger group ahead wins over a smaller one behind: the body is the largest group */
    double cx[] = {0, 10 * s, 10.5 * s, 11 * s}, cy[] = {0, 0, 0, 0};
    cr_assert_float_eq(val_front_connected(cx, cy, 4, s, &body), 11 * s, 1e-12);
    cr_assert_eq(body, 3);
    cr_assert(isnan(val_front_connected(x, y, 0, s, NULL)), "no particles");
    cr_assert(isnan(val_front_connected(x, y, n, 0, NULL)), "no link length");
}

Test(validate, hydrostatic_column_of_the_equation_of_state)
{
    const double rho0 = 1000, g = 9.81, H0 = 0.3, k = 400;
    const val_eos lin = {rho0, k, 0}, tait = {rho0, k, 7}, stiff = {rho0, 1e9, 0};
    cr_assert_float_eq(val_hydrostatic_p(&lin, g, H0, 0), rho0 * g * H0, 1e-9);
    double mass = 0, dy = H0 / 20000; /* the column's mass up to where p = 0 (its top, below H0) */
    for (double y = 0.5 * dy; val_hydrostatic_p(&lin, g, H0, y) > 0; y += dy)
        mass += (rho0 + val_hydrostatic_p(&lin, g, H0, y) / k) * dy;
    cr_assert_float_eq(mass, rho0 * H0, 1e-3 * rho0 * H0, "mass %g, want %g", mass, rho0 * H0);
    for (double y = 0; y <= H0; y += 0.05) {
        double exact = k * rho0 * ((1 + g * H0 / k) * exp(-g * y / k) - 1);
        cr_assert_float_eq(val_hydrostatic_p(&lin, g, H0, y), exact, 1e-8 * rho0 * g * H0, "linear, y = %g", y);
        cr_assert_float_eq(val_hydrostatic_p(&stiff, g, H0, y), rho0 * g * (H0 - y), 1e-5 * rho0 * g * H0);
        /* the compressed column's pressure lies below rho0 g (H0 - y), by
         * at most g H0 / 2k of rho0 g H0 (at the top): 0.37 % here */
        double lo = rho0 * g * (H0 - y) - (g * H0 / (2 * k)) * rho0 * g * H0 * 1.01;
        cr_assert(val_hydrostatic_p(&lin, g, H0, y) <= rho0 * g * (H0 - y) + 1e-9 && val_hydrostatic_p(&lin, g, H0, y) >= lo,
                  "y = %g", y);
        cr_assert(fabs(val_hydrostatic_p(&tait, g, H0, y) - exact) < 2e-3 * rho0 * g * H0, "Tait near linear, y = %g", y);
    }
}

/* The reference `validate hydrostatic` builds from a run: with [physics] eos_rest = lattice the pressure is
 * relative to the lattice's density (sim->eos_rho0), not rest_density, and the exact column must be that
 * fluid's (else it is off by (eos_rho0 - rest_density) g y: 1.5 % of rho0 g H at the top with poly6 at
 * h = 2 spacings); the floor carries the fluid's weight either way. */
Test(validate, hydrostatic_reference_uses_the_runs_equation_of_state)
{
    for (int lattice = 0; lattice < 2; lattice++) {
        char ini[800];
        snprintf(ini, sizeof ini,
                 "[scene]\ndimension=2\neffects=gravity pressure walls\n[domain]\nmin=0 0\nmax=0.3 0.5\n"
                 "wall_model=particles\n[fluid water]\nmin=0 0\nmax=0.3 0.3\nspacing=0.01\n[physics]\n"
                 "stiffness=400\neos_rest=%s\n[kernels]\nh=0.02\ndensity=poly6\n",
                 lattice ? "lattice" : "rest_density");
        sph_sim *sim = test_sim(ini, 1);
        val_eos e;
        const double H = val_hydrostatic_column(sim, &e), g = 9.81, W = 0.3;
        double mass = 0;
        for (uint32_t i = 0; i < sim->n; i++)
            if (!sph_is_wall(&sim->P, i)) mass += sim->P.mass[i];
        cr_assert_float_eq(e.rho0, sim->eos_rho0, 1e-6 * sim->eos_rho0, "rho0 %g, the run's %g", e.rho0,
                           (double)sim->eos_rho0);
        cr_assert_float_eq(e.k, 400.0, 1e-9);
        cr_assert_float_eq(e.rho0 * g * H, mass * g / W, 1e-6 * mass * g / W, "the floor carries the weight");
        const double scale = mass * g / W, y = 0.25;
        /* the closed form of the linear equation of state about the run's rho0 */
        const double exact = e.k * e.rho0 * ((1 + g * H / e.k) * exp(-g * y / e.k) - 1);
        cr_assert_float_eq(val_hydrostatic_p(&e, g, H, y), exact, 1e-8 * scale);
        if (lattice) { /* the fluid's rest_density would give another column */
            const val_eos rest = {sim->def.rest_density, e.k, 0};
            const double off = val_hydrostatic_p(&rest, g, mass / (rest.rho0 * W), y) - exact;
            cr_log_info("eos_rest = lattice: rho0 %.2f (rest_density %.0f); at y = %.2f m the rest_density column "
                        "differs by %.2f %% of rho0 g H",
                        e.rho0, rest.rho0, y, 100 * off / scale);
            cr_assert_gt(fabs(off), 5e-3 * scale);
        }
        sph_sim_destroy(sim);
    }
}

Test(validate, poiseuille_series_tends_to_the_parabola_and_starts_at_rest)
{
    const double F = 2e-4, nu = 1e-6, L = 1e-3, umax = F * L * L / (8 * nu);
    cr_assert_float_eq(val_poiseuille_steady(L / 2, F, nu, L), umax, 1e-15 * umax + 1e-20);
    for (int i = 1; i < 10; i++) {
        double y = i * L / 10;
        /* t -> infinity (ten e-folding times of the slowest mode): the parabola */
        cr_assert_float_eq(val_poiseuille(y, 10 * L * L / nu, F, nu, L, 200), val_poiseuille_steady(y, F, nu, L),
                           1e-12 * umax);
        /* t = 0: at rest (the series is the parabola's sine series; 200 terms leave < 1e-5) */
        cr_assert_lt(fabs(val_poiseuille(y, 0, F, nu, L, 200)), 1e-5 * umax, "y = %g", y);
    }
    /* it solves u_t = F + nu u_yy (finite differences, at a start-up time) */
    double y = 0.3 * L, t = 0.05 * L * L / nu, dy = 1e-3 * L, dt = 1e-4 * t;
    double ut = (val_poiseuille(y, t + dt, F, nu, L, 200) - val_poiseuille(y, t - dt, F, nu, L, 200)) / (2 * dt);
    double uyy = (val_poiseuille(y + dy, t, F, nu, L, 200) - 2 * val_poiseuille(y, t, F, nu, L, 200) +
                  val_poiseuille(y - dy, t, F, nu, L, 200)) / (dy * dy);
    cr_assert_float_eq(ut, F + nu * uyy, 1e-4 * F);
}

Test(validate, couette_series_tends_to_the_line_and_keeps_the_walls)
{
    const double U = 0.025, nu = 1, L = 1;
    for (int i = 0; i <= 10; i++) {
        double y = i * L / 10;
        cr_assert_float_eq(val_couette(y, 10, U, nu, L, 400), U * y / L, 1e-12, "steady at y = %g", y);
    }
    cr_assert_float_eq(val_couette(0, 0.01, U, nu, L, 400), 0, 1e-15, "the still wall");
    cr_assert_float_eq(val_couette(L, 0.01, U, nu, L, 400), U, 1e-12, "the moving wall");
    cr_assert_lt(fabs(val_couette(0.5, 0, U, nu, L, 400)), 2e-3 * U, "at rest at t = 0");
    double y = 0.6, t = 0.05, dy = 1e-3, dt = 1e-5;
    double ut = (val_couette(y, t + dt, U, nu, L, 400) - val_couette(y, t - dt, U, nu, L, 400)) / (2 * dt);
    double uyy = (val_couette(y + dy, t, U, nu, L, 400) - 2 * val_couette(y, t, U, nu, L, 400) +
                  val_couette(y - dy, t, U, nu, L, 400)) / (dy * dy);
    cr_assert_float_eq(ut, nu * uyy, 1e-4 * U, "u_t = nu u_yy");
}

Test(validate, taylor_green_decays_at_8_pi2_nu_and_is_divergence_free)
{
    const double U = 1, nu = 0.01, L = 1, t = 0.7;
    cr_assert_float_eq(val_tg_decay(nu, L, t), exp(-8 * PI * PI * nu * t), 1e-15);
    /* the largest speed is U exp(bt), at (L/4, 0) */
    double v[2];
    val_tg_velocity(0.25 * L, 0, t, U, nu, L, v);
    cr_assert_float_eq(hypot(v[0], v[1]), U * val_tg_decay(nu, L, t), 1e-12);
    /* div v = 0 at a few points (central differences) */
    const double d = 1e-6;
    for (int i = 0; i < 5; i++) {
        double x = 0.13 + 0.17 * i, y = 0.71 - 0.11 * i, a[2], b[2], c[2], e[2];
        val_tg_velocity(x + d, y, t, U, nu, L, a);
        val_tg_velocity(x - d, y, t, U, nu, L, b);
        val_tg_velocity(x, y + d, t, U, nu, L, c);
        val_tg_velocity(x, y - d, t, U, nu, L, e);
        cr_assert_lt(fabs((a[0] - b[0]) / (2 * d) + (c[1] - e[1]) / (2 * d)), 1e-6);
    }
    cr_assert_float_eq(val_order(25, 0.08, 50, 0.02), 2.0, 1e-12);
    cr_assert(isnan(val_order(25, 0, 50, 0.02)));
}

/* ---- the moving top wall ---------------------------------------------------- */

static const char *channel_ini(const char *extra)
{
    static char ini[1024];
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=pressure viscosity walls\n[domain]\nmin=0 0\nmax=1.2 1\nperiodic=x\n"
             "wall_model=particles\nwall_slip=no\n%s\n[fluid c]\nmin=0 0\nmax=1.2 1\nspacing=0.1\n"
             "[physics]\nstiffness=1\nviscosity=1\nviscosity_form=morris\nnegative_pressure=keep\n"
             "[kernels]\nh=0.3\ndensity=wendland\npressure=wendland\nviscosity=wendland\n[time]\ncfl=0.125\ndt=0.01\n",
             extra);
    return ini;
}

Test(validate, wall_velocity_drags_the_fluid_and_is_refused_where_it_cannot_be)
{
    sph_sim *sim = test_sim(channel_ini("wall_velocity=0.025 0"), 1);
    while (sim->t < 0.3) sph_sim_step(sim);
    double top = 0, bottom = 0;
    int nt = 0, nb = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (sph_is_wall(&sim->P, i)) {
            /* the wall particles stay where they were put */
            cr_assert(sim->P.pos[1][i] < 0 || sim->P.pos[1][i] > 1);
            continue;
        }
        if (sim->P.pos[1][i] > 0.8) top += sim->P.vel[0][i], nt++;
        if (sim->P.pos[1][i] < 0.2) bottom += sim->P.vel[0][i], nb++;
    }
    top /= nt;
    bottom /= nb;
    /* the exact mean over the top rows at t = 0.3 s is about 0.6 U; the bottom's about 0.1 U */
    cr_assert_gt(top, 0.4 * 0.025, "top rows move with the wall: %g m/s", top);
    cr_assert_lt(bottom, 0.25 * 0.025, "bottom rows lag: %g m/s", bottom);
    sph_sim_destroy(sim);

    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    cr_assert_eq(sph_scene_set(&def, "domain.wall_velocity=1 0", &err), SPH_ERR_OK);
    cr_assert_neq(sph_scene_validate(&def, &err), SPH_ERR_OK, "wall_model = volume cannot move a wall");
    cr_assert(strstr(err.msg, "wall_velocity") && strstr(err.msg, "wall_model = particles"), "%s", err.msg);
    cr_assert_eq(sph_scene_set(&def, "domain.wall_model=particles", &err), SPH_ERR_OK);
    cr_assert_eq(sph_scene_set(&def, "domain.wall_velocity=0 1", &err), SPH_ERR_OK);
    cr_assert_neq(sph_scene_validate(&def, &err), SPH_ERR_OK, "a wall moving along its normal");
    cr_assert(strstr(err.msg, "wall_velocity y = 1"), "%s", err.msg);
}

/* ---- the command ------------------------------------------------------------ */

static bool nonempty(const char *dir, const char *name, const char *ext)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s.%s", dir, name, ext);
    struct stat st;
    return stat(path, &st) == 0 && st.st_size > 0;
}

Test(validate, each_problem_at_quick_writes_csv_png_pdf_and_a_verdict, .timeout = 300)
{
    /* drop-3d is left out for time (35 CPU s at --quick); it shares drop's code, cost line included */
    static const char *const names[] = {"dam-break", "hydrostatic", "taylor-green", "poiseuille",
                                        "couette",   "obstacle",    "drop"};
    char dir[] = "/tmp/sphlab-validate-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    for (size_t k = 0; k < sizeof names / sizeof names[0]; k++) {
        char args[600], out[16384], want[64];
        snprintf(args, sizeof args, "validate %s --quick --quiet --threads 2 --out %s", names[k], dir);
        int rc = test_sphlab(args, out, sizeof out);
        cr_assert(rc == 0 || rc == 1, "%s: exit %d (want 0 pass or 1 fail): %s", names[k], rc, out);
        snprintf(want, sizeof want, "validate %s: %s: ", names[k], rc == 0 ? "PASS" : "FAIL");
        cr_assert(strstr(out, want) && strstr(out, "target"), "%s: no verdict line with its target: %s", names[k], out);
        cr_assert(nonempty(dir, names[k], "csv") && nonempty(dir, names[k], "png") && nonempty(dir, names[k], "pdf"),
                  "%s: CSV, PNG or PDF missing in %s", names[k], dir);
        /* what it cost: a line below the verdict and NAME-cost.csv, one row per run, time per simulated second > 0 */
        snprintf(want, sizeof want, "validate %s: cost (this machine, load ", names[k]);
        cr_expect(strstr(out, want) && strstr(out, "ms per simulated s"), "%s: no cost line: %s", names[k], out);
        char path[700], text[4096] = "";
        snprintf(path, sizeof path, "%s/%s-cost.csv", dir, names[k]);
        FILE *f = fopen(path, "r");
        cr_assert_not_null(f, "%s missing", path);
        size_t len = fread(text, 1, sizeof text - 1, f);
        fclose(f);
        text[len] = '\0';
        cr_expect(strncmp(text, "run,particles,fluid_particles,steps,t_sim,wall_s,cpu_s,ms_per_sim_s,error\n", 73) == 0,
                  "%s: header: %s", path, text);
        const char *row = strchr(text, '\n');
        cr_assert(row && row[1] == '"', "%s: no run row: %s", path, text);
        /* the 8th field of the first row: ms per simulated second */
        const char *q = strchr(row + 2, '"');
        for (int c = 0; q && c < 7; c++) q = strchr(q + 1, ',');
        cr_expect(q && strtod(q + 1, NULL) > 0, "%s: ms_per_sim_s not positive: %s", path, text);
    }
}

/* The hydrostatic line says where its worst figures sit (issue 13: which row,
 * which frame, bias or noise, and where the fastest particle is), so that a
 * miss can be read from the line: at --quick (H/spacing 8, frames from 1 s
 * to 1.2 s) the row lies in the column, the frame in the window, and the
 * fastest particle in the tank. */
Test(validate, hydrostatic_line_says_where_the_worst_figures_sit, .timeout = 120)
{
    char dir[] = "/tmp/sphlab-validate-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char args[600], out[16384];
    snprintf(args, sizeof args, "validate hydrostatic --quick --quiet --threads 2 --out %s", dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert(rc == 0 || rc == 1, "exit %d: %s", rc, out);
    const char *at = strstr(out, "R=8 p ");
    cr_assert_not_null(at, "%s", out);
    int row;
    double p, yh, t, bias, spread, inc, speed, wall, fy;
    int got = sscanf(at,
                     "R=8 p %lf%% (row %d from the floor, y/H %lf, t %lf s; rows' bias up to %lf%%, spread between "
                     "frames up to %lf%%; against rho0 g (H - y): %lf%%) speed %lf%% (%lf spacings from a side wall, "
                     "y/H %lf)",
                     &p, &row, &yh, &t, &bias, &spread, &inc, &speed, &wall, &fy);
    cr_assert_eq(got, 10, "parsed %d fields of: %s", got, at);
    cr_log_info("quick hydrostatic: worst %.2f %% in row %d (y/H %.2f) at t = %.2f s, bias %.2f %%, spread %.2f %%; "
                "fastest %.1f spacings from a side wall at y/H %.2f",
                p, row, yh, t, bias, spread, wall, fy);
    cr_assert(row >= 1 && row <= 9 && yh > 0 && yh < 1.1, "row %d, y/H %g", row, yh);
    cr_assert(t >= 1.0 - 1e-6 && t <= 1.2 + 1e-3, "t %g", t);
    /* the worst single particle is at least the worst row's mean over the frames */
    cr_assert(bias <= p + 0.01 && spread >= 0, "bias %g, spread %g, worst %g", bias, spread, p);
    cr_assert(wall >= 0 && wall <= 4 && fy >= 0 && fy < 1.1, "fastest at %g spacings, y/H %g", wall, fy);
}

/* The channels at steady state (issue 13): validate poiseuille and couette at 10 particles across, run to
 * t = L^2/nu (not --quick, whose samples stop in the start-up and so skip the steady-state target), stay
 * within 1.2 % of the scale at every sample (docs/accuracy.md, "poiseuille and couette"). Measured: Poiseuille
 * 0.4 0.3 0.5 0.6 1.0 %, Couette 1.0 0.6 0.4 0.2 0.1 %. The wall seen in the step's frame without the no-slip
 * mirror's curvature term gave 2.6 % at steady state, the term without the step's frame 1.6 % (slow by
 * g dt); neither (the two errors cancelling) 0.3 %. */
Test(validate, channels_at_steady_state_keep_the_documented_band, .timeout = 120)
{
    static const char *const names[] = {"poiseuille", "couette"};
    char dir[] = "/tmp/sphlab-validate-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    for (int k = 0; k < 2; k++) {
        char args[600], out[16384], want[64];
        snprintf(args, sizeof args, "validate %s --resolution 10 --quiet --threads 2 --out %s", names[k], dir);
        int rc = test_sphlab(args, out, sizeof out);
        snprintf(want, sizeof want, "R=10:");
        const char *at = strstr(out, want);
        cr_assert_not_null(at, "%s: %s", names[k], out);
        double e[5];
        int got = sscanf(at, "R=10: %lf%% %lf%% %lf%% %lf%% %lf%%", &e[0], &e[1], &e[2], &e[3], &e[4]);
        cr_assert_eq(got, 5, "%s: parsed %d of: %s", names[k], got, at);
        cr_log_info("%s R=10: %.1f %.1f %.1f %.1f %.1f %%", names[k], e[0], e[1], e[2], e[3], e[4]);
        cr_expect_eq(rc, 0, "%s: exit %d: %s", names[k], rc, out);
        for (int s = 0; s < 5; s++) cr_expect_leq(e[s], 1.2, "%s: sample %d: %.1f %%", names[k], s, e[s]);
    }
}

/* The channel's centre excess (issue 13): with the density summed, the steady Poiseuille profile ran fast by
 * about 0.9 % of u_max at every resolution (0.92 % at the centre at 20 across). The Morris Laplacian reads the
 * neighbours' volume as m / rho, and the Wendland sum over the lattice at h = 3 spacings is 1.0051 rho0, so the
 * viscous term was 0.5 % weak on top of its own lattice moment (0.9966: 0.34 %); the profile scales as 1 / nu
 * (docs/accuracy.md, "poiseuille and couette"). With the density carried from m / spacing^2 (the scenes'
 * density_method = continuity) only the moment is left: 0.40 % at the centre at 20 across. Read from the CSV at
 * t = L^2/nu, every row within 0.6 % of u_max and the centre still fast (the moment's sign). */
Test(validate, poiseuille_steady_profile_within_the_laplacians_lattice_moment, .timeout = 120)
{
    char dir[] = "/tmp/sphlab-validate-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char args[600], out[16384], path[700], line[256];
    snprintf(args, sizeof args, "validate poiseuille --resolution 20 --quiet --threads 2 --out %s", dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_assert_eq(rc, 0, "exit %d: %s", rc, out);
    snprintf(path, sizeof path, "%s/poiseuille.csv", dir);
    FILE *f = fopen(path, "r");
    cr_assert_not_null(f, "%s missing", path);
    const double umax = 0.2 / (8 * 1.0); /* [m/s] F L^2 / 8 nu of scenes/validate/poiseuille.ini */
    double worst = 0, centre = 0;
    int rows = 0;
    while (fgets(line, sizeof line, f)) {
        int res;
        double t, y, u, ue;
        if (sscanf(line, "%d,%lf,%lf,%lf,%lf", &res, &t, &y, &u, &ue) != 5 || fabs(t - 1.0) > 1e-6) continue;
        rows++;
        worst = fmax(worst, fabs(u - ue) / umax);
        if (fabs(y - 0.475) < 1e-3) centre = (u - ue) / umax;
    }
    fclose(f);
    cr_log_info("poiseuille R=20, t = 1 s: worst row %.3f %%, centre %+.3f %% of u_max", 100 * worst, 100 * centre);
    cr_assert_eq(rows, 20, "rows at t = 1 s: %d", rows);
    cr_expect_leq(worst, 0.006, "worst row %.3f %% of u_max", 100 * worst);
    cr_expect(centre > 0, "centre %+.3f %%: the Laplacian's lattice moment (0.9966) makes it fast", 100 * centre);
}

/* validate hydrostatic --quick (H/spacing 8): its pressure is not judged (issue 13). The pressure target is
 * claimed at the default resolutions, H/spacing >= 20; below, the row under the free surface is off by about
 * 0.08 rho0 g s (1.05 / 0.58 / 0.39 % of rho0 g H at 8 / 12 / 16 spacings, converging), so the quick run used to
 * FAIL on a figure the target never claimed. The quick line says so, and its verdict is the speed's. */
Test(validate, hydrostatic_quick_pressure_is_not_judged_below_20, .timeout = 120)
{
    char dir[] = "/tmp/sphlab-validate-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    char args[600], out[16384];
    snprintf(args, sizeof args, "validate hydrostatic --quick --quiet --threads 2 --out %s", dir);
    int rc = test_sphlab(args, out, sizeof out);
    cr_expect_eq(rc, 0, "exit %d: %s", rc, out);
    cr_expect(strstr(out, "validate hydrostatic: PASS: "), "%s", out);
    cr_expect(strstr(out, "R=8 p ") && strstr(out, "pressure not judged below H/spacing = 20"), "%s", out);
}

Test(validate, bad_input_is_refused_with_exit_2)
{
    char out[8192];
    cr_assert_eq(test_sphlab("validate nosuch", out, sizeof out), 2);
    cr_assert(strstr(out, "unknown problem 'nosuch'") && strstr(out, "dam-break"), "%s", out);
    cr_assert_eq(test_sphlab("validate taylor-green --resolution 20,,40", out, sizeof out), 2);
    cr_assert(strstr(out, "--resolution '20,,40'"), "%s", out);
    cr_assert_eq(test_sphlab("validate taylor-green --resolution 3", out, sizeof out), 2);
    cr_assert(strstr(out, "out of range") && strstr(out, "particles per side"), "%s", out);
    cr_assert_eq(test_sphlab("validate", out, sizeof out), 2);
    cr_assert(strstr(out, "name a problem"), "%s", out);
    cr_assert_eq(test_sphlab("validate list", out, sizeof out), 0);
    cr_assert(strstr(out, "couette") && strstr(out, "obstacle"), "%s", out);
}

/* Every resolution --resolution accepts makes a scene that runs: the smallest gave a refused scene (the
 * periodic domain shorter than 3 h) with exit 3 for couette and poiseuille at 4 to 7 and taylor-green at 8
 * to 12 (a user's review); one below it is refused as out of range. */
Test(validate, smallest_accepted_resolution_runs, .timeout = 600)
{
    static char out[8192];
    static const char *const names[] = {"dam-break", "hydrostatic", "taylor-green", "poiseuille",
                                        "couette",   "drop",        "drop-3d",      "obstacle"};
    const char *dir = test_temp_dir("valmin");
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        /* the range as the refusal of --resolution 0 states it */
        char args[512];
        snprintf(args, sizeof args, "validate %s --resolution 0", names[i]);
        cr_assert_eq(test_sphlab(args, out, sizeof out), 2, "%s: %s", args, out);
        const char *acc = strstr(out, "accepted: ");
        int lo = 0;
        cr_assert(acc && sscanf(acc, "accepted: %d to", &lo) == 1 && lo > 1, "%s: %s", args, out);
        snprintf(args, sizeof args, "validate %s --resolution %d --quick --quiet --out %s", names[i], lo, dir);
        int rc = test_sphlab(args, out, sizeof out);
        cr_expect(rc == 0 || rc == 1, "%s: exit %d, want a verdict: %s", args, rc, out);
    }
    test_remove_dir(dir);
}

/* The drop's verdict names a period it could not measure (a record that crossed its mean fewer than 3 times:
 * R/20's growing mode) in words, not as "period nan s (+nan%)". */
Test(validate, drop_period_text_says_when_there_is_no_period)
{
    char buf[256];
    val_period_text(buf, sizeof buf, 2.581, 2.409, 6);
    cr_expect_str_eq(buf, "period 2.581 s (from the first 4 of its 5 half periods: whole periods only) vs Rayleigh "
                          "2.409 s (+7.1%)");
    /* a user averaged the three half periods listed beside 2.478 s (1.09, 1.39, 0.975 s: 2.30 s) and found -4.4 %
     * where the line said +2.9 %: the period was read from the first two alone, unsaid */
    val_period_text(buf, sizeof buf, 2.478, 2.409, 4);
    cr_expect(strstr(buf, "the first 2 of its 3 half periods"), "%s", buf);
    val_period_text(buf, sizeof buf, 2.5, 2.409, 5);
    cr_expect(strstr(buf, "from its 4 half periods"), "%s", buf);
    val_period_text(buf, sizeof buf, NAN, 2.409, 2);
    cr_expect(strstr(buf, "no period") && strstr(buf, "2 crossings") && strstr(buf, "3 needed") &&
                  strstr(buf, "Rayleigh 2.409 s"),
              "%s", buf);
    cr_expect_null(strstr(buf, "nan"), "%s", buf);
    val_period_text(buf, sizeof buf, 2.5, NAN, 6);
    cr_expect_null(strstr(buf, "nan"), "%s", buf);
}

/* Each verdict line names what its percentages are of, with the figure, and its target's quantities: the
 * channels said "/ scale" (of what?) and the hydrostatic target "<= 1 %, < 1 %" (of which quantity?). */
Test(validate, verdicts_name_the_scale_of_their_percentages, .timeout = 120)
{
    static const char *const names[] = {"poiseuille", "couette", "hydrostatic"};
    static const char *const want[][2] = {
        {"/ u_max (", "m/s"}, {"/ U (", "m/s"}, {"p <= 1 % of rho0 g H", "sqrt(g H)"}};
    char dir[] = "/tmp/sphlab-validate-XXXXXX";
    cr_assert_not_null(mkdtemp(dir));
    for (int k = 0; k < 3; k++) {
        char args[600], out[16384];
        snprintf(args, sizeof args, "validate %s --quick --quiet --threads 2 --out %s", names[k], dir);
        int rc = test_sphlab(args, out, sizeof out);
        cr_assert(rc == 0 || rc == 1, "%s: exit %d: %s", names[k], rc, out);
        cr_expect(strstr(out, want[k][0]) && strstr(out, want[k][1]), "%s: want '%s' and '%s' in: %s", names[k],
                  want[k][0], want[k][1], out);
    }
}

/* Into a file or a pipe (a log, CI) the progress is whole lines, not a line rewritten with carriage returns (a
 * user's review: a log of `validate dam-break` held one line of thousands of "\r" updates). */
Test(validate, progress_into_a_pipe_has_no_carriage_returns, .timeout = 120)
{
    const char *dir = test_temp_dir("valpipe");
    char args[512], out[16384];
    snprintf(args, sizeof args, "validate couette --quick --out %s", dir);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    cr_assert(strstr(out, "done: "), "no progress at all: %s", out);
    cr_assert_null(strchr(out, '\r'), "a carriage return in: %s", out);
    test_remove_dir(dir);
}
