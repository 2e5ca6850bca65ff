/* Boundary particles ([domain] wall_model = particles; src/core/sph_wall_particles.c
 * and the wall_state pass): the generalized wall boundary condition of
 * Adami, Hu & Adams 2012 (J. Comput. Phys. 231, 7057-7075), eq. 27-28.
 * The layers fill a corner particle's support; the first row of a lattice
 * block reads the interior's density; a box full of fluid stays at rest; a
 * hydrostatic tank's pressure follows rho g (H - y) down to the wall row;
 * plane Poiseuille flow follows the series solution of Morris, Fox & Zhu
 * 1997 (J. Comput. Phys. 136, 214-226, eq. 21) with no-slip walls, and is a
 * plug flow with free-slip ones. The figures measured are in
 * docs/accuracy.md. */
#include <criterion/criterion.h>
#include <criterion/logging.h>
#include <math.h>
#include <stdio.h>

#include "sph_walls.h"
#include "test_util.h"

static const double PI = 3.14159265358979323846;

/* A 2D tank 0.4 m x 0.5 m, water 0.3 m deep on a 0.01 m lattice, h = 2 spacings. */
static void tank_ini(char *ini, size_t n, const char *model, const char *kernel, double depth, const char *effects)
{
    snprintf(ini, n,
             "[scene]\ndimension=2\neffects=%s\n[domain]\nmin=0 0\nmax=0.4 0.5\nwall_model=%s\n"
             "[fluid water]\nmin=0 0\nmax=0.4 %g\nspacing=0.01\n[physics]\nstiffness=400\nviscosity=0.05\n"
             "viscosity_form=morris\n[kernels]\nh=0.02\ndensity=%s\npressure=%s\nviscosity=%s\n[time]\ncfl=0.25\n"
             "dt=0.001\n",
             effects, model, depth, kernel, kernel, kernel);
}

/* Runs passes until the given one has run (within the current step). */
static void run_through(sph_sim *sim, sph_pass_id last)
{
    for (int guard = 0; guard < 2 * SPH_PASS_COUNT; guard++)
        if (sph_sim_step_pass(sim) == last) return;
    cr_assert_fail("pass %s never ran", sph_passes[last]->name);
}

static uint32_t close_neighbours(const sph_sim *sim, uint32_t i)
{
    uint32_t count = 0;
    const float r = 0.95f * sim->def.h;
    for (uint32_t e = sim->S.nbr_start[i]; e < sim->S.nbr_start[i + 1]; e++) {
        uint32_t j = sim->S.nbr[e];
        float dx = sim->P.pred[0][i] - sim->P.pred[0][j], dy = sim->P.pred[1][i] - sim->P.pred[1][j];
        count += dx * dx + dy * dy < r * r;
    }
    return count;
}

