/* What each lesson exports. Every figure comes from this binary's own
 * commands (run, render, plot, view in SDL's offscreen mode, hardcases,
 * bench, study) run as subprocesses, or from the core's functions called
 * here (lesson_lab.c); the numbers in the report are read back from what
 * those commands print and write. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench_cmd.h"
#include "lesson.h"
#include "sph_kernel.h"
#include "sph_search.h"
#include "sph_sim.h"

#define PI 3.14159265358979323846

/* ---- helpers ---------------------------------------------------------------- */

static bool load_def(lx *x, const char *path, sph_scene_def *def)
{
    sph_error err;
    *def = sph_default_scene_def();
    if (sph_scene_load(path, def, &err) == SPH_ERR_OK && sph_scene_validate(def, &err) == SPH_ERR_OK) return true;
    fprintf(stderr, "sphlab lesson: %s\n", err.msg);
    lx_md(x, "\n**The scene does not load:** %s\n\n", err.msg);
    x->failed++;
    return false;
}

/* `sphlab check` of a scene, into the report; fills the pipeline's pass names. */
static int pipeline(lx *x, const char *file, char names[][24], int cap)
{
    char none[1][24];
    lx_block(x, "pipeline");
    int n = lx_check(x, lx_src(x, file), names ? names : none, names ? cap : 0);
    lx_block_end(x);
    return n;
}

static const char *work(lx *x, const char *sub)
{
    return lx_fmt("%s/%s", x->scratch, sub);
}


/* Least-squares slope of y against x. */
static double slope(const double *xs, const double *ys, size_t n)
{
    double sx = 0, sy = 0, sxx = 0, sxy = 0;
    for (size_t i = 0; i < n; i++) {
        sx += xs[i];
        sy += ys[i];
        sxx += xs[i] * xs[i];
        sxy += xs[i] * ys[i];
    }
    double d = (double)n * sxx - sx * sx;
    return d != 0 ? ((double)n * sxy - sx * sy) / d : 0;
}

/* Decay rate of the velocity (half that of the kinetic energy) from a stats CSV. */
static bool decay_rate(lx *x, const char *stats, double *rate, plot_table *keep)
{
    plot_table t;
    if (!lx_table(x, &t, stats)) return false;
    const double *tt = lx_col(x, &t, "t"), *ek = lx_col(x, &t, "ekin");
    if (!tt || !ek || t.nrows < 3) {
        plot_table_free(&t);
        return false;
    }
    double *le = malloc(t.nrows * sizeof *le);
    for (size_t i = 0; i < t.nrows; i++) le[i] = log(ek[i] > 0 ? ek[i] : 1e-300);
    *rate = -0.5 * slope(tt, le, t.nrows);
    free(le);
    if (keep) *keep = t;
    else plot_table_free(&t);
    return true;
}

/* The 2D scenes' lattice: the particle of a block at (column, row). */
static uint32_t lattice_id(const sph_scene_def *d, int col, int row)
{
    return (uint32_t)(row * sph_block_nodes(d, 0, 0) + col);
}

/* Values of a dump by particle id (the dump is in id order). */
typedef struct dump {
    plot_table t;
    const double *id, *x, *y, *vx, *vy, *rho, *p;
    size_t n;
} dump;

static bool read_dump(lx *x, const char *path, dump *d)
{
    memset(d, 0, sizeof *d);
    if (!lx_table(x, &d->t, path)) return false;
    d->id = lx_col(x, &d->t, "id");
    d->x = lx_col(x, &d->t, "x");
    d->y = lx_col(x, &d->t, "y");
    d->vx = lx_col(x, &d->t, "vx");
    d->vy = lx_col(x, &d->t, "vy");
    d->rho = lx_col(x, &d->t, "rho");
    d->p = lx_col(x, &d->t, "p");
    d->n = d->t.nrows;
    if (!d->id || !d->x || !d->y || !d->vx || !d->vy || !d->rho || !d->p) {
        plot_table_free(&d->t);
        return false;
    }
    return true;
}

static double at_id(const dump *d, const double *col, uint32_t id)
{
    return id < d->n ? col[id] : NAN;
}

static void md_bullet_fig(lx *x, const char *file, const char *what)
{
    lx_fig(x, file, what);
}

/* Moves every file of DIR/.work/SUB into DIR/SUB (made afresh). */
static int take_all(lx *x, const char *sub)
{
    char dst[1200];
    snprintf(dst, sizeof dst, "%s/%s", x->dir, sub);
    char cmd[2600];
    /* the destination holds only frames from this export */
    snprintf(cmd, sizeof cmd, "%s/%s", x->scratch, sub);
    struct stat st;
    if (stat(cmd, &st) != 0) return 0;
    if (stat(dst, &st) == 0) {
        /* remove old frames one by one: the folder is ours (frames/) */
        for (int i = 0; i < 100000; i++) {
            char f[1300];
            snprintf(f, sizeof f, "%s/frame_%05d.png", dst, i);
            if (unlink(f) != 0 && i > 0) break;
        }
        rmdir(dst);
    }
    if (rename(cmd, dst) != 0) return 0;
    int n = 0;
    for (int i = 0; i < 100000; i++) {
        char f[1300];
        snprintf(f, sizeof f, "%s/frame_%05d.png", dst, i);
        if (stat(f, &st) != 0) break;
        n++;
    }
    return n;
}

/* ---- lesson 1: kernel estimation ------------------------------------------------- */

int lx_lesson1(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    const double s = def.blocks[0].spacing, h0 = def.h, rho0 = def.rest_density;
    pipeline(x, "lesson.ini", NULL, 0);

    /* 1. the kernels */
    for (int dim = 2; dim <= 3; dim++)
        lx_sphlab(x, lx_fmt("plot-kernels-%dd", dim), NULL, NULL, NULL, "plot", "kernels", "--dim", lx_fmt("%d", dim),
                  "--h", lx_fmt("%g", h0), "--out", x->dir, "--quiet", LX_END);
    md_bullet_fig(x, "kernels-2d.png", "the five kernels in 2D: W, dW/dr and the Laplacian against r/h (PDF and CSV "
                                       "beside it)");
    md_bullet_fig(x, "kernels-3d.png", "the same in 3D");
    md_bullet_fig(x, "kernel-NAME-2d.png, kernel-NAME-3d.png",
                  "each kernel on its own, NAME = poly6, spiky, viscosity, cubic, wendland (PDF, CSV)");
    plot_table kt;
    double w0_csv[SPH_KERNEL_COUNT];
    for (int k = 0; k < SPH_KERNEL_COUNT; k++) w0_csv[k] = NAN;
    if (lx_table(x, &kt, lx_out(x, "kernels-2d.csv"))) {
        for (int k = 0; k < SPH_KERNEL_COUNT; k++) {
            int c = plot_table_find(&kt, lx_fmt("w_%s", sph_kernel_names[k]));
            if (c >= 0 && kt.nrows) w0_csv[k] = kt.col[c][0];
        }
        plot_table_free(&kt);
    }
    lx_val(x, "h", "%g", h0);
    lx_block(x, "kernels_table");
    lx_md(x, "| kernel | sigma 2D [1/m^2] | sigma 3D [1/m^3] | W(0) 2D [1/m^2] | W(0) in kernels-2d.csv | M2 / h^2 (2D) |\n"
             "|---|---|---|---|---|---|\n");
    for (int k = 0; k < SPH_KERNEL_COUNT; k++) {
        sph_kernel k2 = sph_kernel_make((sph_kernel_kind)k, 2, (float)h0);
        sph_kernel k3 = sph_kernel_make((sph_kernel_kind)k, 3, (float)h0);
        lx_md(x, "| %s | %.6g | %.6g | %.6g | %.6g | %.4f |\n", sph_kernel_names[k], k2.sigma, k3.sigma,
              sph_kernel_w(&k2, 0.0f), w0_csv[k], k2.m2 / (h0 * h0));
    }
    lx_block_end(x);
    lx_val(x, "spacing", "%g", s);
    lx_val(x, "neighbours", "%.1f", PI * (h0 / s) * (h0 / s));

    /* 2. the seed's kernel estimation of a known function */
    lx_block(x, "estimate_tables");
    if (!lx_has_command(x, "estimate")) {
        lx_missing(x, "`sphlab estimate` is not in this build: no estimate of a known function (1D and 2D)");
    } else {
        static const struct {
            const char *name, *dim, *samples, *nq, *nf, *what;
        } est[3] = {
            {"estimate-1d", "1", "random", "100,1000", "100,1000,10000",
             "1D: error of the estimate of sin(2 pi x) from n random samples against h (log-log), with the "
             "predicted bias"},
            {"estimate-2d", "2", "jitter", "50,100", "50,100,200",
             "2D: the same from a lattice jittered by 0.3 spacing, n x n samples"},
            {"estimate-2d-lattice", "2", "lattice", "50,100", "50,100,200",
             "2D: the same from a perfect lattice: no noise, only the bias"},
        };
        for (int e = 0; e < 3; e++) {
            if (lx_sphlab(x, est[e].name, NULL, NULL, NULL, "estimate", "--dim", est[e].dim, "--samples",
                          est[e].samples, "--n", x->quick ? est[e].nq : est[e].nf, "--out", x->dir, "--name",
                          est[e].name, "--quiet", LX_END) != 0)
                continue;
            lx_fig(x, lx_fmt("%s.png", est[e].name), lx_fmt("%s (PDF and CSV beside it)", est[e].what));
            plot_table t;
            if (!lx_table(x, &t, lx_out(x, lx_fmt("%s.csv", est[e].name)))) continue;
            const double *n = lx_col(x, &t, "n"), *h = lx_col(x, &t, "h"), *hs = lx_col(x, &t, "h_over_spacing"),
                         *nb = lx_col(x, &t, "neighbours"), *err = lx_col(x, &t, "error"),
                         *bias = lx_col(x, &t, "bias_predicted");
            if (n && h && hs && nb && err && bias) {
                lx_md(x, "`sphlab estimate --dim %s --samples %s` (%s): for each sample count, the error at each h "
                         "and the best h.\n\n| n | h | h / spacing | neighbours | rms error | predicted bias |\n"
                         "|---|---|---|---|---|---|\n",
                      est[e].dim, est[e].samples, est[e].name);
                for (size_t i = 0; i < t.nrows; i++) {
                    bool best = true;
                    for (size_t j = 0; j < t.nrows; j++)
                        if (n[j] == n[i] && err[j] < err[i]) best = false;
                    lx_md(x, "| %.0f | %g | %g | %.1f | %s%.3g%s | %.3g |\n", n[i], h[i], hs[i], nb[i],
                          best ? "**" : "", err[i], best ? "**" : "", bias[i]);
                }
                lx_md(x, "\n");
            }
            plot_table_free(&t);
        }
    }

    lx_block_end(x);
    /* 3. the density of the slab against h */
    static const double hq[] = {1.5, 2, 4}, hf[] = {1.2, 1.5, 2, 3, 4, 6};
    const double *hl = x->quick ? hq : hf;
    int nhl = x->quick ? 3 : 6;
    const int cols = (int)sph_block_nodes(&def, 0, 0), rows = (int)sph_block_nodes(&def, 0, 1);
    double xs[8], noise[8], deficit[8];
    FILE *f = lx_csv_open(x, "density-vs-h.csv");
    if (f) fprintf(f, "h_over_spacing,h,neighbours,interior_mean,interior_rms_percent,surface_mean,surface_deficit_percent\n");
    lx_val(x, "rho0", "%g", rho0);
    lx_block(x, "density_table");
    lx_md(x, "| h / s | h [m] | interior mean [kg/m^2] | interior rms error | top row mean [kg/m^2] | top row deficit |\n"
             "|---|---|---|---|---|---|\n");
    int good = 0;
    for (int k = 0; k < nhl; k++) {
        double h = hl[k] * s;
        const char *dpath = work(x, lx_fmt("density-h%g.csv", hl[k]));
        if (!lx_run_sim(x, lx_fmt("run-h%g", hl[k]),
                        &(lx_run_opts){scene, {lx_fmt("kernels.h=%g", h)}, 1, 1, NULL, dpath}, NULL))
            continue;
        dump d;
        if (!read_dump(x, dpath, &d)) continue;
        int margin = (int)ceil(h / s);
        double sum = 0, sq = 0, top = 0;
        int ni = 0, nt = 0;
        for (size_t i = 0; i < d.n; i++) {
            int row = (int)d.id[i] / cols;
            if (row >= margin && row <= rows - 1 - margin) {
                sum += d.rho[i];
                sq += (d.rho[i] / rho0 - 1) * (d.rho[i] / rho0 - 1);
                ni++;
            }
            if (row == rows - 1) {
                top += d.rho[i];
                nt++;
            }
        }
        plot_table_free(&d.t);
        if (!ni || !nt) continue;
        double mean = sum / ni, rms = 100 * sqrt(sq / ni), tmean = top / nt, def_pc = 100 * (1 - tmean / rho0);
        xs[good] = hl[k];
        noise[good] = rms;
        deficit[good++] = def_pc;
        if (f)
            fprintf(f, "%g,%g,%.1f,%.2f,%.3f,%.2f,%.3f\n", hl[k], h, PI * hl[k] * hl[k], mean, rms, tmean, def_pc);
        lx_md(x, "| %g | %g | %.1f | %.2f%% | %.1f | %.1f%% |\n", hl[k], h, mean, rms, tmean, def_pc);
    }
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "density-vs-h.csv", "the slab's interior noise and surface deficit against h");
    plot_lines L3 = {0};
    snprintf(L3.title, sizeof L3.title, "Density of a jittered slab: noise inside, deficit at the surface");
    snprintf(L3.subtitle, sizeof L3.subtitle, "sphlab run lesson.ini --steps 1 --set kernels.h=H; jitter 0.3 spacing");
    snprintf(L3.xlabel, sizeof L3.xlabel, "h / spacing [-]");
    L3.np = 1;
    snprintf(L3.p[0].ylabel, sizeof L3.p[0].ylabel, "density error [%%]");
    L3.p[0].n = 2;
    L3.p[0].s[0] = (plot_series){"interior rms error", xs, noise, (size_t)good, 0};
    L3.p[0].s[1] = (plot_series){"top row deficit", xs, deficit, (size_t)good, 1};
    lx_chart(x, PLOT_LINES, &L3, "density-vs-h", 1000, 650, "the slab's interior noise and surface deficit against h");

    /* 4. two pictures */
    const double pics[2] = {1.5, 4};
    for (int k = 0; k < 2; k++) {
        const char *sub = lx_fmt("render-h%g", pics[k]);
        if (lx_sphlab(x, sub, NULL, NULL, NULL, "render", scene, "--out", work(x, sub), "--steps", "1", "--every", "1",
                      "--threads", "1", "--quiet", "--set", lx_fmt("kernels.h=%g", pics[k] * s), "--color", "density",
                      "--range", "600:1400", "--overlay", "neighbours,hud,legend", "--select", "625", "--size",
                      "900x650", LX_END) == 0 &&
            lx_take(x, sub, "frame_00001.png", lx_fmt("density-h%g.png", pics[k])))
            lx_fig(x, lx_fmt("density-h%g.png", pics[k]),
                   lx_fmt("the slab coloured by density (600 to 1400 kg/m^2) with h = %g spacings, particle 625's "
                          "neighbours and weights",
                          pics[k]));
    }
    return 0;
}

