/* validate drop: a drop without gravity, held by surface tension (the scene's
 * surface_tension = csf or stress at a stated sigma; akinci, whose sigma is measured),
 * oscillating in its fundamental mode, against Rayleigh's frequency
 * (scenes/validate/drop.ini, 2D: a liquid cylinder; drop-3d.ini: a sphere).
 *
 *   2D (Rayleigh 1879, Proc. R. Soc. Lond. 29:71, the cylinder's modes
 *       cos(n theta); Lamb, Hydrodynamics, 6th ed. 1932, art. 274-275):
 *                               omega^2 = (n^3 - n) sigma / (rho R^3),  n = 2
 *   3D (Rayleigh 1879; Lamb art. 275):
 *                               omega^2 = l (l - 1) (l + 2) sigma / (rho R^3),  l = 2
 *
 * Akinci's gamma is not a physical surface tension, so sigma is measured
 * first, from the Laplace pressure: each drop settles round (the scene's
 * damping_time), and the mean pressure within R/2 of its centre is taken
 * over the last fifth of the settling. The pressure inside is p_b + sigma/R
 * in 2D (2 sigma/R in 3D), where p_b, the pressure the bulk's cohesion
 * needs, does not depend on R; two drops, of radius R and about R/2, give
 * sigma = (p_1 - p_2) / (k (1/R_1 - 1/R_2)), k = 1 (2D) or 2 (3D). R is the
 * radius of the disc (sphere) of the drop's volume at rest density, N s^dim.
 *
 * The settled drop of radius R then gets the velocity of the n = 2 mode,
 * v = A (x, -y) in 2D (potential A r^2 cos(2 theta) / 2), v = A (2x, -y, -z)
 * in 3D (potential A r^2 P2(cos theta) about x), about its centre, with A such
 * that the surface moves out at U = 0.01 sqrt(p_in / rho) at the poles (a
 * speed of the cohesive fluid, known even where sigma is not); its extent along
 * x, D_x = 4 sqrt(<x^2>) in 2D, 2 sqrt(5 <x^2>) in 3D (the diameter of the
 * disc or sphere with the same second moment; smooth, where max x - min x
 * moves by whole particles), is recorded for 3 s (R = 0.1 m; scaled as
 * R^1.5) after the kick and compared with Rayleigh's period at the measured
 * sigma. The period is twice the mean time between the first and the last
 * crossing, over an even number of half periods (val_period_crossings), of
 * D_x - D_y (3D: D_x minus the mean of D_y and D_z) through its mean: that difference is the n = 2 moment sum r^2 cos(2 theta) alone, free
 * of the breathing and the slow settling that move D_x and D_y together, and
 * of the n = 4 mode the square leaves. The target: the period within 5 % of
 * Rayleigh's at R / spacing = 20 (2D, validate drop) or 10 (3D, validate drop-3d: the particles laid on
 * the lattice points nearest the centre, a sphere), and the half periods between those crossings no more
 * uneven than a steady sine's over the same record (val_half_period_bound): a period read from one fast and
 * one slow half is no steady oscillation. A resolution whose run the watchdog stops gets the verdict
 * "unstable" with where and when, and the others are still run. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "validate_run.h"

#define KICK 0.05     /* the kick's surface speed, share of sqrt(p_in / rho) */
#define RUN_TIME 3.0  /* [s] time the oscillation is followed, at R = 0.1 m (scaled with R^1.5, as the period) */
#define TARGET 0.05
#define PI 3.14159265358979323846

typedef struct drop_obs {
    double R, R_small, p_in, p_small, sigma, sigma_laplace, T_ray, T, D0;
    int crossings, dim; /* dim: 2 or 3, for the units */
    double cross[16];   /* [s] the first crossings of D_x - D_y through its mean, since the kick */
    int ncross;
    double spread, spread_max; /* the half periods' (longest - shortest) / mean, and the most a steady sine shows */
    bool stopped;       /* the watchdog stopped this resolution's run: *why says where and when */
    double t_stop;      /* [s] since the kick (negative: while settling) */
    char why[400];
    bool stated; /* sigma is the scene's input (surface_tension = csf), not measured */
    val_series dx, ray, dx_minmax, aniso; /* aniso: D_x minus the mean of the other axes' D */
} drop_obs;