Test(wall_particles, layers_fill_the_support_and_stay_put)
{
    char ini[1024];
    tank_ini(ini, sizeof ini, "particles", "cubic", 0.3, "gravity pressure viscosity walls");
    sph_sim *sim = test_sim(ini, 2);
    const uint32_t n_fluid = 40 * 30;
    /* ceil(h / s) = 2 layers round a 40 x 50 box, corners included */
    cr_assert_eq(sim->n, n_fluid + (40 + 4) * (50 + 4) - 40 * 50);
    float x0[2][1000];
    uint32_t n_wall = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        bool wall = sph_is_wall(&sim->P, i);
        cr_assert_eq(wall, sim->P.id[i] >= n_fluid, "particle %u: walls come after the fluid", i);
        if (!wall) continue;
        float x = sim->P.pos[0][i], y = sim->P.pos[1][i];
        cr_assert(x < 0 || x > 0.4f || y < 0 || y > 0.5f, "wall particle %u at (%g, %g) is inside the box", i, x, y);
        /* on the fluid's lattice continued: nodes at (k + 1/2) s */
        cr_assert_float_eq(fmodf(x + 1.0f, 0.01f), 0.005f, 1e-4f, "x = %g", x);
        x0[0][sim->P.id[i] - n_fluid] = x;
        x0[1][sim->P.id[i] - n_fluid] = y;
        n_wall++;
    }
    cr_assert_eq(n_wall, sim->n - n_fluid);
    run_through(sim, SPH_PASS_NEIGHBOURS);
    /* a fluid particle in the corner has as many neighbours as one inside
     * (counted within 0.95 h: whether a node at exactly h is listed depends
     * on rounding) */
    int corner = -1, inside = -1;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (sph_is_wall(&sim->P, i)) continue;
        if (sim->P.id[i] == 0) corner = (int)i;              /* (0.005, 0.005) */
        if (sim->P.id[i] == 10 * 40 + 20) inside = (int)i;  /* (0.205, 0.105) */
    }
    cr_assert(corner >= 0 && inside >= 0);
    uint32_t nc = close_neighbours(sim, (uint32_t)corner), ni = close_neighbours(sim, (uint32_t)inside);
    cr_assert_eq(ni, 8);
    cr_assert_eq(nc, ni, "corner particle: %u neighbours, inside: %u", nc, ni);
    /* under gravity, pressure and viscosity, the walls neither move nor reorder away from their marks */
    for (int s = 0; s < 100; s++) sph_sim_step(sim);
    cr_assert(!sim->alarm.raised);
    for (uint32_t i = 0; i < sim->n; i++) {
        if (!sph_is_wall(&sim->P, i)) continue;
        cr_assert_geq(sim->P.id[i], n_fluid);
        uint32_t k = sim->P.id[i] - n_fluid;
        cr_assert(sim->P.pos[0][i] == x0[0][k] && sim->P.pos[1][i] == x0[1][k], "wall particle %u moved", k);
        cr_assert(sim->P.vel[0][i] == 0.0f && sim->P.vel[1][i] == 0.0f);
        cr_assert(sim->P.acc_p[1][i] == 0.0f && sim->P.acc_v[1][i] == 0.0f);
    }
    sph_sim_destroy(sim);
}

/* Mean density of the row next to the floor, and of the interior (3 h away
 * from every wall and from the surface), after the first density pass. */
static void first_row_density(const char *model, const char *kernel, double *row, double *inner)
{
    char ini[1024];
    tank_ini(ini, sizeof ini, model, kernel, 0.3, "gravity pressure viscosity walls");
    sph_sim *sim = test_sim(ini, 2);
    run_through(sim, SPH_PASS_DENSITY);
    double sr = 0, si = 0;
    int nr = 0, ni = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        if (sph_is_wall(&sim->P, i)) continue;
        float x = sim->P.pos[0][i], y = sim->P.pos[1][i];
        if (x < 0.06f || x > 0.34f) continue;
        if (y < 0.01f) {
            sr += sim->P.rho[i];
            nr++;
        } else if (y > 0.06f && y < 0.24f) {
            si += sim->P.rho[i];
            ni++;
        }
    }
    *row = sr / nr;
    *inner = si / ni;
    sph_sim_destroy(sim);
}

Test(wall_particles, first_row_reads_the_interior_density)
{
    const char *kernels[] = {"poly6", "cubic", "wendland"};
    for (int k = 0; k < 3; k++) {
        double row, inner, vrow, vinner;
        first_row_density("particles", kernels[k], &row, &inner);
        first_row_density("volume", kernels[k], &vrow, &vinner);
        cr_log_info("%s, h = 2 spacings: first row / interior = %.4f with wall particles, %.4f with the volume model",
                    kernels[k], row / inner, vrow / vinner);
        /* issue 13's target: within 0.5 % */
        cr_assert(fabs(row / inner - 1.0) < 0.005, "%s: first row %.2f, interior %.2f", kernels[k], row, inner);
    }
}

/* A box full of fluid, no gravity: every particle has a full support, and
 * the walls' extrapolated pressure balances the fluid's. Nothing may move. */