/* ---- lesson 2: density summation ---------------------------------------------------- */

int lx_lesson2(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    const double s = def.blocks[0].spacing, h0 = def.h, rho0 = def.rest_density;
    const int cols = (int)sph_block_nodes(&def, 0, 0), rows = (int)sph_block_nodes(&def, 0, 1);
    pipeline(x, "lesson.ini", NULL, 0);

    static const struct {
        const char *name;
        int col, row; /* -1: last */
    } spot[] = {
        {"interior", -2, -3}, {"top (free surface)", -2, -1}, {"right side (free surface)", -1, -3},
        {"floor (wall)", -2, 0}, {"left side (wall)", 0, -3}, {"corner floor / left wall", 0, 0},
        {"corner top / right (free)", -1, -1},
    };
    enum { NSPOT = 7 };
    static const double hq[] = {2}, hf[] = {1.5, 2, 3};
    const double *hl = x->quick ? hq : hf;
    const int nh = x->quick ? 1 : 3;
    const char *models[2] = {"volume", "reflect"};
    double val[2][3][NSPOT], vmin[2][3], vmax[2][3];
    double prof_y[64], prof[2][64];
    int nprof = rows < 64 ? rows : 64;
    bool ok[2][3] = {{false}};
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < nh; k++) {
            double h = hl[k] * s;
            const char *dpath = work(x, lx_fmt("d-%s-%g.csv", models[m], hl[k]));
            if (!lx_run_sim(x, lx_fmt("run-%s-h%g", models[m], hl[k]),
                            &(lx_run_opts){scene,
                                           {lx_fmt("domain.wall_model=%s", models[m]), lx_fmt("kernels.h=%g", h)},
                                           1, 1, NULL, dpath},
                            NULL))
                continue;
            dump d;
            if (!read_dump(x, dpath, &d)) continue;
            vmin[m][k] = INFINITY;
            vmax[m][k] = -INFINITY;
            for (size_t i = 0; i < d.n; i++) {
                vmin[m][k] = fmin(vmin[m][k], d.rho[i]);
                vmax[m][k] = fmax(vmax[m][k], d.rho[i]);
            }
            for (int q = 0; q < NSPOT; q++) {
                int col = spot[q].col == -1 ? cols - 1 : spot[q].col == -2 ? cols / 2 : spot[q].col;
                int row = spot[q].row == -1 ? rows - 1 : spot[q].row == -3 ? rows / 2 : spot[q].row;
                val[m][k][q] = at_id(&d, d.rho, lattice_id(&def, col, row));
            }
            if (fabs(h - h0) < 1e-9)
                for (int r = 0; r < nprof; r++) {
                    prof_y[r] = at_id(&d, d.y, lattice_id(&def, cols / 2, r));
                    prof[m][r] = at_id(&d, d.rho, lattice_id(&def, cols / 2, r));
                }
            ok[m][k] = true;
            plot_table_free(&d.t);
        }
    lx_val(x, "cols", "%d", cols);
    lx_val(x, "rows", "%d", rows);
    lx_val(x, "spacing", "%g", s);
    lx_val(x, "rho0", "%g", rho0);
    lx_block(x, "points_table");
    lx_md(x, "| particle |");
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < nh; k++) lx_md(x, " %s, h = %g s |", models[m], hl[k]);
    lx_md(x, "\n|---|");
    for (int i = 0; i < 2 * nh; i++) lx_md(x, "---|");
    lx_md(x, "\n");
    FILE *f = lx_csv_open(x, "density-points.csv");
    if (f) fprintf(f, "wall_model,h_over_spacing,particle,rho,error_percent\n");
    for (int q = 0; q < NSPOT + 2; q++) {
        lx_md(x, "| %s |", q < NSPOT ? spot[q].name : q == NSPOT ? "lowest" : "highest");
        for (int m = 0; m < 2; m++)
            for (int k = 0; k < nh; k++) {
                if (!ok[m][k]) {
                    lx_md(x, " - |");
                    continue;
                }
                double v = q < NSPOT ? val[m][k][q] : q == NSPOT ? vmin[m][k] : vmax[m][k];
                lx_md(x, " %.1f (%+.1f%%) |", v, 100 * (v / rho0 - 1));
                if (f)
                    fprintf(f, "%s,%g,%s,%.3f,%.3f\n", models[m], hl[k],
                            q < NSPOT ? spot[q].name : q == NSPOT ? "lowest" : "highest", v, 100 * (v / rho0 - 1));
            }
        lx_md(x, "\n");
    }
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "density-points.csv", "the density at the interior, surfaces, walls and corners");

    /* the profile up the middle column */
    f = lx_csv_open(x, "density-profile.csv");
    if (f) {
        fprintf(f, "y,rho_volume,rho_reflect\n");
        for (int r = 0; r < nprof; r++) fprintf(f, "%.4f,%.3f,%.3f\n", prof_y[r], prof[0][r], prof[1][r]);
        lx_csv_close(x, f, "density-profile.csv", "the density up the middle column, both wall models");
    }
    double flat[64];
    for (int r = 0; r < nprof; r++) flat[r] = rho0;
    plot_lines L = {0};
    snprintf(L.title, sizeof L.title, "Density up the middle column: floor (wall) to free surface");
    snprintf(L.subtitle, sizeof L.subtitle, "lattice %g m, h = %g m, poly6; sphlab run lesson.ini --steps 1", s, h0);
    snprintf(L.xlabel, sizeof L.xlabel, "height y [m]");
    L.np = 1;
    snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "density [kg/m#u2#d]");
    L.p[0].n = 3;
    L.p[0].s[0] = (plot_series){"walls count (volume)", prof_y, prof[0], (size_t)nprof, 0};
    L.p[0].s[1] = (plot_series){"reflect only (the seed)", prof_y, prof[1], (size_t)nprof, 1};
    L.p[0].s[2] = (plot_series){"rest density", prof_y, flat, (size_t)nprof, 6};
    lx_chart(x, PLOT_LINES, &L, "density-profile", 1000, 650,
             "the density up the middle column, with and without the walls' share");

    /* 2. the walls decide whether a pool can rest */
    const char *pool = lx_src(x, "pool.ini");
    plot_table pt[2];
    bool pok[2] = {false, false};
    for (int m = 0; m < 2; m++) {
        char stats[1100], set[64];
        snprintf(stats, sizeof stats, "%s", work(x, lx_fmt("pool-%s.csv", models[m])));
        snprintf(set, sizeof set, "domain.wall_model=%s", models[m]);
        bool ran = lx_run_sim(x, lx_fmt("run-pool-%s", models[m]),
                              &(lx_run_opts){pool, {set}, x->quick ? 400 : -1, 1, stats, NULL}, NULL);
        if (ran && lx_table(x, &pt[m], stats)) pok[m] = true;
    }
    if (pok[0] && pok[1]) {
        const double *t0 = lx_col(x, &pt[0], "t"), *e0 = lx_col(x, &pt[0], "ekin"), *v0 = lx_col(x, &pt[0], "max_speed");
        const double *t1 = lx_col(x, &pt[1], "t"), *e1 = lx_col(x, &pt[1], "ekin"), *v1 = lx_col(x, &pt[1], "max_speed");
        if (t0 && e0 && v0 && t1 && e1 && v1) {
            plot_lines P = {0};
            snprintf(P.title, sizeof P.title, "A pool at rest: kinetic energy with each wall model");
            snprintf(P.subtitle, sizeof P.subtitle, "sphlab run pool.ini --set domain.wall_model=M --stats; "
                                                    "#gn = 0.002 m#u2#d/s");
            snprintf(P.xlabel, sizeof P.xlabel, "t [s]");
            P.np = 1;
            snprintf(P.p[0].ylabel, sizeof P.p[0].ylabel, "kinetic energy [J/m]");
            P.p[0].n = 2;
            P.p[0].s[0] = (plot_series){"walls count (volume)", t0, e0, pt[0].nrows, 0};
            P.p[0].s[1] = (plot_series){"reflect only (the seed)", t1, e1, pt[1].nrows, 1};
            lx_chart(x, PLOT_LINES, &P, "pool-walls", 1000, 600,
                     "a pool at rest: kinetic energy over time with volume walls and with the seed's reflecting walls");
            size_t a = pt[0].nrows - 1, b = pt[1].nrows - 1;
            lx_val(x, "pool_t", "%.3g", t0[a]);
            lx_val(x, "ekin_volume", "%.4g", e0[a]);
            lx_val(x, "speed_volume", "%.3g", v0[a]);
            lx_val(x, "ekin_reflect", "%.4g", e1[b]);
            lx_val(x, "speed_reflect", "%.3g", v1[b]);
        }
    }
    for (int m = 0; m < 2; m++)
        if (pok[m]) plot_table_free(&pt[m]);

    /* pictures */
    for (int m = 0; m < 2; m++) {
        const char *sub = lx_fmt("render-%s", models[m]);
        const char *name = m == 0 ? "density.png" : "density-reflect.png";
        if (lx_sphlab(x, sub, NULL, NULL, NULL, "render", scene, "--out", work(x, sub), "--steps", "1", "--every", "1",
                      "--threads", "1", "--quiet", "--set", lx_fmt("domain.wall_model=%s", models[m]), "--color",
                      "density", "--range", "600:1100", "--overlay", "grid,neighbours,hud,legend", "--select",
                      lx_fmt("%u", lattice_id(&def, cols / 2, rows - 1)), "--size", "1000x640", LX_END) == 0 &&
            lx_take(x, sub, "frame_00001.png", name))
            lx_fig(x, name,
                   lx_fmt("the block coloured by density (600 to 1100 kg/m^2), %s walls, the search grid and the "
                          "neighbours of a particle of the top row",
                          models[m]));
    }
    return 0;
}