/* Centre, mean square offsets along each axis, the radius of the drop's volume. */
static void drop_shape(const sph_sim *sim, double spacing, double c[3], double m2[3], double *R)
{
    const sph_particles *P = &sim->P;
    const int dim = sim->dim;
    double n = (double)sim->n;
    for (int d = 0; d < 3; d++) c[d] = m2[d] = 0;
    for (uint32_t i = 0; i < sim->n; i++)
        for (int d = 0; d < dim; d++) c[d] += P->pos[d][i];
    for (int d = 0; d < dim; d++) c[d] /= n;
    for (uint32_t i = 0; i < sim->n; i++)
        for (int d = 0; d < dim; d++) m2[d] += (P->pos[d][i] - c[d]) * (P->pos[d][i] - c[d]);
    for (int d = 0; d < dim; d++) m2[d] /= n;
    double vol = n * pow(spacing, dim);
    *R = dim == 3 ? cbrt(3.0 * vol / (4.0 * PI)) : sqrt(vol / PI);
}

/* The units of sigma and of a pressure: in 2D per metre of depth (sigma N, pressure N/m), in 3D N/m and Pa. */
#define SIGMA_UNIT(dim) ((dim) == 3 ? "N/m" : "N")
#define P_UNIT(dim) ((dim) == 3 ? "Pa" : "N/m")

/* Mean pressure within R/2 of the centre [Pa, N/m in 2D]. */
static double drop_inner_pressure(const sph_sim *sim, double spacing)
{
    double c[3], m2[3], R, sum = 0;
    int count = 0;
    drop_shape(sim, spacing, c, m2, &R);
    for (uint32_t i = 0; i < sim->n; i++) {
        double r2 = 0;
        for (int d = 0; d < sim->dim; d++) r2 += pow(sim->P.pos[d][i] - c[d], 2);
        if (r2 < 0.25 * R * R) sum += sim->P.p[i], count++;
    }
    return count ? sum / count : NAN;
}

/* One step; false where the watchdog stopped the run, its report's first line then in why (n bytes). */
static bool drop_step(const val_ctx *c, sph_sim *sim, const char *label, char *why, size_t n)
{
    sph_sim_step(sim);
    if (!sim->alarm.raised) return true;
    char report[4096];
    sph_sim_alarm_report(sim, report, sizeof report);
    char *nl = strchr(report, '\n');
    if (nl) *nl = '\0';
    size_t len = strlen(report) < n ? strlen(report) : n - 1;
    memcpy(why, report, len), why[len] = '\0';
    fprintf(stderr, "%ssphlab validate: %s: stopped by the watchdog at t = %.4g s: %s\n", c->quiet ? "" : "\n", label,
            sim->t, report);
    return false;
}

/* 2D: the block's particles laid again as a disc of the same area about the
 * block's centre, on rings of radius R - (l + 1/2) s of round(2 pi r / s)
 * particles each (the innermost takes what is left), so that the drop
 * starts round: a square rounds through a large n = 4 oscillation that a
 * drop with a stated sigma and little viscosity does not damp in time. */
static int drop_cmp_r2(const void *a, const void *b)
{
    const double *x = a, *y = b;
    return (x[0] > y[0]) - (x[0] < y[0]);
}

/* 3D: the block's particles laid again on the points of its lattice (spacing s) nearest the block's centre,
 * a sphere of about the same volume, so that the drop does not start as a cube (whose rounding is a large
 * l = 4 oscillation, as the square's in 2D). */