Test(wall_particles, full_box_without_gravity_stays_at_rest)
{
    sph_sim *sim = test_sim("[scene]\ndimension=2\neffects=pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.2 0.2\n"
                            "wall_model=particles\n[fluid a]\nmin=0 0\nmax=0.2 0.2\nspacing=0.01\n[physics]\n"
                            "stiffness=400\nviscosity_form=morris\n[kernels]\nh=0.02\ndensity=cubic\npressure=cubic\n"
                            "viscosity=cubic\n[time]\ncfl=0.25\n",
                            2);
    for (int s = 0; s < 300; s++) sph_sim_step(sim);
    sph_stats st;
    sph_sim_stats(sim, &st);
    cr_assert(!sim->alarm.raised);
    cr_assert_eq(st.n, sim->n);
    cr_log_info("full box at rest, 300 steps: max speed %.3g m/s (c = 20 m/s)", st.max_speed);
    cr_assert_lt(st.max_speed, 1e-4, "max speed %g m/s", st.max_speed);
    sph_sim_destroy(sim);
}

/* During gravity_ramp the wall particles' hydrostatic term uses the gravity
 * the fluid feels (Adami et al. 2012's eq. 27 with the ramped g): at the
 * start of a 10 s ramp that is about none, so the wall pressures must be
 * those of the same tank without gravity. With the full g there (the old
 * code) the floor's wall particles read rho0 g times their depth below the
 * fluid more: about 100 to 200 Pa. */
Test(wall_particles, wall_pressure_follows_the_gravity_ramp)
{
    char ini_g[1024], ini_0[1024], ramp[1100];
    tank_ini(ini_g, sizeof ini_g, "particles", "cubic", 0.3, "gravity pressure viscosity walls");
    tank_ini(ini_0, sizeof ini_0, "particles", "cubic", 0.3, "pressure viscosity walls");
    snprintf(ramp, sizeof ramp, "%s[physics]\ngravity_ramp=10\n", ini_g);
    sph_sim *g = test_sim(ramp, 1), *z = test_sim(ini_0, 1);
    for (int s = 0; s < 3; s++) sph_sim_step(g), sph_sim_step(z);
    cr_assert_eq(g->n, z->n);
    /* the ramp's share after 3 steps of 1 ms: (1 - cos(pi 3e-3 / 10)) / 2 ~ 2e-7 */
    double worst = 0, pmax = 0;
    for (uint32_t i = 0; i < g->n; i++) {
        if (!sph_is_wall(&g->P, i)) continue;
        uint32_t j = UINT32_MAX; /* the same wall particle in the other run (reorder may move it) */
        for (uint32_t k = 0; k < z->n && j == UINT32_MAX; k++)
            if (z->P.id[k] == g->P.id[i]) j = k;
        cr_assert_neq(j, UINT32_MAX);
        worst = fmax(worst, fabs((double)g->P.p[i] - z->P.p[j]));
        pmax = fmax(pmax, g->P.p[i]);
    }
    cr_log_info("gravity ramp of 10 s, step 3: wall pressure differs from the no-gravity tank by %.3g Pa at most "
                "(largest wall pressure %.3g Pa)", worst, pmax);
    cr_assert_lt(worst, 1.0, "wall pressure off by %g Pa from the tank without gravity", worst);
    sph_sim_destroy(g);
    sph_sim_destroy(z);
}

/* Hydrostatic tank: after 1.3 s of settling, in every frame sampled over the
 * next 0.2 s, the pressure of the two columns nearest the centre line
 * against rho0 g (H - y), H the surface (the highest particle + s/2). */