/* ---- lesson 3: the pressure gradient -------------------------------------------------- */

/* Total energy from a dump: kinetic + potential (from the floor) + the
 * internal energy of the linear equation of state (0 below rho0 with clamp). */
static double dump_energy(const dump *d, const sph_scene_def *def)
{
    double m = def->rest_density * def->blocks[0].spacing * def->blocks[0].spacing, g = -def->gravity[1];
    double k = def->stiffness, r0 = def->rest_density, e = 0;
    for (size_t i = 0; i < d->n; i++) {
        e += 0.5 * m * (d->vx[i] * d->vx[i] + d->vy[i] * d->vy[i]) + m * g * (d->y[i] - def->domain_min[1]);
        double rho = d->rho[i];
        if (rho > 0 && (rho > r0 || def->negative_pressure != SPH_NEGP_CLAMP))
            e += m * k * (log(rho / r0) + r0 / rho - 1);
    }
    return e;
}

static int cmp_dbl2(const void *a, const void *b)
{
    const double *x = a, *y = b;
    return (x[0] > y[0]) - (x[0] < y[0]);
}

int lx_lesson3(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    const double s = def.blocks[0].spacing, rho0 = def.rest_density, g = -def.gravity[1], h = def.h;
    pipeline(x, "lesson.ini", NULL, 0);

    /* 1. the hydrostatic pool: the scene's kernels (linear and Tait), and Mueller's pair */
    static const char *const pool_runs[3][4] = {
        /* log, eos, density kernel, pressure kernel (NULL: the scene's) */
        {"pool", "linear", NULL, NULL},
        {"pool-tait", "tait", NULL, NULL},
        {"pool-mueller", "linear", "poly6", "spiky"},
    };
    dump pool[2];
    bool have[2] = {false, false}, have_stats[3] = {false, false, false};
    char statp[3][1100];
    for (int e = 0; e < 3; e++) {
        char dpath[1100], eosset[64], kd[64], kp[64];
        snprintf(dpath, sizeof dpath, "%s", work(x, lx_fmt("%s.csv", pool_runs[e][0])));
        snprintf(statp[e], sizeof statp[e], "%s",
                 e == 0 ? lx_out(x, "pool-stats.csv") : work(x, lx_fmt("%s-stats.csv", pool_runs[e][0])));
        snprintf(eosset, sizeof eosset, "physics.eos=%s", pool_runs[e][1]);
        lx_run_opts ro = {scene, {eosset}, x->quick ? 300 : -1, 1, statp[e], dpath};
        if (pool_runs[e][2]) {
            snprintf(kd, sizeof kd, "kernels.density=%s", pool_runs[e][2]);
            snprintf(kp, sizeof kp, "kernels.pressure=%s", pool_runs[e][3]);
            ro.sets[1] = kd;
            ro.sets[2] = kp;
        }
        if (!lx_run_sim(x, lx_fmt("run-%s", pool_runs[e][0]), &ro, NULL)) continue;
        have_stats[e] = true;
        if (e < 2) have[e] = read_dump(x, dpath, &pool[e]);
    }
    if (have_stats[0]) lx_fig(x, "pool-stats.csv", "the pool's per-step statistics (sphlab run --stats)");
    if (have_stats[0] && have_stats[2]) {
        plot_table ta, tb;
        if (lx_table(x, &ta, statp[0])) {
            if (lx_table(x, &tb, statp[2])) {
                const double *t0 = lx_col(x, &ta, "t"), *e0 = lx_col(x, &ta, "ekin");
                const double *t1 = lx_col(x, &tb, "t"), *e1 = lx_col(x, &tb, "ekin");
                if (t0 && e0 && t1 && e1) {
                    plot_lines L = {0};
                    snprintf(L.title, sizeof L.title, "Kinetic energy of the pool, no viscosity");
                    snprintf(L.subtitle, sizeof L.subtitle, "sphlab run lesson.ini --stats; the same pool with two "
                                                            "kernel choices");
                    snprintf(L.xlabel, sizeof L.xlabel, "t [s]");
                    L.np = 1;
                    snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "kinetic energy [J/m]");
                    L.p[0].n = 2;
                    L.p[0].s[0] = (plot_series){"", t0, e0, ta.nrows, 0};
                    snprintf(L.p[0].s[0].label, sizeof L.p[0].s[0].label, "%s / %s",
                             sph_kernel_names[def.kernel_density], sph_kernel_names[def.kernel_pressure]);
                    L.p[0].s[1] = (plot_series){"poly6 / spiky", t1, e1, tb.nrows, 1};
                    lx_chart(x, PLOT_LINES, &L, "pool-energy", 1000, 600,
                             "the pool's kinetic energy over time: one kernel against Mueller's pair, no viscosity");
                    lx_val(x, "pool_t", "%.3g", t0[ta.nrows - 1]);
                    lx_val(x, "pool_ekin", "%.4g", e0[ta.nrows - 1]);
                    lx_val(x, "kernel_density", "%s", sph_kernel_names[def.kernel_density]);
                    lx_val(x, "kernel_pressure", "%s", sph_kernel_names[def.kernel_pressure]);
                    lx_val(x, "pool_ekin_mueller", "%.4g", e1[tb.nrows - 1]);
                }
                plot_table_free(&tb);
            }
            plot_table_free(&ta);
        }
    }
    if (have[0]) {
        /* bin the pressure by height, fit the slope below the surface layer */
        /* the depth the fluid would have at rest density: N s^2 / width */
        double H = (double)pool[0].n * s * s / (def.domain_max[0] - def.domain_min[0]);
        int nb = (int)ceil(H / s);
        if (nb > 128) nb = 128;
        double by[128], bp[128], hyd[128];
        int cnt[128] = {0};
        for (int b = 0; b < nb; b++) bp[b] = 0;
        for (size_t i = 0; i < pool[0].n; i++) {
            int b = (int)floor(pool[0].y[i] / s);
            if (b >= 0 && b < nb) {
                bp[b] += pool[0].p[i];
                cnt[b]++;
            }
        }
        int m = 0;
        double fy[128] = {0}, fp[128] = {0};
        int nf = 0;
        for (int b = 0; b < nb; b++) {
            if (!cnt[b]) continue;
            by[m] = (b + 0.5) * s;
            bp[m] = bp[b] / cnt[b];
            hyd[m] = rho0 * g * (H - by[m]);
            if (by[m] < H - 2 * h && by[m] > h) {
                fy[nf] = by[m];
                fp[nf++] = bp[m];
            }
            m++;
        }
        double dpdy = slope(fy, fp, (size_t)nf);
        FILE *f = lx_csv_open(x, "pressure-depth.csv");
        if (f) {
            fprintf(f, "y,p_sph,p_hydrostatic\n");
            for (int b = 0; b < m; b++) fprintf(f, "%.4f,%.3f,%.3f\n", by[b], bp[b], hyd[b]);
            lx_csv_close(x, f, "pressure-depth.csv", "the pool's mean pressure per layer and rho0 g (H - y)");
        }
        plot_lines L = {0};
        snprintf(L.title, sizeof L.title, "Pressure against height in the pool");
        snprintf(L.subtitle, sizeof L.subtitle, "sphlab run lesson.ini --dump; layers one spacing thick; H = %.3f m",
                 H);
        snprintf(L.xlabel, sizeof L.xlabel, "height y [m]");
        L.np = 1;
        snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "pressure [N/m] (2D)");
        L.p[0].n = 2;
        L.p[0].s[0] = (plot_series){"SPH, mean of each layer", by, bp, (size_t)m, 0};
        L.p[0].s[1] = (plot_series){"#gr#d0#u g (H - y)", by, hyd, (size_t)m, 1};
        lx_chart(x, PLOT_LINES, &L, "pressure-depth", 1000, 650, "the pool's pressure against height, and rho0 g (H - y)");
        lx_val(x, "depth", "%.3f", H);
        lx_val(x, "dpdy", "%.0f", dpdy);
        lx_val(x, "dpdy_hydrostatic", "%.0f", -rho0 * g);
        lx_val(x, "dpdy_error", "%+.1f%%", 100 * (dpdy / (-rho0 * g) - 1));
        lx_val(x, "p_floor", "%.0f", m ? bp[0] : NAN);
        lx_val(x, "p_floor_hydrostatic", "%.0f", m ? hyd[0] : NAN);
    }
    if (have[0] && have[1]) {
        /* the equation of state as the code computed it: p against rho of every particle */
        size_t n = pool[0].n < pool[1].n ? pool[0].n : pool[1].n;
        double *pr = malloc(4 * n * sizeof *pr);
        double *xl = malloc(n * sizeof *xl), *yl = malloc(n * sizeof *yl), *xt = malloc(n * sizeof *xt),
               *yt = malloc(n * sizeof *yt);
        if (pr && xl && yl && xt && yt) {
            for (int e = 0; e < 2; e++) {
                for (size_t i = 0; i < n; i++) {
                    pr[2 * i] = pool[e].rho[i];
                    pr[2 * i + 1] = pool[e].p[i];
                }
                qsort(pr, n, 2 * sizeof *pr, cmp_dbl2);
                for (size_t i = 0; i < n; i++) {
                    (e ? xt : xl)[i] = pr[2 * i];
                    (e ? yt : yl)[i] = pr[2 * i + 1];
                }
            }
            FILE *f = lx_csv_open(x, "eos.csv");
            if (f) {
                fprintf(f, "rho_linear,p_linear,rho_tait,p_tait\n");
                for (size_t i = 0; i < n; i++) fprintf(f, "%.3f,%.3f,%.3f,%.3f\n", xl[i], yl[i], xt[i], yt[i]);
                lx_csv_close(x, f, "eos.csv", "pressure against density of every particle, linear and Tait");
            }
            plot_lines L = {0};
            snprintf(L.title, sizeof L.title, "The equation of state as the pressure pass computed it");
            snprintf(L.subtitle, sizeof L.subtitle, "every particle of the pool; k = %g m#u2#d/s#u2#d, negative pressure clamped",
                     def.stiffness);
            snprintf(L.xlabel, sizeof L.xlabel, "density [kg/m#u2#d]");
            L.np = 1;
            snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "pressure [N/m] (2D)");
            L.p[0].n = 2;
            L.p[0].s[0] = (plot_series){"linear: k (#gr - #gr#d0#u)", xl, yl, n, 0};
            L.p[0].s[1] = (plot_series){"Tait, #gg = 7", xt, yt, n, 1};
            lx_chart(x, PLOT_LINES, &L, "eos", 1000, 650, "pressure against density of every particle: linear and Tait");
            lx_val(x, "rho_densest_linear", "%.1f", xl[n - 1]);
            lx_val(x, "p_densest_linear", "%.0f", yl[n - 1]);
            lx_val(x, "rho_densest_tait", "%.1f", xt[n - 1]);
            lx_val(x, "p_densest_tait", "%.0f", yt[n - 1]);
        }
        free(pr);
        free(xl);
        free(yl);
        free(xt);
        free(yt);
    }
    for (int e = 0; e < 2; e++)
        if (have[e]) plot_table_free(&pool[e].t);

    /* 2. energy: the kernel pair and the form of the force */
    const char *column = lx_src(x, "column.ini");
    sph_scene_def cdef;
    if (load_def(x, column, &cdef)) {
        char nsteps[24];
        snprintf(nsteps, sizeof nsteps, "%d", x->quick ? 300 : cdef.steps);
        static const char *pairs[4][3] = {{"poly6", "spiky", "symmetric"},
                                          {"poly6", "spiky", "shared"},
                                          {"cubic", "cubic", "symmetric"},
                                          {"cubic", "cubic", "shared"}};
        lx_val(x, "column_steps", "%s", nsteps);
        lx_block(x, "energy_table");
        lx_md(x, "| density kernel | pressure kernel | force form | E after 1 step [J/m] | E at the end [J/m] | change |\n"
                 "|---|---|---|---|---|---|\n");
        FILE *f = lx_csv_open(x, "energy.csv");
        if (f) fprintf(f, "density_kernel,pressure_kernel,form,steps,e_start,e_end,change_percent\n");
        for (int c = 0; c < 4; c++) {
            double E[2] = {NAN, NAN};
            for (int r = 0; r < 2; r++) {
                const char *dpath = work(x, lx_fmt("energy-%d-%d.csv", c, r));
                lx_run_opts ro = {column,
                                  {lx_fmt("kernels.density=%s", pairs[c][0]), lx_fmt("kernels.pressure=%s", pairs[c][1]),
                                   lx_fmt("physics.pressure_form=%s", pairs[c][2])},
                                  r ? atol(nsteps) : 1, 1, NULL, dpath};
                if (!lx_run_sim(x, lx_fmt("run-energy-%s-%s-%s", pairs[c][0], pairs[c][1], pairs[c][2]), &ro, NULL))
                    continue;
                dump d;
                if (read_dump(x, dpath, &d)) {
                    E[r] = dump_energy(&d, &cdef);
                    plot_table_free(&d.t);
                }
            }
            double ch = 100 * (E[1] - E[0]) / E[0];
            lx_md(x, "| %s | %s | %s | %.2f | %.2f | %+.1f%% |\n", pairs[c][0], pairs[c][1], pairs[c][2], E[0], E[1], ch);
            if (f)
                fprintf(f, "%s,%s,%s,%s,%.4f,%.4f,%.3f\n", pairs[c][0], pairs[c][1], pairs[c][2], nsteps, E[0], E[1],
                        ch);
        }
        lx_block_end(x);
        if (f) lx_csv_close(x, f, "energy.csv", "energy change of the collapsing column per kernel pair and form");
    }

    /* 3. momentum in the open */
    const char *open = lx_src(x, "open.ini");
    sph_scene_def odef;
    if (load_def(x, open, &odef)) {
        char nsteps[24];
        snprintf(nsteps, sizeof nsteps, "%d", x->quick ? 100 : odef.steps);
        lx_val(x, "open_steps", "%s", nsteps);
        lx_block(x, "momentum_table");
        lx_md(x, "| form | sum m abs(v) [kg m/s] | abs(sum m v) [kg m/s] | ratio |\n|---|---|---|---|\n");
        FILE *f = lx_csv_open(x, "momentum.csv");
        if (f) fprintf(f, "form,steps,sum_m_abs_v,abs_sum_m_v,ratio\n");
        const char *forms[2] = {"symmetric", "shared"};
        double m = odef.rest_density * odef.blocks[0].spacing * odef.blocks[0].spacing;
        for (int c = 0; c < 2; c++) {
            const char *dpath = work(x, lx_fmt("open-%s.csv", forms[c]));
            if (!lx_run_sim(x, lx_fmt("run-open-%s", forms[c]),
                            &(lx_run_opts){open, {lx_fmt("physics.pressure_form=%s", forms[c])}, atol(nsteps), 1, NULL,
                                           dpath},
                            NULL))
                continue;
            dump d;
            if (!read_dump(x, dpath, &d)) continue;
            double px = 0, py = 0, sum = 0;
            for (size_t i = 0; i < d.n; i++) {
                px += m * d.vx[i];
                py += m * d.vy[i];
                sum += m * hypot(d.vx[i], d.vy[i]);
            }
            plot_table_free(&d.t);
            double P = hypot(px, py);
            lx_md(x, "| %s | %.4g | %.3g | %.2g |\n", forms[c], sum, P, sum > 0 ? P / sum : 0);
            if (f) fprintf(f, "%s,%s,%.6g,%.6g,%.6g\n", forms[c], nsteps, sum, P, sum > 0 ? P / sum : 0);
        }
        lx_block_end(x);
        if (f) lx_csv_close(x, f, "momentum.csv", "total momentum after the open block's run, both forms");
    }

    /* 4. a picture */
    const char *psteps = x->quick ? "100" : "500";
    if (lx_sphlab(x, "render-pressure", NULL, NULL, NULL, "render", scene, "--out", work(x, "render-pressure"),
                  "--steps", psteps, "--every", psteps, "--threads", "1", "--quiet", "--color", "pressure", "--overlay",
                  "forces,hud,legend", "--size", "1000x560", LX_END) == 0 &&
        lx_take(x, "render-pressure", "frame_00001.png", "pressure.png"))
        lx_fig(x, "pressure.png", lx_fmt("the pool after %s steps, coloured by pressure, with the force arrows "
                                         "(pressure red, gravity green)",
                                         psteps));
    return 0;
}