static void drop_make_sphere(sph_sim *sim, const sph_block_def *b, double s)
{
    sph_particles *P = &sim->P;
    const uint32_t n = sim->n;
    double c[3];
    for (int d = 0; d < 3; d++) c[d] = 0.5 * (b->min[d] + b->max[d]) - sim->origin[d];
    const int m = (int)ceil(cbrt(3.0 * n / (4.0 * PI))) + 2; /* lattice points out to m spacings each way */
    const size_t total = (size_t)(2 * m + 1) * (size_t)(2 * m + 1) * (size_t)(2 * m + 1);
    double *pts = malloc(total * 4 * sizeof *pts);
    if (!pts) return; /* the cube stays: the settling rounds it */
    size_t k = 0;
    for (int i = -m; i <= m; i++)
        for (int j = -m; j <= m; j++)
            for (int l = -m; l <= m; l++, k++) { /* offsets by half a spacing: no particle at the very centre */
                double x = (i + 0.5) * s, y = (j + 0.5) * s, z = (l + 0.5) * s;
                pts[4 * k] = x * x + y * y + z * z, pts[4 * k + 1] = x, pts[4 * k + 2] = y, pts[4 * k + 3] = z;
            }
    qsort(pts, total, 4 * sizeof *pts, drop_cmp_r2);
    for (uint32_t i = 0; i < n && i < total; i++) {
        for (int d = 0; d < 3; d++) P->pos[d][i] = (float)(c[d] + pts[4 * i + 1 + d]), P->vel[d][i] = 0.0f;
    }
    free(pts);
}

static void drop_make_disc(sph_sim *sim, const sph_block_def *b, double s)
{
    if (sim->dim == 3) {
        drop_make_sphere(sim, b, s);
        return;
    }
    if (sim->dim != 2) return;
    sph_particles *P = &sim->P;
    const uint32_t n = sim->n;
    const double cx = 0.5 * (b->min[0] + b->max[0]) - sim->origin[0], cy = 0.5 * (b->min[1] + b->max[1]) - sim->origin[1];
    const double R = sqrt((double)n * s * s / PI);
    uint32_t i = 0;
    for (int l = 0; i < n; l++) {
        double r = R - (l + 0.5) * s;
        int m = r > 0.25 * s ? (int)lround(2 * PI * r / s) : 1;
        if (r <= 0.25 * s || i + (uint32_t)m > n) m = (int)(n - i), r = fmax(r, 0.0); /* the rest on the last ring */
        for (int k = 0; k < m; k++, i++) {
            double a = 2 * PI * (k + 0.5 * (l % 2)) / m, rr = m == 1 ? 0.0 : fmax(r, 0.5 * s);
            P->pos[0][i] = (float)(cx + rr * cos(a)), P->pos[1][i] = (float)(cy + rr * sin(a));
            P->vel[0][i] = P->vel[1][i] = 0.0f;
        }
    }
}

/* Makes the drop and runs it round (to the scene's damping_time); *p_in: the
 * inner pressure over the last fifth of that time. */
static bool drop_settle(const val_ctx *c, const sph_scene_def *def, const char *label, sph_sim **out, double *p_in,
                        double *R, val_clock *clock, drop_obs *o)
{
    sph_error err;
    sph_sim *sim;
    *clock = val_clock_start(); /* the run's cost, from the sim's making (as val_run) */
    if (sph_sim_create(def, c->threads, &sim, &err) != SPH_ERR_OK) {
        fprintf(stderr, "sphlab validate: %s: %s\n", label, err.msg);
        return false;
    }
    const double t_end = def->damping_time, spacing = def->blocks[0].spacing;
    drop_make_disc(sim, &def->blocks[0], spacing);
    if (sim->P.rho_c) { /* density_method = continuity: the liquid starts at its rest density up to the surface
                         * (a sum there reads the kernel's truncation, 0.7 rho0 on the outer ring, as a
                         * deficit the carried density would keep, and the surface force would crush) */
        for (uint32_t i = 0; i < sim->n; i++) sim->P.rho_c[i] = def->rest_density;
        sim->rho_carried = true;
    }
    double sum = 0;
    int count = 0;
    if (!c->quiet) fprintf(stderr, "  %s: settling to t = %g s\n", label, t_end);
    while (sim->t < t_end - 1e-12) {
        if (!drop_step(c, sim, label, o->why, sizeof o->why)) {
            o->stopped = true, o->t_stop = sim->t - t_end;
            val_cost_add(label, sim, *clock);
            sph_sim_destroy(sim);
            return false;
        }
        if (sim->t >= 0.8 * t_end) sum += drop_inner_pressure(sim, spacing), count++;
    }
    double cen[3], m2[3];
    drop_shape(sim, spacing, cen, m2, R);
    *p_in = count ? sum / count : NAN;
    *out = sim;
    return true;
}