Test(wall_particles, hydrostatic_tank_pressure_down_to_the_wall_row, .timeout = 120)
{
    char ini[1024];
    tank_ini(ini, sizeof ini, "particles", "cubic", 0.3, "gravity pressure viscosity walls");
    sph_sim *sim = test_sim(ini, 2);
    const double s = 0.01, H0 = 0.3, rg = 1000.0 * 9.81;
    double worst = 0, worst_row = 0, worst_mean = 0, worst_speed = 0;
    int frames = 0;
    while (sim->t < 1.5 && !sim->alarm.raised) {
        sph_sim_step(sim);
        if (sim->t < 1.3 || sim->step % 50) continue;
        const sph_particles *P = &sim->P;
        double top = 0, bottom = 1;
        for (uint32_t i = 0; i < sim->n; i++)
            if (!sph_is_wall(P, i)) {
                top = fmax(top, P->pos[1][i]);
                if (fabs(P->pos[0][i] - 0.2) < s) bottom = fmin(bottom, P->pos[1][i]);
            }
        double sum = 0, row = 0, all = 0;
        int cnt = 0;
        for (uint32_t i = 0; i < sim->n; i++) {
            if (sph_is_wall(P, i) || fabs(P->pos[0][i] - 0.2) >= s) continue;
            double y = P->pos[1][i], e = fabs(P->p[i] - rg * (top + 0.5 * s - y)) / (rg * H0);
            all = fmax(all, e);
            if (y < bottom + 0.5 * s) row = fmax(row, e);
            sum += e;
            cnt++;
        }
        sph_stats st;
        sph_sim_stats(sim, &st);
        worst = fmax(worst, all);
        worst_row = fmax(worst_row, row);
        worst_mean = fmax(worst_mean, sum / cnt);
        worst_speed = fmax(worst_speed, st.max_speed);
        frames++;
    }
    cr_assert(!sim->alarm.raised);
    cr_assert_geq(frames, 10);
    const double sqrt_gH = sqrt(9.81 * H0);
    cr_log_info("hydrostatic tank, %d frames in 1.3-1.5 s: |p - rho g (H - y)| / rho g H: worst %.4f, wall row %.4f, "
                "column mean %.4f; max speed %.4f sqrt(gH)",
                frames, worst, worst_row, worst_mean, worst_speed / sqrt_gH);
    /* measured: 0.031, 0.018, 0.019 and 0.0022 sqrt(gH) (issue 13's target of
     * 1 % is not met: see docs/accuracy.md); the volume model's wall row is
     * about +100 % */
    cr_assert_lt(worst_row, 0.04, "wall row %.4f", worst_row);
    cr_assert_lt(worst, 0.06, "worst %.4f", worst);
    cr_assert_lt(worst_mean, 0.035, "mean %.4f", worst_mean);
    cr_assert_lt(worst_speed, 0.01 * sqrt_gH, "max speed %g m/s", worst_speed);
    sph_sim_destroy(sim);
}

/* Start-up plane Poiseuille flow (Morris, Fox & Zhu 1997, eq. 21, with the
 * sign of the velocity along the force): plates at y = 0 and L, body force
 * F along x, nu = 1e-6 m^2/s, L = 1 mm, F = 2e-4 m/s^2 (their case),
 * u_max = F L^2 / (8 nu) = 2.5e-5 m/s. */
static double poiseuille(double y, double t, double F, double nu, double L)
{
    double u = F / (2 * nu) * y * (L - y);
    for (int n = 0; n < 100; n++) {
        double m = 2 * n + 1;
        u -= 4 * F * L * L / (nu * PI * PI * PI * m * m * m) * sin(PI * y * m / L) * exp(-m * m * PI * PI * nu * t / (L * L));
    }
    return u;
}

static sph_sim *channel(const char *slip)
{
    char ini[1024];
    const double L = 1e-3, s = L / 20;
    snprintf(ini, sizeof ini,
             "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=%g %g\n"
             "periodic=x\nwall_model=particles\nwall_slip=%s\n[fluid a]\nmin=0 0\nmax=%g %g\nspacing=%g\n"
             "[physics]\nstiffness=4e-4\nviscosity=1e-6\nviscosity_form=morris\ngravity=2e-4 0\n"
             "[kernels]\nh=%g\ndensity=cubic\npressure=cubic\nviscosity=cubic\n[time]\ncfl=0.25\ndt=0.01\n",
             12 * s, L, slip, 12 * s, L, s, 2 * s);
    return test_sim(ini, 2);
}