/* ---- lesson 4: the viscosity Laplacian ------------------------------------------------ */

int lx_lesson4(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    const double nu = def.viscosity, L = def.domain_max[0] - def.domain_min[0], k = 2 * PI / L;
    const double rate0 = 2 * nu * k * k, s = def.blocks[0].spacing;
    pipeline(x, "lesson.ini", NULL, 0);

    typedef struct tg_run {
        const char *form;
        double h_over_s;
    } tg_run;
    static const tg_run runs_full[] = {{"laplacian", 2}, {"smoothing", 2}, {"laplacian", 3}, {"smoothing", 3}},
                        runs_quick[] = {{"laplacian", 2}, {"smoothing", 2}};
    const int nr = x->quick ? 2 : 4;
    const tg_run *runs = x->quick ? runs_quick : runs_full;
    plot_table tab[4];
    double *ratio[4] = {NULL}, rates[4];
    bool ok[4] = {false};
    lx_val(x, "nu", "%g", nu);
    lx_val(x, "length", "%g", L);
    lx_val(x, "rate", "%.4f", rate0);
    lx_block(x, "decay_table");
    lx_md(x, "| viscosity form | h / s | steps | fitted rate [1/s] | analytic [1/s] | error |\n|---|---|---|---|---|---|\n");
    FILE *f = lx_csv_open(x, "taylor-green.csv");
    if (f) fprintf(f, "run,t,ekin_over_ekin0,analytic\n");
    for (int r = 0; r < nr; r++) {
        const char *stats = work(x, lx_fmt("tg-%s-%g.csv", runs[r].form, runs[r].h_over_s));
        const char *hset = lx_fmt("kernels.h=%g", runs[r].h_over_s * s);
        bool ran = lx_run_sim(x, lx_fmt("run-%s-h%g", runs[r].form, runs[r].h_over_s),
                              &(lx_run_opts){scene, {lx_fmt("physics.viscosity_form=%s", runs[r].form), hset},
                                             x->quick ? 100 : -1, 1, stats, NULL},
                              NULL);
        if (!ran || !decay_rate(x, stats, &rates[r], &tab[r])) continue;
        ok[r] = true;
        const double *t = tab[r].col[plot_table_find(&tab[r], "t")];
        const double *ek = tab[r].col[plot_table_find(&tab[r], "ekin")];
        ratio[r] = malloc(tab[r].nrows * sizeof *ratio[r]);
        /* ekin at t = 0 from the fit through the first row */
        double e0 = ek[0] * exp(2 * rates[r] * t[0]);
        for (size_t i = 0; i < tab[r].nrows; i++) {
            ratio[r][i] = ek[i] / e0;
            if (f)
                fprintf(f, "%s h=%gs,%.6g,%.6g,%.6g\n", runs[r].form, runs[r].h_over_s, t[i], ratio[r][i],
                        exp(-2 * rate0 * t[i]));
        }
        lx_md(x, "| %s | %g | %zu | %.4f | %.4f | %+.1f%% |\n", runs[r].form, runs[r].h_over_s, tab[r].nrows, rates[r],
              rate0, 100 * (rates[r] / rate0 - 1));
    }
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "taylor-green.csv", "kinetic energy over time of each run, and the analytic law");
    plot_lines C = {0};
    snprintf(C.title, sizeof C.title, "Taylor-Green vortex: viscous decay of the kinetic energy");
    snprintf(C.subtitle, sizeof C.subtitle, "%dx%d particles, #gn = %g m#u2#d/s; analytic exp(-4#gnk#u2#dt)",
             (int)sph_block_nodes(&def, 0, 0), (int)sph_block_nodes(&def, 0, 1), nu);
    snprintf(C.xlabel, sizeof C.xlabel, "t [s]");
    C.np = 1;
    snprintf(C.p[0].ylabel, sizeof C.p[0].ylabel, "E#dkin#u / E#dkin#u(0) [-]");
    double *an = NULL;
    const double *tan_ = NULL;
    size_t nan_ = 0;
    for (int r = 0; r < nr; r++) {
        if (!ok[r]) continue;
        const double *t = tab[r].col[plot_table_find(&tab[r], "t")];
        plot_series *ps = &C.p[0].s[C.p[0].n++];
        snprintf(ps->label, sizeof ps->label, "%s, h = %g s", runs[r].form, runs[r].h_over_s);
        ps->x = t;
        ps->y = ratio[r];
        ps->n = tab[r].nrows;
        ps->style = r;
        if (!an) {
            nan_ = tab[r].nrows;
            tan_ = t;
            an = malloc(nan_ * sizeof *an);
            for (size_t i = 0; i < nan_; i++) an[i] = exp(-2 * rate0 * t[i]);
        }
    }
    if (an) {
        C.p[0].s[C.p[0].n++] = (plot_series){"analytic", tan_, an, nan_, 6};
        lx_chart(x, PLOT_LINES, &C, "taylor-green", 1000, 650,
                 "kinetic energy over time: the Laplacian and the seed's smoothing form against exp(-4 nu k^2 t)");
    }
    free(an);
    for (int r = 0; r < nr; r++) {
        free(ratio[r]);
        if (ok[r]) plot_table_free(&tab[r]);
    }

    /* the 2D viscosity kernel */
    for (int dim = 2; dim <= 3; dim++)
        if (lx_sphlab(x, lx_fmt("plot-viscosity-%dd", dim), NULL, NULL, NULL, "plot", "kernel", "viscosity", "--dim",
                      lx_fmt("%d", dim), "--h", lx_fmt("%g", def.h), "--out", x->dir, "--quiet", LX_END) == 0)
            lx_fig(x, lx_fmt("kernel-viscosity-%dd.png", dim),
                   lx_fmt("the viscosity kernel in %dD: W, dW/dr, Laplacian (PDF, CSV beside it)", dim));
    plot_table kt;
    if (lx_table(x, &kt, lx_out(x, "kernel-viscosity-2d.csv"))) {
        const double *q = lx_col(x, &kt, "r_over_h"), *lap = lx_col(x, &kt, "lap");
        if (q && lap)
            for (size_t i = 0; i < kt.nrows; i++)
                if (fabs(q[i] - 0.5) < 1e-6) {
                    double hh = def.h, r = 0.5 * hh, want = 40 / (PI * pow(hh, 5)) * (hh - r);
                    lx_val(x, "h", "%g", hh);
                    lx_val(x, "lap_csv", "%.6g", lap[i]);
                    lx_val(x, "lap_exact", "%.6g", want);
                }
        plot_table_free(&kt);
    }

    /* a picture */
    if (lx_sphlab(x, "render-speed", NULL, NULL, NULL, "render", scene, "--out", work(x, "render-speed"), "--steps",
                  "50", "--every", "50", "--threads", "1", "--quiet", "--color", "speed", "--overlay",
                  "forces,hud,legend", "--size", "800x700", LX_END) == 0 &&
        lx_take(x, "render-speed", "frame_00001.png", "speed.png"))
        lx_fig(x, "speed.png", "the vortex after 50 steps coloured by speed, with the viscous force arrows (blue)");
    return 0;
}