/* One resolution: sigma from two drops, then the oscillation. False where it could not run (the scene, memory);
 * a run the watchdog stopped returns true with o->stopped set, so that the verdict says so for this resolution. */
static bool drop_one(const val_ctx *c, const char *file, int res, drop_obs *o)
{
    sph_scene_def def;
    if (!val_scene(file, 0.1 / res, &def)) return false;
    const int dim = def.dim;
    const double spacing = def.blocks[0].spacing, rho = def.rest_density, k = dim == 3 ? 2.0 : 1.0;
    char label[64];
    /* the small drop: the block shrunk to half about its centre */
    sph_scene_def small = def;
    for (int d = 0; d < dim; d++) {
        double mid = 0.5 * (def.blocks[0].min[d] + def.blocks[0].max[d]), half = 0.25 * (def.blocks[0].max[d] - def.blocks[0].min[d]);
        small.blocks[0].min[d] = mid - half;
        small.blocks[0].max[d] = mid + half;
    }
    sph_sim *sim = NULL;
    val_clock clock;
    snprintf(label, sizeof label, "drop R/%d, half size", res);
    o->dim = dim;
    o->stated = def.surface_tension == SPH_STENSION_CSF || def.surface_tension == SPH_STENSION_STRESS;
    if (!drop_settle(c, &small, label, &sim, &o->p_small, &o->R_small, &clock, o)) return o->stopped;
    val_cost_add(label, sim, clock);
    sph_sim_destroy(sim);
    snprintf(label, sizeof label, "drop R/%d", res);
    if (!drop_settle(c, &def, label, &sim, &o->p_in, &o->R, &clock, o)) return o->stopped;
    o->sigma = (o->p_in - o->p_small) / (k * (1.0 / o->R - 1.0 / o->R_small));
    o->sigma_laplace = o->sigma;
    if (o->stated) o->sigma = def.sigma; /* the stated input */
    const double omega2 = (dim == 3 ? 8.0 : 6.0) * o->sigma / (rho * pow(o->R, 3));
    o->T_ray = omega2 > 0 ? 2.0 * PI / sqrt(omega2) : NAN;
    /* the kick: the n = 2 mode with the surface's radial speed U = KICK sqrt(p_in / rho), a
     * speed of the cohesive fluid itself, so the kick does not depend on sigma, which may
     * not be measurable */
    const bool stated = o->stated;
    /* with a stated sigma, the capillary speed sqrt(sigma / (rho R)): the deformation's amplitude is then
     * KICK / sqrt(6) = 2 % of R in 2D (KICK / sqrt(8) in 3D), whatever sigma */
    const double U = KICK * sqrt(fmax(stated ? o->sigma / o->R : o->p_in, 0.0) / rho),
                 A = (dim == 3 ? 0.5 : 1.0) * U / o->R;
    double cen[3], m2[3], R;
    drop_shape(sim, spacing, cen, m2, &R);
    sph_particles *P = &sim->P;
    for (uint32_t i = 0; i < sim->n; i++) {
        P->vel[0][i] = (float)((dim == 3 ? 2.0 : 1.0) * A * (P->pos[0][i] - cen[0]));
        for (int d = 1; d < dim; d++) P->vel[d][i] = (float)(-A * (P->pos[d][i] - cen[d]));
    }
    /* with a stated sigma, 3 of Rayleigh's periods (quick: 1.5); else RUN_TIME */
    const double t0 = sim->t,
                 t_end = t0 + (c->quick ? 0.5 : 1.0) * (stated && isfinite(o->T_ray) ? 3.0 * o->T_ray
                                                                                    : RUN_TIME * pow(o->R / 0.1, 1.5));
    const double form = dim == 3 ? 2.0 * sqrt(5.0) : 4.0; /* D_x = form sqrt(<x^2>) */
    o->D0 = form * sqrt(m2[0]);
    bool ok = true;
    char ray[80] = "not measurable: the Laplace jump is not positive";
    if (isfinite(o->T_ray)) snprintf(ray, sizeof ray, "%.4g s", o->T_ray);
    if (!c->quiet)
        fprintf(stderr, "  %s: sigma %.4g %s (inner pressure %.5g %s at R = %.4g m, %.5g %s at R = %.4g m); oscillating "
                "to t = %.3g s (Rayleigh's period %s)\n", label, o->sigma, SIGMA_UNIT(dim), o->p_in, P_UNIT(dim), o->R,
                o->p_small, P_UNIT(dim), o->R_small, t_end, ray);
    while (ok && sim->t < t_end - 1e-12) {
        double mx = -1e30, mn = 1e30;
        drop_shape(sim, spacing, cen, m2, &R);
        for (uint32_t i = 0; i < sim->n; i++) mx = fmax(mx, P->pos[0][i]), mn = fmin(mn, P->pos[0][i]);
        double perp = dim == 3 ? 0.5 * (sqrt(m2[1]) + sqrt(m2[2])) : sqrt(m2[1]);
        ok = val_series_add(&o->dx, sim->t - t0, form * sqrt(m2[0])) &&
             val_series_add(&o->dx_minmax, sim->t - t0, mx - mn) &&
             val_series_add(&o->aniso, sim->t - t0, form * (sqrt(m2[0]) - perp));
        if (!ok) fprintf(stderr, "sphlab validate: out of memory\n");
        if (ok && !drop_step(c, sim, label, o->why, sizeof o->why)) {
            o->stopped = true, o->t_stop = sim->t - t0;
            break;
        }
    }
    val_cost_add(label, sim, clock); /* the settling and the oscillation: one sim */
    sph_sim_destroy(sim);
    if (!ok) return false;
    if (o->stopped) { /* no period from a record the watchdog cut short: the verdict says where it stopped */
        o->T = NAN;
        return true;
    }
    o->T = val_period_crossings(o->aniso.x, o->aniso.y, o->aniso.n, &o->crossings);
    o->ncross = val_crossing_times(o->aniso.x, o->aniso.y, o->aniso.n, o->cross, 16);
    o->spread = val_half_period_spread(o->cross, o->ncross);
    o->spread_max = val_half_period_bound(o->aniso.n ? o->aniso.x[o->aniso.n - 1] / o->T : NAN,
                                          val_amplitude_ratio(o->aniso.x, o->aniso.y, o->aniso.n, o->cross,
                                                              o->ncross));
    /* Rayleigh's curve: D0 + a sin(omega t), a the largest |D_x - D0| of the measured first half
     * period (the amplitude is only for the chart); D0 where sigma is not measurable */
    const double omega = isfinite(o->T_ray) ? 2.0 * PI / o->T_ray : 0.0;
    double a = 0;
    for (size_t i = 0; i < o->dx.n && o->dx.x[i] <= 0.5 * (isfinite(o->T) ? o->T : 0.0); i++)
        a = fmax(a, fabs(o->dx.y[i] - o->D0));
    for (size_t i = 0; i < o->dx.n; i++)
        if (!val_series_add(&o->ray, o->dx.x[i], o->D0 + a * sin(omega * o->dx.x[i]))) return false;
    if (!c->quiet)
        fprintf(stderr, "  %s: R %.4g m, sigma %.4g %s (p_in %.4g %s at R %.4g m, %.4g %s at R %.4g m), period %.4g s, "
                "Rayleigh %s\n", label, o->R, o->sigma, SIGMA_UNIT(dim), o->p_in, P_UNIT(dim), o->R, o->p_small,
                P_UNIT(dim), o->R_small, o->T, ray);
    return true;
}