/* Worst |u - series| / u_max over all particles at time t. */
static double poiseuille_error(const sph_sim *sim)
{
    const double F = 2e-4, nu = 1e-6, L = 1e-3, umax = F * L * L / (8 * nu);
    double worst = 0;
    for (uint32_t i = 0; i < sim->n; i++)
        if (!sph_is_wall(&sim->P, i))
            worst = fmax(worst, fabs(sim->P.vel[0][i] - poiseuille(sim->P.pos[1][i], sim->t, F, nu, L)) / umax);
    return worst;
}

Test(wall_particles, poiseuille_no_slip_follows_the_series_solution)
{
    sph_sim *sim = channel("no");
    const double at[] = {0.1, 0.3, 2.0}; /* start-up (the series' e-folding time is 0.1 s), then steady */
    for (int k = 0; k < 3; k++) {
        while (sim->t < at[k] && !sim->alarm.raised) sph_sim_step(sim);
        cr_assert(!sim->alarm.raised);
        double e = poiseuille_error(sim);
        cr_log_info("Poiseuille, no-slip, 20 rows, t = %.3f s: worst |u - series| = %.4f u_max", sim->t, e);
        /* measured 0.0039, 0.0097, 0.0092 */
        cr_assert_lt(e, 0.02, "t = %g s: %.4f u_max", sim->t, e);
    }
    sph_sim_destroy(sim);
}

/* Free-slip walls exert no shear: the force accelerates the whole channel
 * alike, u = F t everywhere (a plug), where no-slip walls hold the wall row
 * back to a tenth of the centre's speed. (Measured at t = 0.3 s: free-slip
 * u within 0.8 % across the channel, its mean 1 % above F t, as the
 * extrapolation's g . r_wf term, written for a fluid at rest relative to the
 * wall, adds a small pressure gradient along the flow.) */
Test(wall_particles, poiseuille_free_slip_is_plug_flow)
{
    const char *slips[] = {"free", "no"};
    for (int k = 0; k < 2; k++) {
        sph_sim *sim = channel(slips[k]);
        while (sim->t < 0.3 && !sim->alarm.raised) sph_sim_step(sim);
        cr_assert(!sim->alarm.raised);
        double umin = INFINITY, umax = 0;
        for (uint32_t i = 0; i < sim->n; i++)
            if (!sph_is_wall(&sim->P, i)) {
                umin = fmin(umin, sim->P.vel[0][i]);
                umax = fmax(umax, sim->P.vel[0][i]);
            }
        double plug = 2e-4 * sim->t;
        cr_log_info("channel, %s-slip, t = %.3f s: u from %.4g to %.4g m/s (F t = %.4g)", slips[k], sim->t, umin, umax,
                    plug);
        if (k == 0) {
            cr_assert_lt((umax - umin) / umax, 0.02, "free-slip: u from %g to %g m/s, not a plug", umin, umax);
            cr_assert_lt(fabs(0.5 * (umin + umax) / plug - 1), 0.03, "u about %g m/s, F t = %g", umax, plug);
        } else {
            cr_assert_lt(umin, 0.15 * umax, "no-slip: the wall row moves at %g of the centre", umin / umax);
        }
        sph_sim_destroy(sim);
    }
}

/* Wall particles lie outside the box, where the dense grid clamps them into
 * its edge cells: hash, grid and brute force must still list the same
 * neighbours for every particle. */
