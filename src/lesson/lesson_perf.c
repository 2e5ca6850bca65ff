/* Lessons 7 to 9: where the time of a full simulation goes, the
 * optimisation ladder (through the bench module), and what accuracy costs
 * (through the study module, study_cmd_run). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "bench_cmd.h"
#include "lesson_steps.h"
#include "study_cmd.h"

/* ---- lesson 7: the full simulation --------------------------------------------------------- */

int lx_lesson7(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    char passes[SPH_PASS_COUNT][24];
    int np = lx_pipeline(x, "lesson.ini", passes, SPH_PASS_COUNT);

    /* 1. the run, with per-step statistics */
    lx_run r;
    if (!lx_run_sim(x, "run", &(lx_run_opts){scene, {NULL}, x->quick ? 200 : -1, 0, lx_out(x, "stats.csv"),
                                            lx_out(x, "final.csv")},
                    &r))
        return 1;
    int rc;
    lx_fig(x, "stats.csv", "{{@one row per step: t, dt, energy, density, max speed, ms of each pass|une ligne par "
                           "pas : t, dt, énergie, densité, vitesse maximale, ms de chaque passe}}");
    lx_fig(x, "final.csv", "{{@the particles at the end: id, position, velocity, density, pressure|les particules à la "
                           "fin : id, position, vitesse, densité, pression}}");
    lx_val(x, "particles", "%ld", r.particles);
    lx_val(x, "steps", "%ld", r.steps);
    lx_val(x, "t_sim", "%.3f", r.t_sim);
    lx_val(x, "threads", "%d", r.threads);
    lx_block(x, "passes_table");
    /* the mean over the run's steps (its total over its steps): passes.png and the README give medians, which a
     * stalled step moves less; said in the header (a review compared 0.183 with 0.091 ms unlabelled) */
    lx_md(x, "| {{@pass|passe}} | {{@ms/step, mean over the run|ms/pas, moyenne sur le calcul}} | {{@share|part}} "
             "|\n|---|---|---|\n");
    int top = 0;
    for (int i = 0; i < r.npass; i++) {
        lx_md(x, "| %s | %.4f | %.1f%% |\n", r.pass[i], r.ms_step[i], r.share[i]);
        if (r.ms_step[i] > r.ms_step[top]) top = i;
    }
    lx_md(x, "| {{@all passes|toutes les passes}} | %.4f | 100%% |\n", r.total_ms_step);
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

    if (lx_plot(x, "plot-passes",
                &(plot_opts){.what = "passes", .input = lx_out(x, "stats.csv"), .out = x->dir, .quiet = true})) {
        lx_fig(x, "passes.png", "{{@median milliseconds per step of each pass (PDF, CSV beside it)|millisecondes "
                                "médianes par pas de chaque passe (PDF, CSV à côté)}}");
        lx_fig(x, "passes-time.png", "{{@the passes' time stacked over the run (PDF, CSV beside it)|le temps des "
                                     "passes "
                                     "empilé au cours du calcul (PDF, CSV à côté)}}");
    }
    if (lx_plot(x, "plot-series",
                &(plot_opts){.what = "series", .input = lx_out(x, "stats.csv"), .ycols = "ekin,rho_min,rho_mean,rho_max",
                             .dim = 2, .name = "energy-density", .out = x->dir, .quiet = true}))
        lx_fig(x, "energy-density.png", "{{@kinetic energy and density (min, mean, max) over time (PDF, CSV beside "
                                        "it)|énergie cinétique et densité (min, moyenne, max) au cours du temps (PDF, "
                                        "CSV à côté)}}");

    /* 2. the dam break over time */
    const char *every = x->quick ? "50" : "400";
    /* frames come from `sphlab render` in a child process: its GL context and the
     * software rendering that keeps frames byte-identical are set up per process */
    rc = x->quick ? lx_sphlab(x, "render-frames", NULL, NULL, NULL, "render", scene, "--out", lx_work(x, "frames"),
                              "--steps", "100", "--every", every, "--quiet", "--color", "speed", "--range", "0:4",
                              "--overlay", "hud,legend", "--size", "960x520", LX_END)
                  : lx_sphlab(x, "render-frames", NULL, NULL, NULL, "render", scene, "--out", lx_work(x, "frames"),
                              "--every", every, "--quiet", "--color", "speed", "--range", "0:4", "--overlay",
                              "hud,legend", "--size", "960x520", LX_END);
    if (rc == 0) {
        int nf = lx_take_all(x, "frames");
        lx_fig(x, "frames/frame_NNNNN.png", lx_fmt("{{@%d frames of the dam break, one every %s steps, coloured by "
                                                   "speed (0 to 4 m/s)|%d images de la rupture de barrage, une tous "
                                                   "les %s pas, colorées par la vitesse (0 à 4 m/s)}}",
                                                   nf, every, nf, every));
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
    const char *cwd = lx_work(x, "view");
    sph_mkdir_p(cwd, NULL, 0);
    if (lx_sphlab(x, "view-passes", cwd, "SDL_VIDEODRIVER=offscreen", NULL, "view", lx_abs(scene), "--steps-per-frame", before,
                  "--frames", lx_fmt("%d", 1 + 2 * np), "--keys", keys, "--threads", "1", "--color", "speed",
                  "--overlay", "hud,legend", "--size", "960x560", LX_END) == 0) {
        for (int i = 0; i < np; i++) {
            const char *name = lx_fmt("pass-%02d-%s.png", i + 1, passes[i]);
            if (lx_take(x, "view", lx_fmt("sphlab-%04d.png", i), name))
                lx_fig(x, name, lx_fmt("{{@after the %s pass of the step after the first %s (the window recolours "
                                       "by the field the pass wrote; the HUD names it)|après la passe %s du pas qui "
                                       "suit les %s premiers (la fenêtre recolore selon le champ que la passe a écrit "
                                       "; l'affichage le nomme)}}",
                                       passes[i], before, passes[i], before));
        }
        lx_val(x, "view_before", "%s", before);
    }
    return 0;
}

/* ---- lesson 8: the optimisation ladder ------------------------------------------------------ */

/* The ladder's results as a Markdown table, from bench_ladder_measure's struct. */
static void ladder_table(lx *x, const bench_opts *o, const bench_ladder *lad)
{
    lx_block(x, "ladder_table");
    lx_md(x, "| {{@level|niveau}} | {{@what|ce qu'il fait}} | threads | {{@largest N at 60 steps/s|plus grand N à 60 "
             "pas/s}} | {{@ms/step at the table's N|ms/pas au N du tableau}} |\n|---|---|---|---|---|\n");
    for (int s = 0; s < o->nsel; s++) {
        const bench_level *L = &bench_levels[o->sel[s]];
        const level_result *r = &lad->res[s];
        lx_md(x, "| %s | {{@%s|%s}} | %d | %s%s | %s%s |\n", L->name, L->about, L->about_fr, r->at.threads ? r->at.threads : L->threads,
              r->searched ? lx_fmt("%.0f", r->max_n) : "", r->capped ? " (capped)" : "",
              r->at_ok ? lx_fmt("%.6g", r->at.ms_step) : "", r->at_ok ? lx_fmt(" (N = %u)", r->at.n) : "");
    }
    lx_block_end(x);
}

int lx_lesson8(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    lx_pipeline(x, "lesson.ini", NULL, 0);
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
        double ms[BENCH_MAX_LEVELS], nbm[BENCH_MAX_LEVELS]; /* one per CPU level (lv[], at most that many) */
        long N = 0;
        lx_val(x, "steps", "%s", steps);
        lx_val(x, "spacing_sets", "%s", spacing ? " --set fluid.spacing=0.04 --set kernels.h=0.08" : "");
        lx_block(x, "levels_table");
        lx_md(x, "| {{@level|niveau}} | {{@what|ce qu'il fait}} | threads | {{@ms/step|ms/pas}} | {{@neighbours "
                 "[ms]|voisins [ms]}} | {{@speedup over L0|gain sur L0}} | {{@over the level before|sur le niveau "
                 "précédent}} | "
                 "{{@steps/s|pas/s}} | {{@60 steps/s?|60 pas/s ?}} |\n|---|---|---|---|---|---|---|---|---|\n");
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
            if (*k0) { /* keys left over: the run would not be the level it is labelled; a row of the table says so */
                x->failed++;
                lx_md(x, "| %s | {{@%s|%s}} | - | - | - | - | - | - | {{@not run: more keys than a run takes (%d)|non "
                         "lancé : plus de clés qu'un lancement n'en prend (%d)}} |\n",
                      L->name, L->about, L->about_fr, LX_RUN_MAX_SETS - 1, LX_RUN_MAX_SETS - 1);
                ms[i] = NAN;
                continue;
            }
            if (!lx_run_sim(x, lx_fmt("run-%s", L->name), &ro, &r)) {
                ms[i] = NAN;
                continue;
            }
            ms[i] = r.total_ms_step;
            nbm[i] = lx_run_pass(&r, "neighbours");
            N = r.particles;
            double sp0 = ms[0] / ms[i], spp = i ? ms[i - 1] / ms[i] : 1;
            lx_md(x, "| %s | {{@%s|%s}} | %d | %.3f | %.3f | %.2f | %.2f | %.0f | %s |\n", L->name, L->about, L->about_fr,
                  r.threads,
                  ms[i], nbm[i], sp0, spp, 1000 / ms[i], 1000 / ms[i] >= 60 ? "{{@yes|oui}}" : "{{@no|non}}");
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
        if (f) lx_csv_close(x, f, "levels.csv",
                                "{{@milliseconds per step of each level on the lesson's scene|millisecondes "
                                         "par pas de chaque niveau sur la scène de la leçon}}");
        if (good) {
            snprintf(B.title, sizeof B.title, "The optimisation ladder on %ld particles (3D)", N);
            snprintf(B.subtitle, sizeof B.subtitle, "sphlab run lesson.ini --steps %s with each level's keys; "
                                                    "speedup over L0",
                     steps);
            snprintf(B.xlabel, sizeof B.xlabel, "time per step [ms]");
            lx_chart(x, PLOT_BARS, &B, "levels", 1000, 600,
                     "{{@milliseconds per step of each level, with its speedup|millisecondes par pas de chaque "
                     "niveau, avec son accélération}}");
        }
        /* 3. the ladder: the largest N at 60 steps/s */
        lx_val(x, "ladder_skipped", "%s", x->quick ? "yes" : "");
        lx_val(x, "ladder_table", "%s", "");
        if (x->quick) { /* a full export's ladder in the same folder would read as this one's, which measured none */
            const char *old[4] = {"png", "pdf", "csv", "json"};
            for (int k = 0; k < 4; k++) unlink(lx_out(x, lx_fmt("ladder-3d.%s", old[k])));
        }
        if (!x->quick) {
            /* `sphlab bench ladder --quick --out DIR/.work/bench`, in process: its
             * measurements come back in a struct, its files are its own */
            bench_opts lo;
            bench_opts_init(&lo, true);
            lo.quiet = true;
            lo.out = lx_work(x, "bench");
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
                               k == 0 ? "sphlab bench ladder --quick{{@: the largest N at 60 steps/s per level| : le "
                                        "plus grand N à 60 pas/s par niveau}}"
                                      : "{{@the same (PDF, CSV, JSON)|la même chose (PDF, CSV, JSON)}}");
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
    int rc = x->quick ? lx_sphlab(x, "render-block", NULL, NULL, NULL, "render", scene, "--out", lx_work(x, "render"),
                                  "--steps", psteps, "--every", psteps, "--quiet", "--set", "fluid.spacing=0.04", "--set",
                                  "kernels.h=0.08", "--color", "neighbours", "--overlay", "hud,legend", "--size",
                                  "900x700", LX_END)
                      : lx_sphlab(x, "render-block", NULL, NULL, NULL, "render", scene, "--out", lx_work(x, "render"),
                                  "--steps", psteps, "--every", psteps, "--quiet", "--color", "neighbours",
                                  "--overlay", "hud,legend", "--size", "900x700", LX_END);
    if (rc == 0 && lx_take(x, "render", "frame_00001.png", "block.png"))
        lx_fig(x, "block.png", lx_fmt("{{@the block after %s steps, coloured by neighbour count|le bloc après %s pas, "
                                      "coloré par le nombre de voisins}}",
                                      psteps, psteps));
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
    int nh = nl ? lx_split_csv(lines[0], hdr, 64) : 0;
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
    lx_md(x, " {{@particles|particules}} | {{@error|erreur}} | {{@ms/step|ms/pas}} | {{@run [s]|calcul [s]}} | "
             "{{@Pareto front|front de Pareto}} |\n|");
    for (int i = 1; i < c_part + 5; i++) lx_md(x, "---|");
    lx_md(x, "\n");
    for (int l = 1; l < nl; l++) {
        char *f[64];
        int nf = lx_split_csv(lines[l], f, 64);
        if (nf != nh) continue;
        lx_md(x, "|");
        for (int i = 1; i < c_part; i++) lx_md(x, " %s |", f[i]);
        lx_md(x, " %s | %.2f%% | %.3f | %.3f | %s |\n", f[c_part], 100 * strtod(f[c_err], NULL),
              c_ms >= 0 ? strtod(f[c_ms], NULL) : NAN, strtod(f[c_s], NULL),
              c_front >= 0 && atoi(f[c_front]) ? "{{@yes|oui}}" : "");
    }
    lx_md(x, "\n");
    free(text);
}

int lx_lesson9(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    const double nu = def.viscosity, L = def.domain_max[0] - def.domain_min[0], k = 2 * PI / L;
    const double rate0 = 2 * nu * k * k;
    lx_pipeline(x, "lesson.ini", NULL, 0);

    lx_val(x, "study", "%s", lx_has_command(x, "study") ? "yes" : "");
    lx_val(x, "no_study", "%s", lx_has_command(x, "study") ? "" : "yes");
    if (lx_has_command(x, "study")) {
        /* the study: every combination, median of repeats, the Pareto front */
        static const struct {
            const char *name, *what, *what_fr;
            const char *args_quick[8], *args_full[8];
        } st[2] = {
            {"accuracy", "error against wall time of every combination of spacing and h / spacing (log-log), the "
                         "Pareto front marked",
             "l'erreur contre le temps de calcul de chaque combinaison de l'espacement et de h / espacement "
             "(log-log), le front de Pareto marqué",
             {"--vary", "fluid.spacing=0.04,0.02", "--vary", "h_over_spacing=2,3", "--repeats", "1", NULL},
             {"--vary", "fluid.spacing=0.04,0.025,0.02,0.0125", "--vary", "h_over_spacing=1.5,2,3", "--repeats", "3",
              NULL}},
            {"accuracy-precision", "float against double sums at one resolution (h = 2 spacings)",
             "sommes en float contre double à une résolution (h = 2 espacements)",
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
            /* `sphlab study ...` in process: the same knobs, its table into the log and the report */
            const char *argv[34] = {"sphlab"};
            for (int i = 0; args[i] && i < 32; i++) argv[i + 1] = args[i];
            const char *log;
            FILE *lf = lx_log_open(x, lx_fmt("study-%s", st[q].name), argv, &log);
            study_cmd sc = {.scene = {.path = scene}, .out = x->dir, .metric = "taylor-green", .base = st[q].name,
                            .repeats = 3, .steps = -1, .threads = 1, .until = -1, .quiet = true};
            char why[256] = "";
            bool planned = true;
            for (int i = 2; args[i] && args[i + 1]; i += 2) {
                if (strcmp(args[i], "--vary") == 0) planned &= study_plan_add(&sc.plan, args[i + 1], why, sizeof why);
                else if (strcmp(args[i], "--set") == 0) planned &= app_scene_add_set(&sc.scene, args[i + 1]);
                else if (strcmp(args[i], "--repeats") == 0) sc.repeats = atol(args[i + 1]);
            }
            char *text = NULL;
            size_t tlen = 0;
            sc.table = open_memstream(&text, &tlen);
            int src = planned && sc.table ? study_cmd_run(&sc) : 2;
            if (sc.table) fclose(sc.table);
            if (lf) {
                fputs(text ? text : "", lf);
                fclose(lf);
            }
            if (src != 0) {
                x->failed++;
                lx_md(x, "\n**`sphlab study` failed** (exit %d%s%s), see `logs/%s`.\n\n", src, why[0] ? ": " : "", why,
                      strrchr(log, '/') + 1);
                free(text);
                continue;
            }
            char key[64];
            snprintf(key, sizeof key, "args_%s", st[q].name);
            lx_block(x, key);
            for (int i = 2; args[i]; i++) lx_md(x, "%s%s", i > 2 ? " " : "", args[i] == x->dir ? "DIR" : args[i]);
            snprintf(key, sizeof key, "table_%s", st[q].name);
            lx_block(x, key);
            lx_md_text(x, text ? text : "", 40);
            free(text);
            study_table(x, lx_out(x, lx_fmt("%s.csv", st[q].name)));
            lx_block_end(x);
            lx_fig(x, lx_fmt("%s.png", st[q].name), lx_fmt("{{@%s|%s}}", st[q].what, st[q].what_fr));
            lx_fig(x, lx_fmt("%s.pdf", st[q].name), "{{@the same chart as PDF|le même graphique en PDF}}");
            lx_fig(x, lx_fmt("%s.csv", st[q].name), "{{@one row per combination: knobs, error, ms per step, run "
                                                     "time, on the front or not|une ligne par combinaison : réglages, "
                                                     "erreur, ms par pas, durée du calcul, sur le front ou non}}");
        }
        return 0;
    }
    lx_missing(x, "`sphlab study` is not in this build: no study CSV and no log-log chart with the "
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
            const char *stats = lx_work(x, lx_fmt("acc-%d.csv", nr));
            lx_run r;
            lx_run_opts ro = {scene,
                              {lx_fmt("fluid.spacing=%g", sp[a]), lx_fmt("kernels.h=%g", hos * sp[a]),
                               lx_fmt("physics.accumulate=%s", dbl ? "double" : "float")},
                              -1, 1, stats, NULL};
            if (!lx_run_sim(x, lx_fmt("run-s%g-h%g%s", sp[a], hos, dbl ? "-double" : ""), &ro, &r) ||
                !lx_decay_rate(x, stats, &R->rate, NULL))
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
    lx_md(x, "| {{@spacing [m]|espacement [m]}} | {{@h / spacing|h / espacement}} | {{@sums|sommes}} | "
             "{{@particles|particules}} | {{@steps|pas}} | {{@wall time [s]|temps écoulé [s]}} | "
             "{{@fitted rate [1/s]|taux ajusté [1/s]}} | {{@error|erreur}} | {{@Pareto front|front de Pareto}} "
             "|\n|---|---|---|---|---|---|---|---|---|\n");
    FILE *f = lx_csv_open(x, "accuracy.csv");
    if (f) fprintf(f, "spacing,h_over_spacing,accumulate,particles,steps,wall_s,rate,analytic_rate,error_percent,pareto\n");
    for (int i = 0; i < nr; i++) {
        acc_run *R = &runs[i];
        lx_md(x, "| %g | %g | %s | %ld | %ld | %.3f | %.4f | %.2f%% | %s |\n", R->spacing, R->h_over_s,
              R->dbl ? "double" : "float", R->n, R->steps, R->wall_s, R->rate, 100 * R->err,
              R->pareto ? "{{@yes|oui}}" : "");
        if (f)
            fprintf(f, "%g,%g,%s,%ld,%ld,%.4f,%.6f,%.6f,%.4f,%d\n", R->spacing, R->h_over_s,
                    R->dbl ? "double" : "float", R->n, R->steps, R->wall_s, R->rate, rate0, 100 * R->err, R->pareto);
    }
    lx_block_end(x);
    if (f)
        lx_csv_close(x, f, "accuracy.csv",
                     "{{@error and wall time of every run, and whether it is on the Pareto front|erreur et temps de "
                     "calcul de chaque calcul, et s'il est sur le front de Pareto}}");

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
    if (m) C.p[0].s[C.p[0].n++] = (plot_series){"Pareto front", xv[4], yv[4], m, 6, false};
    if (nr >= 2)
        lx_chart(x, PLOT_LINES, &C, "accuracy", 1000, 650,
                 "{{@error against wall time of every run, with the Pareto front|l'erreur en fonction du temps de "
                 "calcul de chaque calcul, avec le front de Pareto}}");
    return 0;
}
#include "../io/io.h"