/* ---- lesson 5: the spatial hash ---------------------------------------------------------- */

int lx_lesson5(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    pipeline(x, "lesson.ini", NULL, 0);

    /* 1. the seed's worked example */
    lx_hash_row rows[64];
    memset(rows, 0, sizeof rows);
    int cells = 0, coll = 0;
    uint32_t T = 0;
    int n = lx_hash_example(scene, NULL, 0, rows, 64, &cells, &coll, &T);
    if (n < 0) {
        x->failed++;
        return 1;
    }
    lx_val(x, "particles", "%d", n);
    lx_val(x, "cell_size", "%.7g", def.h * (1 + 1.0 / 1024));
    lx_val(x, "table_size", "%u", T);
    lx_block(x, "hash_table");
    lx_md(x, "| particle | x [m] | y [m] | cell | hash | key |\n|---|---|---|---|---|---|\n");
    FILE *f = lx_csv_open(x, "hash-example.csv");
    if (f) fprintf(f, "particle,x,y,cell_x,cell_y,hash,key\n");
    for (int i = 0; i < n; i++) {
        lx_md(x, "| %u | %.3f | %.3f | (%d, %d) | %u | %u |\n", rows[i].id, rows[i].x, rows[i].y, rows[i].cx,
              rows[i].cy, rows[i].hash, rows[i].key);
        if (f)
            fprintf(f, "%u,%.6f,%.6f,%d,%d,%u,%u\n", rows[i].id, rows[i].x, rows[i].y, rows[i].cx, rows[i].cy,
                    rows[i].hash, rows[i].key);
    }
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "hash-example.csv", "cell, hash and key of each of the ten particles");
    if (n > 7) {
        lx_val(x, "p7_cell", "(%d, %d)", rows[7].cx, rows[7].cy);
        lx_val(x, "p7_hash", "%u", rows[7].hash);
        lx_val(x, "p7_key", "%u", rows[7].key);
    }
    lx_val(x, "cells", "%d", cells);
    lx_val(x, "colliding_cells", "%d", coll);
    const char *sub = "render-hash";
    if (lx_sphlab(x, sub, NULL, NULL, NULL, "render", scene, "--out", work(x, sub), "--steps", "1", "--every", "1",
                  "--threads", "1", "--quiet", "--color", "key", "--overlay",
                  "grid,keys,collisions,neighbours,index,hud,legend", "--select", "7", "--size", "1100x760",
                  LX_END) == 0 &&
        lx_take(x, sub, "frame_00001.png", "hash.png"))
        lx_fig(x, "hash.png", "the ten particles coloured by key: cells, keys, colliding cells (red), particle 7's "
                              "neighbours, and the sorted index with its start table under the view");

    /* 2. the traps */
    lx_block(x, "floor_table");
    lx_md(x, "| x [m] | int(x / h) | floor(x / h) |\n|---|---|---|\n");
    const float xs[] = {-0.15f, -0.05f, 0.05f, 0.15f};
    for (int i = 0; i < 4; i++)
        lx_md(x, "| %g | %d | %d |\n", xs[i], (int)(xs[i] / 0.1f), sph_cell_coord(xs[i], 1.0f / 0.1f));
    int32_t bx = 200000, by = 300;
    int64_t exact = (int64_t)bx * SPH_HASH_P1 + (int64_t)by * SPH_HASH_P2;
    lx_block_end(x);
    lx_val(x, "big_cell", "(%d, %d)", bx, by);
    lx_val(x, "big_sum", "%lld", (long long)exact);
    lx_val(x, "big_wrapped", "%u", sph_hash_cell(2, bx, by, 0));
    const float h6 = 0.06f, xa = 0.0599999949f, xb = -1e-9f;
    float inv_h = 1.0f / h6, inv_c = 1.0f / (h6 * (1.0f + 1.0f / 1024.0f));
    lx_val(x, "xa", "%.10g", xa);
    lx_val(x, "xb", "%.3g", xb);
    lx_val(x, "h6", "%g", h6);
    lx_val(x, "gap", "%.10g", (double)xa - (double)xb);
    lx_val(x, "cells_exact", "%d and %d", sph_cell_coord(xa, inv_h), sph_cell_coord(xb, inv_h));
    lx_val(x, "cells_wider", "%d and %d", sph_cell_coord(xa, inv_c), sph_cell_coord(xb, inv_c));

    /* 3. collisions and the table size */
    const char *block = lx_src(x, "block.ini");
    static const unsigned tq[] = {0, 16}, tf[] = {0, 4096, 97, 16, 1};
    const unsigned *ts = x->quick ? tq : tf;
    int nt = x->quick ? 2 : 5;
    f = lx_csv_open(x, "collisions.csv");
    if (f) fprintf(f, "table_size,keys,occupied_cells,colliding_cells,neighbours_ms,density_ms\n");
    lx_block(x, "collisions_table");
    lx_md(x, "| table_size | keys | occupied cells | cells sharing a key | neighbours [ms/step] |\n|---|---|---|---|---|\n");
    for (int i = 0; i < nt; i++) {
        char set[64];
        snprintf(set, sizeof set, "search.table_size=%u", ts[i]);
        const char *sets[1] = {set};
        lx_hash_row dummy[1];
        int c = 0, cc = 0;
        uint32_t keys = 0;
        if (lx_hash_example(block, sets, 1, dummy, 1, &c, &cc, &keys) < 0) {
            x->failed++;
            continue;
        }
        lx_run r = {0};
        double nb = -1;
        if (lx_run_sim(x, lx_fmt("run-table-%u", ts[i]), &(lx_run_opts){block, {set}, 20, 1, NULL, NULL}, &r))
            nb = lx_run_pass(&r, "neighbours");
        lx_md(x, "| %u%s | %u | %d | %d | %.3f |\n", ts[i], ts[i] ? "" : " (N)", keys, c, cc, nb);
        if (f) fprintf(f, "%u,%u,%d,%d,%.4f,%.4f\n", ts[i], keys, c, cc, nb, lx_run_pass(&r, "density"));
    }
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "collisions.csv", "occupied and colliding cells and the neighbour pass's time per table size");
    sub = "render-collisions";
    if (lx_sphlab(x, sub, NULL, NULL, NULL, "render", block, "--out", work(x, sub), "--steps", "1", "--every", "1",
                  "--threads", "1", "--quiet", "--set", "search.table_size=16", "--color", "key", "--overlay",
                  "grid,keys,collisions,hud,legend", "--size", "1000x640", LX_END) == 0 &&
        lx_take(x, sub, "frame_00001.png", "collisions.png"))
        lx_fig(x, "collisions.png", "the block with a table of 16 keys: cells that share a key are red");

    /* 4. the hard cases that check the hash */
    lx_block(x, "hardcases");
    const char *names[2] = {"table-size-1", "negative-borders"};
    for (int i = 0; i < 2; i++) {
        const char *log;
        if (lx_sphlab(x, lx_fmt("hardcases-%s", names[i]), NULL, NULL, &log, "hardcases", "--only", names[i], LX_END) ==
            0)
            lx_md_file(x, log, 10);
    }
    lx_block_end(x);
    return 0;
}

/* ---- lesson 6: sorting and offsets -------------------------------------------------------- */

typedef struct bitonic_ctx {
    lx *x;
    FILE *csv;
} bitonic_ctx;

static void bitonic_row(void *ctx, int stage, int step, uint32_t w, int flip, const uint32_t *keys,
                        const uint32_t *index, uint32_t n, int swaps)
{
    bitonic_ctx *b = ctx;
    lx_md(b->x, "| %d | %d | %u | %s | %d |", stage + 1, step + 1, w, flip ? "flip" : "disperse", swaps);
    for (uint32_t i = 0; i < n; i++) lx_md(b->x, " %u<sub>%u</sub>", keys[i], index[i]);
    lx_md(b->x, " |\n");
    if (b->csv) {
        fprintf(b->csv, "%d,%d,%u,%s,%d", stage + 1, step + 1, w, flip ? "flip" : "disperse", swaps);
        for (uint32_t i = 0; i < n; i++) fprintf(b->csv, ",%u", keys[i]);
        fprintf(b->csv, "\n");
    }
}

