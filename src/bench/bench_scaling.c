/* sphlab bench scaling: time per step against N for each level (log-log),
 * the slope of each (1: O(N), 2: O(N^2)); table, CSV and chart. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cmd.h"
#include "gpu.h"
#include "plot.h"
#include "../io/io.h"

int bench_cmd_scaling(bench_opts *o)
{
    const int dim = o->cfg.dim;
    char date[64];
    double load0[3], load1[3];
    bench_now_iso(date, sizeof date);
    bench_loadavg(load0);
    double t_start = sph_now_ms(), ghz0 = bench_clock_probe();
    /* N = 128, 256, ... up to --at: a GPU's sweep goes to millions; the quick run stops at 8192 */
    const double n_max = o->at_given ? o->at : o->quick ? 8192 : (dim == 3 ? 262144 : 524288);
    const double max_ms = o->quick ? 150 : 1000; /* a level stops after a size this slow */
    const bench_plan plan = o->quick ? (bench_plan){1, 2, 200, 0, false} : (bench_plan){3, 3, 3000, 0, false};
    int ks[64], nk = 0;
    for (double n = fmin(128, n_max); n <= n_max * 1.001 && nk < 64; n *= 2) {
        int k = bench_k_near(dim, n);
        if (nk == 0 || k != ks[nk - 1]) ks[nk++] = k;
    }
    { /* --at between two doublings: it is the sweep's last size */
        int k = bench_k_near(dim, n_max);
        if (nk < 64 && (nk == 0 || k > ks[nk - 1])) ks[nk++] = k;
    }
    char dir_err[1200];
    if (!sph_output_dir(o->out, dir_err, sizeof dir_err)) {
        fprintf(stderr, "sphlab bench: --out: %s\n", dir_err);
        return 1;
    }
    /* GL levels only where an OpenGL 4.3 context can be made; said either way */
    char gl_device[256] = "";
    bool gl_probed = false, gl_ok = false;
    for (int s = 0; s < o->nsel; s++) {
        if (!bench_level_gl(&bench_levels[o->sel[s]])) continue;
        if (!gl_probed) {
            gl_ok = sph_gpu_probe(gl_device, sizeof gl_device);
            gl_probed = true;
            if (!o->quiet) printf("GL levels (G*): %s%s\n", gl_ok ? "" : "skipped, no OpenGL 4.3 device: ", gl_device);
        }
        if (!gl_ok) {
            memmove(o->sel + s, o->sel + s + 1, (size_t)(o->nsel - s - 1) * sizeof o->sel[0]);
            o->nsel--;
            s--;
        }
    }
    double *N = calloc((size_t)o->nsel * nk, sizeof *N), *MS = calloc((size_t)o->nsel * nk, sizeof *MS);
    double *PR = calloc((size_t)o->nsel * nk, sizeof *PR);
    int *cnt = calloc((size_t)o->nsel, sizeof *cnt), *thr = calloc((size_t)o->nsel, sizeof *thr);
    if (!N || !MS || !PR || !cnt || !thr) {
        fprintf(stderr, "sphlab bench: out of memory\n");
        return 1;
    }
    bool ok = true;
    double others[BENCH_MAX_LEVELS], worst = 0;
    for (int s = 0; s < o->nsel && ok; s++) {
        const bench_level *L = &bench_levels[o->sel[s]];
        bench_cpu c0, c1;
        bench_cpu_now(&c0);
        for (int j = 0; j < nk; j++) {
            bench_progress("%s %s: N = %.0f ...", L->name, L->about, bench_count(dim, ks[j]));
            bench_meas m;
            char why[512];
            if (!bench_measure_retry(&o->cfg, L, ks[j], &plan, 0, o->quick ? 1 : 3, &m, why, sizeof why)) {
                bench_progress_done();
                fprintf(stderr, "sphlab bench: %s at N = %.0f: %s\n", L->name, bench_count(dim, ks[j]), why);
                ok = false;
                break;
            }
            N[s * nk + cnt[s]] = m.n;
            MS[s * nk + cnt[s]] = m.ms_step;
            PR[s * nk + cnt[s]] = m.pairs;
            thr[s] = m.threads;
            cnt[s]++;
            if (m.ms_step > max_ms) break;
        }
        bench_cpu_now(&c1);
        others[s] = bench_cpu_others(&c0, &c1);
        worst = fmax(worst, others[s]);
    }
    bench_progress_done();
    bench_loadavg(load1);
    double seconds = (sph_now_ms() - t_start) / 1e3, ghz1 = bench_clock_probe();
    /* slope of log(ms) against log(N) over the upper half of each level's sizes */
    double slope[BENCH_MAX_LEVELS];
    for (int s = 0; s < o->nsel; s++) {
        int c = cnt[s], a = c / 2;
        if (c - a < 2) a = c - 2;
        double sx = 0, sy = 0, sxx = 0, sxy = 0;
        int m = 0;
        for (int i = a < 0 ? 0 : a; i < c; i++) {
            double x = log(N[s * nk + i]), y = log(MS[s * nk + i]);
            sx += x, sy += y, sxx += x * x, sxy += x * y, m++;
        }
        slope[s] = m >= 2 && m * sxx - sx * sx > 0 ? (m * sxy - sx * sy) / (m * sxx - sx * sx) : NAN;
    }
    if (!o->quiet && ok) {
        printf("sphlab bench scaling: %dD, ms per step (median) against N%s\n%s, load %.2f at the start, %.2f at the "
               "end, %.0f s\n",
               dim, o->quick ? " (--quick)" : "", date, load0[0], load1[0], seconds);
        printf("one core's clock %.2f GHz at the start, %.2f at the end (lower when the host is busy)\n", ghz0, ghz1);
        if (worst > 0.2)
            printf("warning: the machine was busy (others: up to %.2f cores during a level): timings are low and\n"
                   "noisy, the threaded levels worst; re-run when quiet\n",
                   worst);
        printf("\n");
        printf("%9s", "N");
        for (int s = 0; s < o->nsel; s++) printf(" %10s", bench_levels[o->sel[s]].name);
        printf("\n");
        for (int j = 0; j < nk; j++) {
            printf("%9.0f", bench_count(dim, ks[j]));
            for (int s = 0; s < o->nsel; s++)
                if (j < cnt[s])
                    printf(" %10.4g", MS[s * nk + j]);
                else
                    printf(" %10s", "-");
            printf("\n");
        }
        printf("%9s", "slope");
        for (int s = 0; s < o->nsel; s++) printf(" %10.2f", slope[s]);
        printf("\n%9s", "others");
        for (int s = 0; s < o->nsel; s++) printf(" %10.2f", others[s]);
        printf("\n\nslope: of log(ms/step) against log(N) over each level's larger half of sizes (1: O(N), 2: O(N^2));\n"
               "a level stops after the first size above %g ms per step; others: cores that other processes kept\n"
               "busy while the level was measured.\n\n",
               max_ms);
    }
    if (ok) {
        char name[64];
        snprintf(name, sizeof name, "scaling-%s.csv", bench_dim_tag(dim));
        FILE *f = plot_out_stage_csv(o->out, name);
        ok = f != NULL;
        if (f) {
            fprintf(f, "level,description,threads,n,ms_per_step,steps_per_s,pairs_per_step,others_cores\n");
            for (int s = 0; s < o->nsel; s++) {
                char about[128];
                snprintf(about, sizeof about, "%s", bench_levels[o->sel[s]].about);
                for (char *c = about; *c; c++)
                    if (*c == ',' || *c == '"') *c = ';';
                for (int i = 0; i < cnt[s]; i++) {
                    fprintf(f, "%s,%s,%d,%.0f,%.6g,%.6g", bench_levels[o->sel[s]].name, about, thr[s], N[s * nk + i],
                            MS[s * nk + i], 1000.0 / MS[s * nk + i]);
                    bench_csv_num(f, PR[s * nk + i], "%.0f"); /* empty for a GL level: no lists */
                    fprintf(f, ",%.3f\n", others[s]);
                }
            }
            ok &= plot_out_close_csv(f, o->out, name);
        }
    }
    if (ok) {
        static bench_scaling_chart c;
        memset(&c, 0, sizeof c);
        snprintf(c.title, sizeof c.title, "Time per step against N, %dD, each level of the ladder", dim);
        snprintf(c.subtitle, sizeof c.subtitle, "%s   load %.2f   median of repeats", date, load0[0]);
        c.fps = o->fps > 0 ? o->fps : 60; /* the --fps line (it drew 60 whatever --fps said) */
        c.ns = o->nsel;
        for (int s = 0; s < o->nsel; s++) {
            snprintf(c.s[s].label, sizeof c.s[s].label, "%s %.42s", bench_levels[o->sel[s]].name,
                     bench_levels[o->sel[s]].about);
            c.s[s].n = N + s * nk;
            c.s[s].ms = MS + s * nk;
            c.s[s].count = (size_t)cnt[s];
        }
        char name[64];
        snprintf(name, sizeof name, "scaling-%s", bench_dim_tag(dim));
        ok &= bench_chart_scaling(&c, o->out, name);
    }
    if (ok)
        ok = plot_out_commit(o->quiet);
    else
        plot_out_abort();
    free(N);
    free(MS);
    free(PR);
    free(cnt);
    free(thr);
    return ok ? 0 : 1;
}
