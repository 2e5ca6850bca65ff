/* Lessons 1 and 2: the kernel estimate and what h does; density summation,
 * the free surface's deficit and the walls' share. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lesson_steps.h"
#include "sph_kernel.h"
#include "study.h"

/* ---- lesson 1: kernel estimation ------------------------------------------------- */

int lx_lesson1(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    const double s = def.blocks[0].spacing, h0 = def.h, rho0 = def.rest_density;
    lx_pipeline(x, "lesson.ini", NULL, 0);

    /* 1. the kernels */
    for (int dim = 2; dim <= 3; dim++)
        lx_plot(x, lx_fmt("plot-kernels-%dd", dim),
                &(plot_opts){.what = "kernels", .dim = dim, .h = h0, .out = x->dir, .quiet = true});
    lx_fig(x, "kernels-2d.png", "{{@the five kernels in 2D: W, dW/dr and the Laplacian against r/h (PDF and CSV "
                                "beside it)|les cinq noyaux en 2D : W, dW/dr et le laplacien en fonction de r/h "
                                "(PDF et CSV à côté)}}");
    lx_fig(x, "kernels-3d.png", "{{@the same in 3D|la même chose en 3D}}");
    lx_fig(x, "kernel-NAME-2d.png, kernel-NAME-3d.png",
           "{{@each kernel on its own, NAME = poly6, spiky, viscosity, cubic, wendland (PDF, CSV)|chaque noyau seul, "
           "NAME = poly6, spiky, viscosity, cubic, wendland (PDF, CSV)}}");
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
    /* sigma's unit is the kernel's: W = sigma f is 1/m^d, and f is (h^2 - r^2)^3 for poly6 (m^6), (h - r)^3 for
     * spiky, a function of r/h for the others: m^-8 for poly6 in 2D, not the m^-2 the column said. The power is
     * read off sigma itself (sigma ~ h^-p) */
    lx_md(x, "| {{@kernel|noyau}} | sigma 2D | sigma 3D | W(0) 2D [1/m^2] | {{@W(0) in "
             "kernels-2d.csv|W(0) dans kernels-2d.csv}} | M2 / h^2 (2D) |\n"
             "|---|---|---|---|---|---|\n");
    for (int k = 0; k < SPH_KERNEL_COUNT; k++) {
        sph_kernel k2 = sph_kernel_make((sph_kernel_kind)k, 2, (float)h0);
        sph_kernel k3 = sph_kernel_make((sph_kernel_kind)k, 3, (float)h0);
        sph_kernel d2 = sph_kernel_make((sph_kernel_kind)k, 2, (float)(2 * h0));
        sph_kernel d3 = sph_kernel_make((sph_kernel_kind)k, 3, (float)(2 * h0));
        const int p2 = (int)lround(log2(k2.sigma / d2.sigma)), p3 = (int)lround(log2(k3.sigma / d3.sigma));
        lx_md(x, "| %s | %.6g m^-%d | %.6g m^-%d | %.6g | %.6g | %.4f |\n", sph_kernel_names[k], k2.sigma, p2, k3.sigma,
              p3, sph_kernel_w(&k2, 0.0f), w0_csv[k], k2.m2 / (h0 * h0));
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
            const char *name;
            int dim;
            study_samples samples;
            const char *nq, *nf; /* the --n lists of --quick and of a full export */
            double q[3], full[3];
            int nnq, nnf;
            const char *what, *what_fr;
        } est[3] = {
            {"estimate-1d", 1, STUDY_SAMPLES_RANDOM, "100,1000", "100,1000,10000", {100, 1000}, {100, 1000, 10000}, 2,
             3,
             "1D: error of the estimate of sin(2 pi x) from n random samples against h (log-log), with the "
             "predicted bias",
             "1D : erreur de l'estimation de sin(2 pi x) par n échantillons aléatoires en fonction de h (log-log), "
             "avec le biais prédit"},
            {"estimate-2d", 2, STUDY_SAMPLES_JITTER, "50,100", "50,100,200", {50, 100}, {50, 100, 200}, 2, 3,
             "2D: the same from a lattice jittered by 0.3 spacing, n x n samples",
             "2D : la même chose sur un réseau perturbé de 0.3 pas, n x n échantillons"},
            {"estimate-2d-lattice", 2, STUDY_SAMPLES_LATTICE, "50,100", "50,100,200", {50, 100}, {50, 100, 200}, 2, 3,
             "2D: the same from a perfect lattice: no noise, only the bias",
             "2D : la même chose sur un réseau parfait : pas de bruit, seulement le biais"},
        };
        for (int e = 0; e < 3; e++) {
            /* `sphlab estimate --dim D --samples S --n N --out DIR --name NAME --quiet`, in process */
            const char *argv[] = {"sphlab", "estimate", "--dim", est[e].dim == 1 ? "1" : "2", "--samples",
                                  study_samples_names[est[e].samples], "--n", x->quick ? est[e].nq : est[e].nf,
                                  "--out", x->dir, "--name", est[e].name, NULL};
            const char *log_path;
            FILE *lf = lx_log_open(x, est[e].name, argv, &log_path);
            if (lf) fclose(lf);
            study_est_opts eo = {est[e].dim, STUDY_FN_SIN, SPH_KERNEL_POLY6, est[e].samples, 0.3, 1};
            if (study_estimate_write(&eo, NULL, 0, x->quick ? est[e].q : est[e].full, x->quick ? est[e].nnq : est[e].nnf,
                                     x->dir, est[e].name, true) != 0) {
                x->failed++;
                lx_md(x, "\n**`sphlab estimate` failed** for `%s`.\n\n", est[e].name);
                continue;
            }
            lx_fig(x, lx_fmt("%s.png", est[e].name),
                   lx_fmt("{{@%s (PDF and CSV beside it)|%s (PDF et CSV à côté)}}", est[e].what, est[e].what_fr));
            plot_table t;
            if (!lx_table(x, &t, lx_out(x, lx_fmt("%s.csv", est[e].name)))) continue;
            const double *n = lx_col(x, &t, "n"), *h = lx_col(x, &t, "h"), *hs = lx_col(x, &t, "h_over_spacing"),
                         *nb = lx_col(x, &t, "neighbours"), *err = lx_col(x, &t, "error"),
                         *bias = lx_col(x, &t, "bias_predicted");
            if (n && h && hs && nb && err && bias) {
                lx_md(x, "`sphlab estimate --dim %d --samples %s` (%s){{@: for each sample count, the error at each h "
                         "and the best h| : pour chaque nombre d'échantillons, l'erreur à chaque h et le meilleur h}}."
                         "\n\n| n | h | {{@h / spacing|h / espacement}} | {{@neighbours|voisins}} | "
                         "{{@rms error|erreur rms}} | {{@predicted bias|biais prédit}} |\n|---|---|---|---|---|---|\n",
                      est[e].dim, study_samples_names[est[e].samples], est[e].name);
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
    lx_md(x, "| {{@h / spacing|h / espacement}} | h [m] | {{@interior mean [kg/m^2]|moyenne intérieure [kg/m^2]}} | "
             "{{@interior rms error|erreur rms intérieure}} | {{@top row mean [kg/m^2]|moyenne de la rangée du haut "
             "[kg/m^2]}} | {{@top row deficit|déficit de la rangée du haut}} |\n"
             "|---|---|---|---|---|---|\n");
    int good = 0;
    for (int k = 0; k < nhl; k++) {
        double h = hl[k] * s;
        const char *dpath = lx_work(x, lx_fmt("density-h%g.csv", hl[k]));
        if (!lx_run_sim(x, lx_fmt("run-h%g", hl[k]),
                        &(lx_run_opts){scene, {lx_fmt("kernels.h=%g", h)}, 1, 1, NULL, dpath}, NULL))
            continue;
        lx_dump d;
        if (!lx_read_dump(x, dpath, &d)) continue;
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
    if (f)
        lx_csv_close(x, f, "density-vs-h.csv",
                     "{{@the slab's interior noise and surface deficit against h|le bruit intérieur de la tranche et "
                     "son déficit en surface en fonction de h}}");
    plot_lines L3 = {0};
    snprintf(L3.title, sizeof L3.title, "Density of a jittered slab: noise inside, deficit at the surface");
    snprintf(L3.subtitle, sizeof L3.subtitle, "sphlab run lesson.ini --steps 1 --set kernels.h=H; jitter 0.3 spacing");
    snprintf(L3.xlabel, sizeof L3.xlabel, "h / spacing [-]");
    L3.np = 1;
    snprintf(L3.p[0].ylabel, sizeof L3.p[0].ylabel, "density error [%%]");
    L3.p[0].n = 2;
    L3.p[0].s[0] = (plot_series){"interior rms error", xs, noise, (size_t)good, 0, false};
    L3.p[0].s[1] = (plot_series){"top row deficit", xs, deficit, (size_t)good, 1, false};
    lx_chart(x, PLOT_LINES, &L3, "density-vs-h", 1000, 650,
             "{{@the slab's interior noise and surface deficit against h|le bruit intérieur de la tranche et son "
             "déficit en surface en fonction de h}}");

    /* 4. two pictures */
    const double pics[2] = {1.5, 4};
    for (int k = 0; k < 2; k++) {
        const char *sub = lx_fmt("render-h%g", pics[k]);
        /* frames come from `sphlab render` in a child process: its GL context and the
         * software rendering that keeps frames byte-identical are set up per process */
        if (lx_sphlab(x, sub, NULL, NULL, NULL, "render", scene, "--out", lx_work(x, sub), "--steps", "1", "--every", "1",
                      "--threads", "1", "--quiet", "--set", lx_fmt("kernels.h=%g", pics[k] * s), "--color", "density",
                      "--range", "600:1400", "--overlay", "neighbours,hud,legend", "--select", "625", "--size",
                      "900x650", LX_END) == 0 &&
            lx_take(x, sub, "frame_00001.png", lx_fmt("density-h%g.png", pics[k])))
            lx_fig(x, lx_fmt("density-h%g.png", pics[k]),
                   /* the whole slab, where the surfaces' dark bands show: too small for the weights' labels,
                    * which the window shows zoomed in (the caption promised them) */
                   lx_fmt("{{@the slab coloured by density (600 to 1400 kg/m^2) with h = %g spacings, particle 625's "
                          "neighbours (their weights show when zoomed in, in the window)|la tranche colorée par la "
                          "densité (600 à 1400 kg/m^2) avec h = %g espacements, les voisins de la particule 625 (leurs "
                          "poids s'affichent en zoomant, dans la fenêtre)}}",
                          pics[k], pics[k]));
    }
    return 0;
}

/* ---- lesson 2: density summation ---------------------------------------------------- */

int lx_lesson2(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    const double s = def.blocks[0].spacing, h0 = def.h, rho0 = def.rest_density;
    const int cols = (int)sph_block_nodes(&def, 0, 0), rows = (int)sph_block_nodes(&def, 0, 1);
    lx_pipeline(x, "lesson.ini", NULL, 0);

    static const struct {
        const char *name, *name_fr; /* the CSV's and the English report's; the French report's */
        int col, row;               /* -1: last */
    } spot[] = {
        {"interior", "intérieur", -2, -3},
        {"top (free surface)", "haut (surface libre)", -2, -1},
        {"right side (free surface)", "côté droit (surface libre)", -1, -3},
        {"floor (wall)", "fond (paroi)", -2, 0},
        {"left side (wall)", "côté gauche (paroi)", 0, -3},
        {"corner floor / left wall", "coin fond / paroi gauche", 0, 0},
        {"corner top / right (free)", "coin haut / droite (libre)", -1, -1},
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
            const char *dpath = lx_work(x, lx_fmt("d-%s-%g.csv", models[m], hl[k]));
            if (!lx_run_sim(x, lx_fmt("run-%s-h%g", models[m], hl[k]),
                            &(lx_run_opts){scene,
                                           {lx_fmt("domain.wall_model=%s", models[m]), lx_fmt("kernels.h=%g", h)},
                                           1, 1, NULL, dpath},
                            NULL))
                continue;
            lx_dump d;
            if (!lx_read_dump(x, dpath, &d)) continue;
            vmin[m][k] = INFINITY;
            vmax[m][k] = -INFINITY;
            for (size_t i = 0; i < d.n; i++) {
                vmin[m][k] = fmin(vmin[m][k], d.rho[i]);
                vmax[m][k] = fmax(vmax[m][k], d.rho[i]);
            }
            for (int q = 0; q < NSPOT; q++) {
                int col = spot[q].col == -1 ? cols - 1 : spot[q].col == -2 ? cols / 2 : spot[q].col;
                int row = spot[q].row == -1 ? rows - 1 : spot[q].row == -3 ? rows / 2 : spot[q].row;
                val[m][k][q] = lx_at_id(&d, d.rho, lx_lattice_id(&def, col, row));
            }
            if (fabs(h - h0) < 1e-9)
                for (int r = 0; r < nprof; r++) {
                    prof_y[r] = lx_at_id(&d, d.y, lx_lattice_id(&def, cols / 2, r));
                    prof[m][r] = lx_at_id(&d, d.rho, lx_lattice_id(&def, cols / 2, r));
                }
            ok[m][k] = true;
            plot_table_free(&d.t);
        }
    lx_val(x, "cols", "%d", cols);
    lx_val(x, "rows", "%d", rows);
    lx_val(x, "spacing", "%g", s);
    lx_val(x, "rho0", "%g", rho0);
    lx_block(x, "points_table");
    lx_md(x, "| {{@particle|particule}} |");
    for (int m = 0; m < 2; m++)
        for (int k = 0; k < nh; k++) lx_md(x, " %s, h = %g {{@spacings|espacements}} |", models[m], hl[k]);
    lx_md(x, "\n|---|");
    for (int i = 0; i < 2 * nh; i++) lx_md(x, "---|");
    lx_md(x, "\n");
    FILE *f = lx_csv_open(x, "density-points.csv");
    if (f) fprintf(f, "wall_model,h_over_spacing,particle,rho,error_percent\n");
    for (int q = 0; q < NSPOT + 2; q++) {
        lx_md(x, "| %s |", q < NSPOT    ? lx_fmt("{{@%s|%s}}", spot[q].name, spot[q].name_fr)
                           : q == NSPOT ? "{{@lowest density|densité la plus basse}}"
                                        : "{{@highest density|densité la plus haute}}");
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
    if (f)
        lx_csv_close(x, f, "density-points.csv",
                     "{{@the density at the interior, surfaces, walls and corners|la densité à l'intérieur, aux "
                     "surfaces, aux parois et aux coins}}");

    /* the profile up the middle column */
    f = lx_csv_open(x, "density-profile.csv");
    if (f) {
        fprintf(f, "y,rho_volume,rho_reflect\n");
        for (int r = 0; r < nprof; r++) fprintf(f, "%.4f,%.3f,%.3f\n", prof_y[r], prof[0][r], prof[1][r]);
        lx_csv_close(x, f, "density-profile.csv",
                     "{{@the density up the middle column, both wall models|la densité le long de la colonne du "
                     "milieu, les deux modèles de paroi}}");
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
    L.p[0].s[0] = (plot_series){"walls count (volume)", prof_y, prof[0], (size_t)nprof, 0, false};
    L.p[0].s[1] = (plot_series){"reflect only (the seed)", prof_y, prof[1], (size_t)nprof, 1, false};
    L.p[0].s[2] = (plot_series){"rest density", prof_y, flat, (size_t)nprof, 6, false};
    lx_chart(x, PLOT_LINES, &L, "density-profile", 1000, 650,
             "{{@the density up the middle column, with and without the walls' share|la densité le long de la "
             "colonne du milieu, avec et sans la part des parois}}");

    /* 2. the walls decide whether a pool can rest */
    const char *pool = lx_src(x, "pool.ini");
    plot_table pt[2];
    bool pok[2] = {false, false};
    for (int m = 0; m < 2; m++) {
        char stats[1100], set[64];
        snprintf(stats, sizeof stats, "%s", lx_work(x, lx_fmt("pool-%s.csv", models[m])));
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
            P.p[0].s[0] = (plot_series){"walls count (volume)", t0, e0, pt[0].nrows, 0, false};
            P.p[0].s[1] = (plot_series){"reflect only (the seed)", t1, e1, pt[1].nrows, 1, false};
            lx_chart(x, PLOT_LINES, &P, "pool-walls", 1000, 600,
                     "{{@a pool at rest: kinetic energy over time with volume walls and with the seed's reflecting "
                     "walls|un bassin au repos : énergie cinétique au cours du temps avec les parois volume et avec "
                     "les parois réfléchissantes du TIPE}}");
            /* the chart's data beside it, as every chart's (the runs' own stats stay in the work folder) */
            FILE *pw = lx_csv_open(x, "pool-walls.csv");
            if (pw) {
                fprintf(pw, "wall_model,t,ekin,max_speed\n");
                for (size_t i = 0; i < pt[0].nrows; i++) fprintf(pw, "volume,%.6g,%.6g,%.6g\n", t0[i], e0[i], v0[i]);
                for (size_t i = 0; i < pt[1].nrows; i++) fprintf(pw, "reflect,%.6g,%.6g,%.6g\n", t1[i], e1[i], v1[i]);
                lx_csv_close(x, pw, "pool-walls.csv",
                             "{{@the pool's kinetic energy [J/m] and largest speed [m/s] at each step, both wall "
                             "models|l'énergie cinétique [J/m] et la plus grande vitesse [m/s] du bassin à chaque pas, "
                             "les deux modèles de paroi}}");
            }
            size_t a = pt[0].nrows - 1, b = pt[1].nrows - 1;
            /* each run's own end: a run of --quick's steps ends at another t with each wall model */
            lx_val(x, "pool_t", "%.3g", t0[a]);
            lx_val(x, "pool_t_reflect", "%.3g", t1[b]);
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
        if (lx_sphlab(x, sub, NULL, NULL, NULL, "render", scene, "--out", lx_work(x, sub), "--steps", "1", "--every", "1",
                      "--threads", "1", "--quiet", "--set", lx_fmt("domain.wall_model=%s", models[m]), "--color",
                      "density", "--range", "600:1100", "--overlay", "grid,neighbours,hud,legend", "--select",
                      lx_fmt("%u", lx_lattice_id(&def, cols / 2, rows - 1)), "--size", "1000x640", LX_END) == 0 &&
            lx_take(x, sub, "frame_00001.png", name))
            lx_fig(x, name,
                   lx_fmt("{{@the block coloured by density (600 to 1100 kg/m^2), %s walls, the search grid and the "
                          "neighbours of a particle of the top row|le bloc coloré par la densité (600 à 1100 kg/m^2), "
                          "parois %s, la grille de recherche et les voisins d'une particule de la rangée du haut}}",
                          models[m], models[m]));
    }
    return 0;
}