Test(wall_particles, every_search_finds_the_wall_particles)
{
    const char *methods[] = {"hash", "grid", "brute"};
    uint32_t counts[3][1600];
    uint32_t n = 0;
    for (int m = 0; m < 3; m++) {
        char ini[1024], set[64];
        tank_ini(ini, sizeof ini, "particles", "cubic", 0.3, "gravity pressure viscosity walls");
        snprintf(set, sizeof set, "search.method=%s", methods[m]);
        sph_scene_def def = test_scene(ini);
        sph_error err;
        cr_assert_eq(sph_scene_set(&def, set, &err), SPH_ERR_OK, "%s", err.msg);
        sph_sim *sim;
        cr_assert_eq(sph_sim_create(&def, 2, &sim, &err), SPH_ERR_OK, "%s", err.msg);
        n = sim->n;
        cr_assert_leq(n, 1600);
        run_through(sim, SPH_PASS_NEIGHBOURS); /* the first step's lists: every method sees the same positions */
        for (uint32_t i = 0; i < n; i++) counts[m][sim->P.id[i]] = sim->S.nbr_start[i + 1] - sim->S.nbr_start[i];
        sph_sim_destroy(sim);
    }
    for (uint32_t id = 0; id < n; id++)
        for (int m = 1; m < 3; m++)
            cr_assert_eq(counts[m][id], counts[0][id], "particle %u: %u neighbours by %s, %u by hash", id,
                         counts[m][id], methods[m], counts[0][id]);
}

/* Switching no-slip to free-slip live keeps the particles, and each keeps its
 * mark (the reorder pass has moved them; the flag is state, carried over). */