static void offsets_table(lx *x, const uint32_t *keys, uint32_t n, uint32_t T, const char *csv_name)
{
    sph_entry e[64], scratch[64];
    uint32_t count[65], start[64];
    for (uint32_t i = 0; i < n; i++) e[i] = (sph_entry){keys[i], keys[i], i};
    sph_sort_counting(e, scratch, count, n, T);
    sph_offsets_build(e, n, start, T);
    lx_md(x, "Sorted (key<sub>particle</sub>):");
    for (uint32_t i = 0; i < n; i++) lx_md(x, " %u<sub>%u</sub>", e[i].key, e[i].index);
    lx_md(x, "\n\nStart table (`sph_offsets_build`, src/passes/offsets.c), key: start:");
    for (uint32_t k = 0; k < T; k++)
        lx_md(x, " %u: %s%s", k, start[k] == SPH_EMPTY ? "inf" : lx_fmt("%u", start[k]), k + 1 < T ? "," : "\n\n");
    FILE *f = csv_name ? lx_csv_open(x, csv_name) : NULL;
    if (f) {
        fprintf(f, "key,count,start\n");
        for (uint32_t k = 0; k < T; k++) {
            uint32_t c = 0;
            for (uint32_t i = 0; i < n; i++) c += keys[i] == k;
            if (start[k] == SPH_EMPTY) fprintf(f, "%u,%u,inf\n", k, c);
            else fprintf(f, "%u,%u,%u\n", k, c, start[k]);
        }
        lx_csv_close(x, f, csv_name, "per key: its count and its start in the sorted entries (inf: empty)");
    }
}

int lx_lesson6(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    char passes[SPH_PASS_COUNT][24];
    int np = pipeline(x, "lesson.ini", passes, SPH_PASS_COUNT);

    /* 1. the slide's keys through the bitonic network */
    static const uint32_t slide[10] = {9, 0, 6, 7, 1, 1, 4, 2, 2, 2};
    lx_block(x, "bitonic_table");
    lx_md(x, "| stage | step | w | kind | swaps | entries after the step |\n|---|---|---|---|---|---|\n");
    bitonic_ctx b = {x, lx_csv_open(x, "bitonic-steps.csv")};
    if (b.csv) fprintf(b.csv, "stage,step,w,kind,swaps,k0,k1,k2,k3,k4,k5,k6,k7,k8,k9\n");
    int steps = lx_bitonic_steps(slide, 10, bitonic_row, &b);
    lx_block_end(x);
    if (b.csv) lx_csv_close(x, b.csv, "bitonic-steps.csv", "the keys after each step of the bitonic network");
    /* the core's own sorts give the same order */
    sph_entry e1[10], e2[10], sc[10];
    uint32_t cnt[11];
    for (int i = 0; i < 10; i++) e1[i] = e2[i] = (sph_entry){slide[i], slide[i], (uint32_t)i};
    sph_sort_bitonic(e1, 10);
    sph_sort_counting(e2, sc, cnt, 10, 10);
    bool same = memcmp(e1, e2, sizeof e1) == 0;
    lx_val(x, "bitonic_steps", "%d", steps);
    lx_val(x, "sorts_differ", "%s", same ? "" : "DIFFERENT");
    if (!same) x->failed++;

    lx_block(x, "offsets_slide");
    offsets_table(x, slide, 10, 10, "offsets-slide.csv");
    lx_block_end(x);

    lx_hash_row rows[16];
    int cells, coll;
    uint32_t T;
    int n = lx_hash_example(scene, NULL, 0, rows, 16, &cells, &coll, &T);
    if (n > 0 && n <= 16) {
        uint32_t keys[16];
        lx_val(x, "real_last", "%d", n - 1);
        lx_block(x, "real_keys");
        for (int i = 0; i < n; i++) {
            keys[i] = rows[i].key;
            lx_md(x, "%u%s", keys[i], i + 1 < n ? ", " : "");
        }
        lx_block(x, "offsets_real");
        offsets_table(x, keys, (uint32_t)n, T, "offsets.csv");
        lx_block_end(x);
    }

    /* 2. the passes one at a time, in the window's scripted mode */
    lx_val(x, "view_ok", "%s", "");
    if (!lx_has_command(x, "view")) {
        lx_missing(x, "`sphlab view` is not in this build: no pass-by-pass screenshots");
    } else {
        /* the window's own scripted mode (SDL's event loop, keys, screenshots)
         * runs as `sphlab view` in a child process: SDL's video subsystem and
         * the offscreen driver are set up per process, from its environment */
        int upto = 0;
        while (upto < np && strcmp(passes[upto], "neighbours") != 0) upto++;
        if (upto < np) upto++;
        char keys[64] = "";
        for (int i = 0; i < upto; i++) strcat(keys, ".p");
        const char *cwd = work(x, "view");
        mkdir(cwd, 0755);
        if (lx_sphlab(x, "view-passes", cwd, "SDL_VIDEODRIVER=offscreen", NULL, "view", lx_abs(scene), "--paused", "--frames",
                      lx_fmt("%d", 2 * upto), "--keys", keys, "--threads", "1", "--color", "key", "--overlay",
                      "grid,keys,index,hud,legend", "--select", "7", "--size", "1100x760", LX_END) == 0) {
            for (int i = 0; i < upto; i++) {
                const char *name = lx_fmt("pass-%d-%s.png", i + 1, passes[i]);
                if (lx_take(x, "view", lx_fmt("sphlab-%04d.png", i), name))
                    lx_fig(x, name, lx_fmt("the window after the %s pass of the first step (index strip: entries "
                                           "and start table as they are in memory then)",
                                           passes[i]));
            }
            lx_val(x, "view_ok", "yes");
        }
    }

    /* 3. what a sort costs */
    const char *big = lx_src(x, "big.ini");
    static const double sq[] = {0.02, 0.01}, sf[] = {0.02, 0.01, 0.005};
    const double *sp = x->quick ? sq : sf;
    const int ns = x->quick ? 2 : 3;
    const char *sorts[3] = {"bitonic", "counting", "qsort"};
    double N[3], ms[3][3];
    FILE *f = lx_csv_open(x, "sort-time.csv");
    if (f) fprintf(f, "particles,bitonic_ms,counting_ms,qsort_ms\n");
    lx_block(x, "sort_table");
    lx_md(x, "| particles | bitonic | counting | qsort |\n|---|---|---|---|\n");
    int good = 0;
    for (int i = 0; i < ns; i++) {
        bool all = true;
        for (int k = 0; k < 3; k++) {
            lx_run r;
            ms[k][good] = NAN;
            lx_run_opts ro = {big,
                              {lx_fmt("fluid.spacing=%g", sp[i]), lx_fmt("kernels.h=%g", 2 * sp[i]),
                               lx_fmt("search.sort=%s", sorts[k])},
                              x->quick ? 3 : 10, 1, NULL, NULL};
            if (!lx_run_sim(x, lx_fmt("run-%s-%g", sorts[k], sp[i]), &ro, &r)) {
                all = false;
                continue;
            }
            N[good] = (double)r.particles;
            ms[k][good] = lx_run_pass(&r, "sort");
        }
        if (!all) continue;
        lx_md(x, "| %.0f | %.3f | %.3f | %.3f |\n", N[good], ms[0][good], ms[1][good], ms[2][good]);
        if (f) fprintf(f, "%.0f,%.4f,%.4f,%.4f\n", N[good], ms[0][good], ms[1][good], ms[2][good]);
        good++;
    }
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "sort-time.csv", "the sort pass's milliseconds per step per sort and particle count");
    if (good >= 2) {
        plot_lines L = {0};
        snprintf(L.title, sizeof L.title, "What the sort costs: bitonic network, counting sort, qsort");
        snprintf(L.subtitle, sizeof L.subtitle, "sphlab run big.ini, one thread; the sort pass only");
        snprintf(L.xlabel, sizeof L.xlabel, "particles [-]");
        L.np = 1;
        snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "sort pass [ms/step]");
        for (int k = 0; k < 3; k++)
            L.p[0].s[L.p[0].n++] = (plot_series){"", N, ms[k], (size_t)good, k};
        for (int k = 0; k < 3; k++) snprintf(L.p[0].s[k].label, sizeof L.p[0].s[k].label, "%s", sorts[k]);
        lx_chart(x, PLOT_LINES, &L, "sort-time", 1000, 650, "the sort pass's time against the particle count");
    }
    return 0;
}

/* ---- lesson 7: the full simulation --------------------------------------------------------- */

int lx_lesson7(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    char passes[SPH_PASS_COUNT][24];
    int np = pipeline(x, "lesson.ini", passes, SPH_PASS_COUNT);

    /* 1. the run, with per-step statistics */
    lx_run r;
    if (!lx_run_sim(x, "run", &(lx_run_opts){scene, {NULL}, x->quick ? 200 : -1, 0, lx_out(x, "stats.csv"),
                                            lx_out(x, "final.csv")},
                    &r))
        return 1;
    int rc;
    lx_fig(x, "stats.csv", "one row per step: t, dt, energy, density, max speed, ms of each pass");
    lx_fig(x, "final.csv", "the particles at the end: id, position, velocity, density, pressure");
    lx_val(x, "particles", "%ld", r.particles);
    lx_val(x, "steps", "%ld", r.steps);
    lx_val(x, "t_sim", "%.3f", r.t_sim);
    lx_val(x, "threads", "%d", r.threads);
    lx_block(x, "passes_table");
    lx_md(x, "| pass | ms/step | share |\n|---|---|---|\n");
    int top = 0;
    for (int i = 0; i < r.npass; i++) {
        lx_md(x, "| %s | %.4f | %.1f%% |\n", r.pass[i], r.ms_step[i], r.share[i]);
        if (r.ms_step[i] > r.ms_step[top]) top = i;
    }
    lx_md(x, "| all passes | %.4f | 100%% |\n", r.total_ms_step);
    lx_block_end(x);
    lx_val(x, "top_pass", "%s", r.pass[top]);
    lx_val(x, "top_share", "%.1f%%", r.share[top]);
    lx_val(x, "wall_s", "%.3f", r.wall_s);
    lx_val(x, "steps_per_s", "%.0f", r.steps_per_s);
    lx_val(x, "particle_steps_per_s", "%.3g", r.steps_per_s * (double)r.particles);
    lx_val(x, "ekin", "%.4g", r.ekin);
    lx_val(x, "rho_min", "%.1f", r.rho_min);
    lx_val(x, "rho_max", "%.1f", r.rho_max);
    lx_val(x, "rho_error_max", "%+.2f%%", 100 * (r.rho_max / def.rest_density - 1));

    if (lx_sphlab(x, "plot-passes", NULL, NULL, NULL, "plot", "passes", lx_out(x, "stats.csv"), "--out", x->dir,
                  "--quiet", LX_END) == 0) {
        lx_fig(x, "passes.png", "median milliseconds per step of each pass (PDF, CSV beside it)");
        lx_fig(x, "passes-time.png", "the passes' time stacked over the run (PDF, CSV beside it)");
    }
    if (lx_sphlab(x, "plot-series", NULL, NULL, NULL, "plot", "series", lx_out(x, "stats.csv"), "--y",
                  "ekin,rho_min,rho_mean,rho_max", "--dim", "2", "--name", "energy-density", "--out", x->dir,
                  "--quiet", LX_END) == 0)
        lx_fig(x, "energy-density.png", "kinetic energy and density (min, mean, max) over time (PDF, CSV beside it)");

    /* 2. the dam break over time */
    const char *every = x->quick ? "50" : "400";
    rc = x->quick ? lx_sphlab(x, "render-frames", NULL, NULL, NULL, "render", scene, "--out", work(x, "frames"),
                              "--steps", "100", "--every", every, "--quiet", "--color", "speed", "--range", "0:4",
                              "--overlay", "hud,legend", "--size", "960x520", LX_END)
                  : lx_sphlab(x, "render-frames", NULL, NULL, NULL, "render", scene, "--out", work(x, "frames"),
                              "--every", every, "--quiet", "--color", "speed", "--range", "0:4", "--overlay",
                              "hud,legend", "--size", "960x520", LX_END);
    if (rc == 0) {
        int nf = take_all(x, "frames");
        lx_fig(x, "frames/frame_NNNNN.png", lx_fmt("%d frames of the dam break, one every %s steps, coloured by speed "
                                                   "(0 to 4 m/s)",
                                                   nf, every));
        lx_val(x, "every", "%s", every);
        lx_val(x, "frames", "%d", nf);
    }

    /* 3. one step, pass by pass, in the window's scripted mode */
    lx_val(x, "view_before", "%s", "");
    if (!lx_has_command(x, "view")) {
        lx_missing(x, "`sphlab view` is not in this build: no pass-by-pass screenshots");
        return 0;
    }
    /* the window's scripted mode runs as `sphlab view` in a child process: SDL
     * sets up its video subsystem and offscreen driver per process */
    const char *before = x->quick ? "20" : "1500";
    char keys[64] = "j";
    for (int i = 0; i < np; i++) strcat(keys, ".p");
    const char *cwd = work(x, "view");
    mkdir(cwd, 0755);
    if (lx_sphlab(x, "view-passes", cwd, "SDL_VIDEODRIVER=offscreen", NULL, "view", lx_abs(scene), "--steps-per-frame", before,
                  "--frames", lx_fmt("%d", 1 + 2 * np), "--keys", keys, "--threads", "1", "--color", "speed",
                  "--overlay", "hud,legend", "--size", "960x560", LX_END) == 0) {
        for (int i = 0; i < np; i++) {
            const char *name = lx_fmt("pass-%02d-%s.png", i + 1, passes[i]);
            if (lx_take(x, "view", lx_fmt("sphlab-%04d.png", i), name))
                lx_fig(x, name, lx_fmt("after the %s pass of the step after the first %s (the window recolours by "
                                       "the field the pass wrote; the HUD names it)",
                                       passes[i], before));
        }
        lx_val(x, "view_before", "%s", before);
    }
    return 0;
}