static void drop_free(drop_obs *o)
{
    val_series_free(&o->dx), val_series_free(&o->ray), val_series_free(&o->dx_minmax), val_series_free(&o->aniso);
}

static int drop_run(const val_ctx *c, const val_problem *p, const char *file, int target_res)
{
    drop_obs obs[VAL_MAX_RES];
    memset(obs, 0, sizeof obs);
    bool ok = true;
    int done = 0;
    for (int r = 0; r < c->nres && ok; r++) {
        ok = drop_one(c, file, c->res[r], &obs[r]);
        if (ok) done = r + 1;
    }
    /* each resolution ran two sims (the half-size drop, then the drop): the period's error beside the second */
    for (int r = 0; r < done; r++) val_cost_error(2 * r + 1, fabs(obs[r].T / obs[r].T_ray - 1));
    char csv[64];
    snprintf(csv, sizeof csv, "%s.csv", p->name);
    FILE *f = ok ? val_csv(c, csv) : NULL;
    ok = ok && f;
    if (f) {
        fprintf(f, "resolution,R,sigma,period,period_rayleigh,t,extent_x,extent_x_rayleigh,extent_x_minmax,extent_x_minus_y\n");
        for (int r = 0; r < done; r++) {
            const drop_obs *o = &obs[r];
            for (size_t i = 0; i < o->dx.n; i++)
                fprintf(f, "%d,%.6g,%.6g,%.6g,%.6g,%.5f,%.6g,%.6g,%.6g,%.6g\n", c->res[r], o->R, o->sigma, o->T,
                        o->T_ray, o->dx.x[i], o->dx.y[i], i < o->ray.n ? o->ray.y[i] : NAN, o->dx_minmax.y[i],
                        o->aniso.y[i]); /* a run the watchdog stopped has no Rayleigh curve */
        }
        ok = val_csv_close(c, f, csv);
    }
    char trend[2400] = "";
    for (int r = 0; r < done; r++) {
        const drop_obs *o = &obs[r];
        char period[400];
        if (o->stopped) { /* the method does not hold this drop: the figure, where and when */
            val_append(trend, sizeof trend, "%sR/%d: unstable, stopped by the watchdog %.3g s %s (%s); no period",
                       r ? "; " : "", c->res[r], fabs(o->t_stop), o->t_stop < 0 ? "before the kick, settling"
                                                                             : "after the kick", o->why);
            continue;
        }
        val_period_text(period, sizeof period, o->T, o->T_ray, o->crossings);
        if (o->ncross >= 3) { /* the half periods, so that an unsteady period shows */
            val_append(period, sizeof period, "; half periods");
            for (int i = 1; i < o->ncross && i < 6; i++)
                val_append(period, sizeof period, "%s %.3g", i > 1 ? "," : "", o->cross[i] - o->cross[i - 1]);
            val_append(period, sizeof period, "%s s, spread %.0f %% (a steady sine's over this record: <= %.0f %%)",
                       o->ncross > 6 ? " ..." : "", 100 * o->spread, 100 * o->spread_max);
        }
        if (isfinite(o->T_ray))
            val_append(trend, sizeof trend, "%sR/%d: R %.4g m, sigma %.4g %s%s, %s", r ? "; " : "", c->res[r], o->R,
                       o->sigma, SIGMA_UNIT(o->dim), o->stated ? " (stated)" : "", period);
        else
            val_append(trend, sizeof trend,
                       "%sR/%d: R %.4g m, period %.4g s; sigma not measurable (Laplace jump %.3g %s between R and "
                       "R/2, inner pressure %.4g %s)",
                       r ? "; " : "", c->res[r], o->R, o->T, o->p_small - o->p_in, P_UNIT(o->dim), o->p_in,
                       P_UNIT(o->dim));
    }
    if (ok) {
        plot_lines ch;
        memset(&ch, 0, sizeof ch);
        /* Rayleigh's mode number, as `validate list` names it: n for the 2D drop, l for the 3D one */
        snprintf(ch.title, sizeof ch.title, "%s oscillation (%s = 2) against Rayleigh's period", p->name,
                 done > 0 && obs[0].dim == 3 ? "l" : "n");
        for (int r = 0; r < done; r++)
            if (isfinite(obs[r].T_ray) && isfinite(obs[r].T))
                val_append(ch.subtitle, sizeof ch.subtitle, "%sR/%d: %+.1f%%", r ? "; " : "period error: ", c->res[r],
                           100 * (obs[r].T / obs[r].T_ray - 1));
            else if (obs[r].stopped)
                val_append(ch.subtitle, sizeof ch.subtitle, "%sR/%d: unstable (watchdog)", r ? "; " : "period error: ",
                           c->res[r]);
            else if (isfinite(obs[r].T_ray)) /* fewer than 3 crossings: no period, not nan */
                val_append(ch.subtitle, sizeof ch.subtitle, "%sR/%d: no period", r ? "; " : "period error: ",
                           c->res[r]);
            else /* no sigma, so no reference: say so rather than print nan */
                val_append(ch.subtitle, sizeof ch.subtitle, "%sR/%d: sigma not measurable", r ? "; " : "period error: ",
                           c->res[r]);
        snprintf(ch.xlabel, sizeof ch.xlabel, "t since the kick [s]");
        ch.np = 1;
        snprintf(ch.p[0].ylabel, sizeof ch.p[0].ylabel, "extent along x [m]");
        for (int r = 0; r < done && ch.p[0].n < PLOT_MAX_SERIES - 1; r++) {
            plot_series *s = &ch.p[0].s[ch.p[0].n++];
            snprintf(s->label, sizeof s->label, "R/%d", c->res[r]);
            s->x = obs[r].dx.x, s->y = obs[r].dx.y, s->n = obs[r].dx.n, s->style = r;
        }
        int last = done - 1; /* the finest resolution that ran to its end: a stopped run has no curve */
        while (last >= 0 && obs[last].stopped) last--;
        if (last >= 0 && isfinite(obs[last].T_ray)) { /* Rayleigh's curve only where sigma was measured */
            const drop_obs *o = &obs[last];
            plot_series *e = &ch.p[0].s[ch.p[0].n++];
            snprintf(e->label, sizeof e->label, "Rayleigh, R/%d's sigma", c->res[last]);
            e->x = o->ray.x, e->y = o->ray.y, e->n = o->ray.n, e->style = 7;
        }
        ok = val_chart(c, p->name, &ch);
    }
    int at = 0;
    for (int r = 1; r < done; r++)
        if (abs(c->res[r] - target_res) < abs(c->res[at] - target_res)) at = r;
    double err = done ? fabs(obs[at].T / obs[at].T_ray - 1) : NAN;
    /* a period whose half periods differ by more than a steady sine's do over the record is not a steady period
     * (val_half_period_bound): the 3D R/10 drop's 1.38 and 0.80 s crossed within 5 % of Rayleigh's by chance */
    bool pass = done > 0 && !obs[at].stopped && err <= TARGET && obs[at].crossings >= 3 &&
                obs[at].spread <= obs[at].spread_max; /* false for a NaN */
    char judged[64];
    snprintf(judged, sizeof judged, "R/%d%s", done ? c->res[at] : 0,
             done && c->res[at] != target_res ? ", the run nearest the target's" : "");
    int rc = val_verdict(c, p, ok, pass, "%s (target at %s: period within 5 %% of Rayleigh's at the %s sigma)", trend,
                         judged, done && obs[0].stated ? "stated" : "measured");
    for (int r = 0; r < VAL_MAX_RES; r++) drop_free(&obs[r]);
    return rc;
}

int val_run_drop(const val_ctx *c, const val_problem *p)
{
    return drop_run(c, p, "drop.ini", 20);
}

int val_run_drop_3d(const val_ctx *c, const val_problem *p)
{
    return drop_run(c, p, "drop-3d.ini", 10);
}