Test(wall_particles, reconfigure_keeps_the_wall_marks)
{
    char ini[1024];
    tank_ini(ini, sizeof ini, "particles", "cubic", 0.3, "gravity pressure viscosity walls");
    sph_sim *sim = test_sim(ini, 2);
    for (int s = 0; s < 10; s++) sph_sim_step(sim);
    sph_scene_def def = sim->def;
    sph_error err;
    cr_assert_eq(sph_scene_set(&def, "domain.wall_slip=free", &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert_eq(sph_sim_reconfigure(sim, &def, &err), SPH_ERR_OK, "%s", err.msg);
    for (int s = 0; s < 10; s++) sph_sim_step(sim);
    cr_assert(!sim->alarm.raised);
    for (uint32_t i = 0; i < sim->n; i++)
        cr_assert_eq(sph_is_wall(&sim->P, i), sim->P.id[i] >= 1200, "particle %u (id %u)", i, sim->P.id[i]);
    /* another wall model makes other particles: refused */
    cr_assert_eq(sph_scene_set(&def, "domain.wall_model=volume", &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert_neq(sph_sim_reconfigure(sim, &def, &err), SPH_ERR_OK);
    sph_sim_destroy(sim);
}

/* A column at rest stays at rest: the tank of `sphlab validate hydrostatic`
 * (water 0.3 m deep, 0.3 m wide, 20 rows, continuity with Molteni's
 * diffusion, 0.3 s gravity ramp), whose largest fluid speed after t = 1 s
 * must stay below 1e-3 sqrt(g H). The external pass adds g dt to the fluid's
 * velocity before the forces, and the pressure force takes it back from a
 * fluid at rest; the rates that compare the fluid with the wall particles
 * (continuity, the no-slip mirror of wall_state) must see the wall in the
 * same frame. Compared with the wall at rest (the old code), the column
 * read as flowing into the floor at g dt: the rows next to the side walls
 * were dragged up by the mirror and the tank turned over, 2.8e-3 sqrt(g H). */
Test(wall_particles, column_at_rest_stays_at_rest, .timeout = 120)
{
    const char *ini = "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n"
                      "[domain]\nmin=0 0\nmax=0.3 0.5\nwall_model=particles\nwall_slip=no\n"
                      "[fluid water]\nmin=0 0\nmax=0.3 0.3\nspacing=0.015\n"
                      "[physics]\nrest_density=1000\neos=linear\nstiffness=400\nnegative_pressure=clamp\n"
                      "viscosity_form=morris\n"
                      "viscosity=0.05\ngravity_ramp=0.3\n"
                      "density_method=continuity\ndelta=0.1\n"
                      "[kernels]\nh=0.03\ndensity=cubic\npressure=cubic\nviscosity=cubic\n[time]\ncfl=0.25\ndt=0.001\n";
    sph_sim *sim = test_sim(ini, 2);
    double worst = 0;
    while (sim->t < 1.2 && !sim->alarm.raised) {
        sph_sim_step(sim);
        if (sim->t < 1.0) continue;
        for (uint32_t i = 0; i < sim->n; i++) {
            if (sph_is_wall(&sim->P, i)) continue;
            worst = fmax(worst, hypot(sim->P.vel[0][i], sim->P.vel[1][i]));
        }
    }
    cr_assert(!sim->alarm.raised);
    const double scale = sqrt(9.81 * 0.3);
    cr_log_info("column at rest, 1 to 1.2 s: max speed %.3g m/s = %.3g sqrt(gH)", worst, worst / scale);
    cr_assert_lt(worst, 1e-3 * scale, "max speed %.3g sqrt(gH) after settling", worst / scale);
    sph_sim_destroy(sim);
}

/* The first step of a tank at rest: the external pass has kicked every fluid velocity by g dt, the same for
 * all, which the pressure force is about to take back. A rate comparing a fluid particle's velocity with a
 * wall particle's must see the wall in that frame, v_w + g dt (sph_wall_kick), as continuity's wall term and
 * the no-slip mirror do; else the floor row reads as approaching the floor at g dt. Monaghan's artificial
 * viscosity (alone and beside Morris's) then gave the floor row a push off the floor; XSPH leaves the walls
 * out, so it gives nothing here either way. The fluid-fluid pairs have equal velocities: every term is zero. */
Test(wall_particles, pair_terms_see_the_wall_in_the_steps_frame)
{
    const char *forms[] = {"artificial", "morris-artificial"};
    for (int f = 0; f < 2; f++) {
        char ini[1200];
        snprintf(ini, sizeof ini,
                 "[scene]\ndimension=2\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.4 0.5\n"
                 "wall_model=particles\n[fluid water]\nmin=0 0\nmax=0.4 0.1\nspacing=0.01\n[physics]\n"
                 "stiffness=400\nviscosity=0.05\nviscosity_form=%s\nalpha=0.1\nxsph=0.3\n[kernels]\nh=0.025\n"
                 "density=cubic\npressure=cubic\nviscosity=cubic\n[time]\ncfl=0.25\ndt=0.001\n",
                 forms[f]);
        sph_sim *sim = test_sim(ini, 1);
        run_through(sim, SPH_PASS_XSPH);
        cr_assert_gt(sim->dt, 0.0f);
        double worst_v = 0, worst_x = 0, kick = 9.81 * sim->dt;
        for (uint32_t i = 0; i < sim->n; i++) {
            if (sph_is_wall(&sim->P, i)) continue;
            cr_assert(fabs(sim->P.vel[1][i] + kick) < 1e-6 * kick, "fluid velocity %g, not -g dt", sim->P.vel[1][i]);
            worst_v = fmax(worst_v, hypot(sim->P.acc_v[0][i], sim->P.acc_v[1][i]));
            worst_x = fmax(worst_x, hypot(sim->P.acc_x[0][i], sim->P.acc_x[1][i]));
        }
        cr_log_info("%s, first step: largest viscous acceleration %.3g m/s^2, XSPH %.3g m/s^2 (g = 9.81)", forms[f],
                    worst_v, worst_x);
        /* rounding only: the viscous term of a wall pair was alpha c h_s g dt / (r^2 + ...) times the kernel */
        cr_assert_lt(worst_v, 1e-4, "%s: viscous acceleration %g m/s^2 in a column at rest", forms[f], worst_v);
        cr_assert_lt(worst_x, 1e-4, "XSPH acceleration %g m/s^2 in a column at rest", worst_x);
        sph_sim_destroy(sim);
    }
}