/* ---- lesson 8: the optimisation ladder ------------------------------------------------------ */

/* Splits a CSV line (no quoting) in place. */
static int split_csv(char *line, char **f, int cap)
{
    int n = 0;
    for (char *p = line; n < cap;) {
        f[n++] = p;
        p = strchr(p, ',');
        if (!p) break;
        *p++ = '\0';
    }
    return n;
}

/* The ladder's results as a Markdown table, from bench_ladder_measure's struct. */
static void ladder_table(lx *x, const bench_opts *o, const bench_ladder *lad)
{
    lx_block(x, "ladder_table");
    lx_md(x, "| level | what | threads | largest N at 60 steps/s | ms/step at the table's N |\n|---|---|---|---|---|\n");
    for (int s = 0; s < o->nsel; s++) {
        const bench_level *L = &bench_levels[o->sel[s]];
        const level_result *r = &lad->res[s];
        lx_md(x, "| %s | %s | %d | %s%s | %s%s |\n", L->name, L->about, r->at.threads ? r->at.threads : L->threads,
              r->searched ? lx_fmt("%.0f", r->max_n) : "", r->capped ? " (capped)" : "",
              r->at_ok ? lx_fmt("%.6g", r->at.ms_step) : "", r->at_ok ? lx_fmt(" (N = %u)", r->at.n) : "");
    }
    lx_block_end(x);
}

int lx_lesson8(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    pipeline(x, "lesson.ini", NULL, 0);
    lx_val(x, "bench", "%s", lx_has_command(x, "bench") ? "yes" : "");
    if (!lx_has_command(x, "bench")) {
        lx_missing(x, "`sphlab bench` is not in this build: no levels, no ladder; only the picture below");
    } else {
        /* the CPU levels of the bench module's table (the GL ones need a device) */
        int lv[BENCH_MAX_LEVELS], nl = 0;
        for (int i = 0; i < bench_level_count && nl < BENCH_MAX_LEVELS; i++)
            if (!bench_level_gl(&bench_levels[i])) lv[nl++] = i;
        bench_opts bo;
        bench_opts_init(&bo, true);
        memcpy(bo.sel, lv, sizeof lv);
        bo.nsel = nl;
        char *text = NULL;
        size_t len = 0;
        FILE *m = open_memstream(&text, &len);
        const char *vpath;
        FILE *vf = lx_log_open(x, "bench-levels", (const char *const[]){"sphlab", "bench", "levels", NULL}, &vpath);
        if (m) {
            bench_levels_print(m, &bo);
            fclose(m);
            if (vf) {
                /* the log has the whole table and the benchmark's scene, as the command prints them */
                bench_levels_print(vf, &bo);
                char ini[2048];
                bench_scene_ini(bo.cfg.dim, bench_k_near(bo.cfg.dim, 1000), BENCH_JITTER, ini, sizeof ini);
                fprintf(vf, "\n%s", ini);
            }
            lx_block(x, "levels");
            lx_md_text(x, text, nl + 1);
            lx_block_end(x);
            free(text);
        }
        if (vf) fclose(vf);
        if (nl == 0) {
            x->failed++;
            lx_md(x, "**No level could be read from `sphlab bench levels`.**\n\n");
        }
        /* 2. each level on the lesson's scene */
        char steps[24];
        snprintf(steps, sizeof steps, "%d", x->quick ? 5 : def.steps);
        const char *spacing = x->quick ? "0.04" : NULL;
        double ms[16], nbm[16];
        long N = 0;
        lx_val(x, "steps", "%s", steps);
        lx_val(x, "spacing_sets", "%s", spacing ? " --set fluid.spacing=0.04 --set kernels.h=0.08" : "");
        lx_block(x, "levels_table");
        lx_md(x, "| level | what | threads | ms/step | neighbours [ms] | speedup over L0 | over the level before | "
                 "steps/s | 60 steps/s? |\n|---|---|---|---|---|---|---|---|---|\n");
        FILE *f = lx_csv_open(x, "levels.csv");
        if (f) fprintf(f, "level,threads,particles,ms_per_step,neighbours_ms,speedup,steps_per_s\n");
        int good = 0;
        plot_bars B = {0};
        for (int i = 0; i < nl; i++) {
            const bench_level *L = &bench_levels[lv[i]];
            lx_run_opts ro = {scene, {NULL}, atol(steps), L->threads, NULL, NULL};
            int ns = 0;
            if (spacing) {
                ro.sets[ns++] = "fluid.spacing=0.04";
                ro.sets[ns++] = "kernels.h=0.08";
            }
            /* the level's keys, "section.key=value" separated by spaces */
            char keys[LX_RUN_MAX_SETS][80];
            const char *k0 = L->sets;
            while (*k0 && ns < LX_RUN_MAX_SETS - 1) {
                size_t kl = strcspn(k0, " ");
                if (kl) {
                    snprintf(keys[ns], sizeof keys[0], "%.*s", (int)kl, k0);
                    ro.sets[ns] = keys[ns];
                    ns++;
                }
                k0 += kl;
                while (*k0 == ' ') k0++;
            }
            lx_run r;
            if (!lx_run_sim(x, lx_fmt("run-%s", L->name), &ro, &r)) {
                ms[i] = NAN;
                continue;
            }
            ms[i] = r.total_ms_step;
            nbm[i] = lx_run_pass(&r, "neighbours");
            N = r.particles;
            double sp0 = ms[0] / ms[i], spp = i ? ms[i - 1] / ms[i] : 1;
            lx_md(x, "| %s | %s | %d | %.3f | %.3f | %.2f | %.2f | %.0f | %s |\n", L->name, L->about, r.threads,
                  ms[i], nbm[i], sp0, spp, 1000 / ms[i], 1000 / ms[i] >= 60 ? "yes" : "no");
            if (f)
                fprintf(f, "%s,%d,%ld,%.4f,%.4f,%.4f,%.2f\n", L->name, r.threads, r.particles, ms[i], nbm[i], sp0,
                        1000 / ms[i]);
            if (B.n < PLOT_MAX_BARS) {
                snprintf(B.name[B.n], sizeof B.name[0], "%.7s", L->name);
                snprintf(B.note[B.n], sizeof B.note[0], "%.2f ms, x%.1f", ms[i], sp0);
                B.value[B.n++] = ms[i];
            }
            good++;
        }
        lx_block_end(x);
        if (f) lx_csv_close(x, f, "levels.csv", "milliseconds per step of each level on the lesson's scene");
        if (good) {
            snprintf(B.title, sizeof B.title, "The optimisation ladder on %ld particles (3D)", N);
            snprintf(B.subtitle, sizeof B.subtitle, "sphlab run lesson.ini --steps %s with each level's keys; "
                                                    "speedup over L0",
                     steps);
            snprintf(B.xlabel, sizeof B.xlabel, "time per step [ms]");
            lx_chart(x, PLOT_BARS, &B, "levels", 1000, 600, "milliseconds per step of each level, with its speedup");
        }
        /* 3. the ladder: the largest N at 60 steps/s */
        lx_val(x, "ladder_skipped", "%s", x->quick ? "yes" : "");
        lx_val(x, "ladder_table", "%s", "");
        if (!x->quick) {
            /* `sphlab bench ladder --quick --out DIR/.work/bench`, in process: its
             * measurements come back in a struct, its files are its own */
            bench_opts lo;
            bench_opts_init(&lo, true);
            lo.quiet = true;
            lo.out = work(x, "bench");
            char *largv[] = {"bench", "ladder", "--quick", "--out", (char *)lo.out, NULL};
            bench_ladder lad;
            bench_progress_opts(&lo);
            bool ok = bench_ladder_measure(&lo, &lad) == 0;
            const char *lpath;
            FILE *lf = lx_log_open(x, "bench-ladder", (const char *const[]){"sphlab", "bench", "ladder", "--quick",
                                                                           "--out", lo.out, NULL},
                                   &lpath);
            if (ok && lf) bench_ladder_print(lf, &lo, &lad); /* the table goes to the log */
            if (lf) fclose(lf);
            ok = ok && bench_ladder_write(&lo, &lad, 5, largv);
            if (ok) {
                const char *ext[4] = {"png", "pdf", "csv", "json"};
                for (int k = 0; k < 4; k++)
                    if (lx_take(x, "bench", lx_fmt("ladder-3d.%s", ext[k]), lx_fmt("ladder-3d.%s", ext[k])))
                        lx_fig(x, lx_fmt("ladder-3d.%s", ext[k]),
                               k == 0 ? "sphlab bench ladder --quick: the largest N at 60 steps/s per level"
                                      : "the same (PDF, CSV, JSON)");
                ladder_table(x, &lo, &lad);
            } else {
                x->failed++;
                lx_md(x, "\n**`sphlab bench ladder --quick` failed**, see `logs/%s`.\n\n", strrchr(lpath, '/') + 1);
            }
            bench_ladder_free(&lad);
        }
    }
    /* a picture */
    const char *psteps = x->quick ? "5" : "100";
    int rc = x->quick ? lx_sphlab(x, "render-block", NULL, NULL, NULL, "render", scene, "--out", work(x, "render"),
                                  "--steps", psteps, "--every", psteps, "--quiet", "--set", "fluid.spacing=0.04", "--set",
                                  "kernels.h=0.08", "--color", "neighbours", "--overlay", "hud,legend", "--size",
                                  "900x700", LX_END)
                      : lx_sphlab(x, "render-block", NULL, NULL, NULL, "render", scene, "--out", work(x, "render"),
                                  "--steps", psteps, "--every", psteps, "--quiet", "--color", "neighbours",
                                  "--overlay", "hud,legend", "--size", "900x700", LX_END);
    if (rc == 0 && lx_take(x, "render", "frame_00001.png", "block.png"))
        lx_fig(x, "block.png", lx_fmt("the block after %s steps, coloured by neighbour count", psteps));
    return 0;
}

/* ---- lesson 9: what accuracy costs ---------------------------------------------------------- */

typedef struct acc_run {
    double spacing, h_over_s, wall_s, rate, err;
    long n, steps;
    bool dbl, pareto;
} acc_run;

/* The study's CSV as a Markdown table: its knobs, error, time, front. */
static void study_table(lx *x, const char *csv)
{
    char *text = lx_read_file(csv);
    if (!text) {
        x->failed++;
        return;
    }
    char *lines[256];
    int nl = 0;
    for (char *l = strtok(text, "\n"); l && nl < 256; l = strtok(NULL, "\n")) lines[nl++] = l;
    char *hdr[64];
    int nh = nl ? split_csv(lines[0], hdr, 64) : 0;
    int c_part = -1, c_err = -1, c_ms = -1, c_s = -1, c_front = -1;
    for (int i = 0; i < nh; i++) {
        if (!strcmp(hdr[i], "particles")) c_part = i;
        if (!strcmp(hdr[i], "error")) c_err = i;
        if (!strcmp(hdr[i], "ms_per_step")) c_ms = i;
        if (!strcmp(hdr[i], "total_s")) c_s = i;
        if (!strcmp(hdr[i], "pareto")) c_front = i;
    }
    if (c_part < 1 || c_err < 0 || c_s < 0) {
        lx_md(x, "`%s`: not the columns expected (particles, error, total_s).\n\n", csv);
        free(text);
        return;
    }
    lx_md(x, "|");
    for (int i = 1; i < c_part; i++) lx_md(x, " %s |", hdr[i]);
    lx_md(x, " particles | error | ms/step | run [s] | Pareto front |\n|");
    for (int i = 1; i < c_part + 5; i++) lx_md(x, "---|");
    lx_md(x, "\n");
    for (int l = 1; l < nl; l++) {
        char *f[64];
        int nf = split_csv(lines[l], f, 64);
        if (nf != nh) continue;
        lx_md(x, "|");
        for (int i = 1; i < c_part; i++) lx_md(x, " %s |", f[i]);
        lx_md(x, " %s | %.2f%% | %.3f | %.3f | %s |\n", f[c_part], 100 * strtod(f[c_err], NULL),
              c_ms >= 0 ? strtod(f[c_ms], NULL) : NAN, strtod(f[c_s], NULL), c_front >= 0 && atoi(f[c_front]) ? "yes" : "");
    }
    lx_md(x, "\n");
    free(text);
}

int lx_lesson9(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!load_def(x, scene, &def)) return 1;
    const double nu = def.viscosity, L = def.domain_max[0] - def.domain_min[0], k = 2 * PI / L;
    const double rate0 = 2 * nu * k * k;
    pipeline(x, "lesson.ini", NULL, 0);

    lx_val(x, "study", "%s", lx_has_command(x, "study") ? "yes" : "");
    lx_val(x, "no_study", "%s", lx_has_command(x, "study") ? "" : "yes");
    if (lx_has_command(x, "study")) {
        /* the study: every combination, median of repeats, the Pareto front */
        static const struct {
            const char *name, *what;
            const char *args_quick[8], *args_full[8];
        } st[2] = {
            {"accuracy", "error against wall time of every combination of spacing and h / spacing (log-log), the "
                         "Pareto front marked",
             {"--vary", "fluid.spacing=0.04,0.02", "--vary", "h_over_spacing=2,3", "--repeats", "1", NULL},
             {"--vary", "fluid.spacing=0.04,0.025,0.02,0.0125", "--vary", "h_over_spacing=1.5,2,3", "--repeats", "3",
              NULL}},
            {"accuracy-precision", "float against double sums at one resolution (h = 2 spacings)",
             {"--vary", "physics.accumulate=float,double", "--set", "fluid.spacing=0.02", "--set", "kernels.h=0.04",
              "--repeats", "1"},
             {"--vary", "physics.accumulate=float,double", "--set", "fluid.spacing=0.0125", "--set", "kernels.h=0.025",
              "--repeats", "3"}},
        };
        for (int q = 0; q < 2; q++) {
            const char *args[32];
            int na = 0;
            args[na++] = "study";
            args[na++] = scene;
            for (int i = 0; i < 8 && (x->quick ? st[q].args_quick[i] : st[q].args_full[i]); i++)
                args[na++] = x->quick ? st[q].args_quick[i] : st[q].args_full[i];
            args[na++] = "--metric";
            args[na++] = "taylor-green";
            args[na++] = "--threads";
            args[na++] = "1";
            args[na++] = "--out";
            args[na++] = x->dir;
            args[na++] = "--name";
            args[na++] = st[q].name;
            args[na] = NULL;
            const char *log;
            if (lx_sphlab_v(x, lx_fmt("study-%s", st[q].name), NULL, NULL, &log, args) != 0) continue;
            char key[64];
            snprintf(key, sizeof key, "args_%s", st[q].name);
            lx_block(x, key);
            for (int i = 2; args[i]; i++) lx_md(x, "%s%s", i > 2 ? " " : "", args[i] == x->dir ? "DIR" : args[i]);
            snprintf(key, sizeof key, "table_%s", st[q].name);
            lx_block(x, key);
            lx_md_file(x, log, 40);
            study_table(x, lx_out(x, lx_fmt("%s.csv", st[q].name)));
            lx_block_end(x);
            lx_fig(x, lx_fmt("%s.png", st[q].name), lx_fmt("%s (PDF and CSV beside it)", st[q].what));
            lx_fig(x, lx_fmt("%s.csv", st[q].name), "one row per combination: knobs, error, ms per step, run time, "
                                                     "on the front or not");
        }
        return 0;
    }
    lx_missing(x, "`sphlab study` is not in this build (issue 5): no study CSV and no log-log chart with the "
                  "Pareto front; the table and chart below are a stand-in measured with `sphlab run`");

    lx_val(x, "nu", "%g", nu);
    lx_val(x, "length", "%g", L);
    lx_val(x, "rate", "%.4f", rate0);
    lx_val(x, "duration", "%g", def.duration);
    static const double sq[] = {0.04, 0.02}, sf[] = {0.04, 0.025, 0.02, 0.0125};
    static const double hq[] = {2, 3}, hf[] = {1.5, 2, 3};
    const double *sp = x->quick ? sq : sf, *hs = x->quick ? hq : hf;
    const int ns = x->quick ? 2 : 4, nh = x->quick ? 2 : 3;
    acc_run runs[16];
    int nr = 0;
    for (int a = 0; a < ns; a++)
        for (int b = 0; b < nh + 1 && nr < 16; b++) {
            bool dbl = b == nh;
            if (dbl && a != ns - 1) continue; /* double accumulation: only at the finest spacing, h = 2 s */
            double hos = dbl ? 2 : hs[b];
            acc_run *R = &runs[nr];
            memset(R, 0, sizeof *R);
            R->spacing = sp[a];
            R->h_over_s = hos;
            R->dbl = dbl;
            const char *stats = work(x, lx_fmt("acc-%d.csv", nr));
            lx_run r;
            lx_run_opts ro = {scene,
                              {lx_fmt("fluid.spacing=%g", sp[a]), lx_fmt("kernels.h=%g", hos * sp[a]),
                               lx_fmt("physics.accumulate=%s", dbl ? "double" : "float")},
                              -1, 1, stats, NULL};
            if (!lx_run_sim(x, lx_fmt("run-s%g-h%g%s", sp[a], hos, dbl ? "-double" : ""), &ro, &r) ||
                !decay_rate(x, stats, &R->rate, NULL))
                continue;
            R->wall_s = r.wall_s;
            R->n = r.particles;
            R->steps = r.steps;
            R->err = fabs(R->rate / rate0 - 1);
            nr++;
        }
    /* the Pareto front: no other run is both faster and more accurate */
    for (int i = 0; i < nr; i++) {
        runs[i].pareto = true;
        for (int j = 0; j < nr; j++)
            if (j != i && runs[j].wall_s <= runs[i].wall_s && runs[j].err < runs[i].err) runs[i].pareto = false;
    }
    lx_block(x, "runs_table");
    lx_md(x, "| spacing [m] | h / s | sums | particles | steps | wall time [s] | fitted rate [1/s] | error | Pareto "
             "front |\n|---|---|---|---|---|---|---|---|---|\n");
    FILE *f = lx_csv_open(x, "accuracy.csv");
    if (f) fprintf(f, "spacing,h_over_spacing,accumulate,particles,steps,wall_s,rate,analytic_rate,error_percent,pareto\n");
    for (int i = 0; i < nr; i++) {
        acc_run *R = &runs[i];
        lx_md(x, "| %g | %g | %s | %ld | %ld | %.3f | %.4f | %.2f%% | %s |\n", R->spacing, R->h_over_s,
              R->dbl ? "double" : "float", R->n, R->steps, R->wall_s, R->rate, 100 * R->err, R->pareto ? "yes" : "");
        if (f)
            fprintf(f, "%g,%g,%s,%ld,%ld,%.4f,%.6f,%.6f,%.4f,%d\n", R->spacing, R->h_over_s,
                    R->dbl ? "double" : "float", R->n, R->steps, R->wall_s, R->rate, rate0, 100 * R->err, R->pareto);
    }
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "accuracy.csv", "error and wall time of every run, and whether it is on the Pareto front");

    /* chart: one series per h/s (over spacing), plus the front */
    plot_lines C = {0};
    snprintf(C.title, sizeof C.title, "What accuracy costs: Taylor-Green decay rate error against wall time");
    snprintf(C.subtitle, sizeof C.subtitle, "sphlab run, one thread; each curve refines the spacing (%g to %g m)", sp[0],
             sp[ns - 1]);
    snprintf(C.xlabel, sizeof C.xlabel, "wall time [s]");
    C.np = 1;
    snprintf(C.p[0].ylabel, sizeof C.p[0].ylabel, "decay rate error [%%]");
    static double xv[5][16], yv[5][16];
    for (int b = 0; b < nh; b++) {
        plot_series *ps = &C.p[0].s[C.p[0].n];
        size_t m = 0;
        for (int i = 0; i < nr; i++)
            if (!runs[i].dbl && runs[i].h_over_s == hs[b]) {
                xv[b][m] = runs[i].wall_s;
                yv[b][m++] = 100 * runs[i].err;
            }
        if (!m) continue;
        snprintf(ps->label, sizeof ps->label, "h = %g spacings", hs[b]);
        ps->x = xv[b];
        ps->y = yv[b];
        ps->n = m;
        ps->style = b;
        C.p[0].n++;
    }
    /* the front, in order of time */
    size_t m = 0;
    for (int i = 0; i < nr; i++)
        if (runs[i].pareto) {
            size_t j = m++;
            while (j > 0 && xv[4][j - 1] > runs[i].wall_s) {
                xv[4][j] = xv[4][j - 1];
                yv[4][j] = yv[4][j - 1];
                j--;
            }
            xv[4][j] = runs[i].wall_s;
            yv[4][j] = 100 * runs[i].err;
        }
    if (m) C.p[0].s[C.p[0].n++] = (plot_series){"Pareto front", xv[4], yv[4], m, 6};
    if (nr >= 2) lx_chart(x, PLOT_LINES, &C, "accuracy", 1000, 650, "error against wall time of every run, with the "
                                                                    "Pareto front");
    return 0;
}
