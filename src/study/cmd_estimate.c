/* sphlab estimate: the first step of the seed, measured. A known function is
 * estimated from samples with the SPH sum, for every support radius h and
 * sample count n asked for; the error against h shows the O(h^2) smoothing
 * bias at large h and the noise of too few samples at small h. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "plot.h"
#include "study.h"
#include "study_plot.h"

static const app_cmd_spec spec = {
    .name = "estimate",
    .cmd = APP_CMD(estimate),
    .synopsis = "usage: sphlab estimate [options]\n"
                "Estimates a known function from samples over the unit interval (1D) or square (2D) with the SPH sum\n"
                "<f>(x) = sum_j (m_j/rho_j) f(x_j) W(x - x_j, h), rho_j by summation, and prints the RMS error over\n"
                "the centre [0.25, 0.75]^dim for each h and sample count (docs/accuracy.md).\n",
};

#define MAX_LIST 16

/* A comma-separated list of numbers within [lo, hi]. */
static int parse_list(const char *opt, const char *s, double lo, double hi, bool whole, double *out)
{
    int n = 0;
    const char *p = s;
    for (;;) {
        char *end;
        double v = strtod(p, &end);
        if (end == p || (*end && *end != ',') || !isfinite(v)) {
            fprintf(stderr, "sphlab estimate: %s '%s': want a comma-separated list of numbers\n", opt, s);
            return -1;
        }
        if (v < lo || v > hi || (whole && v != floor(v))) {
            fprintf(stderr, "sphlab estimate: %s %g: out of range (accepted: %s%g to %g)\n", opt, v,
                    whole ? "whole numbers " : "", lo, hi);
            return -1;
        }
        if (n == MAX_LIST) {
            fprintf(stderr, "sphlab estimate: %s: at most %d values\n", opt, MAX_LIST);
            return -1;
        }
        out[n++] = v;
        if (!*end) break;
        p = end + 1;
    }
    return n;
}

int cmd_estimate(int argc, char **argv)
{
    study_est_opts eo = {1, STUDY_FN_SIN, SPH_KERNEL_POLY6, STUDY_SAMPLES_RANDOM, 0.3, 1};
    app_opts opt;
    app_opts_init(&opt);
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    const char *hs = opt.h_list, *ns = opt.n_list, *out = opt.out, *base = opt.name ? opt.name : "estimate";
    bool quiet = opt.quiet;
    if (opt.dim >= 0) eo.dim = (int)opt.dim;
    if (opt.function) {
        int k = -1;
        for (int f = 0; f < STUDY_FN_COUNT; f++)
            if (strcmp(opt.function, study_function_names[f]) == 0) k = f;
        if (k < 0) {
            fprintf(stderr, "sphlab estimate: --function '%s': unknown (accepted: sin, gauss)\n", opt.function);
            return 2;
        }
        eo.fn = (study_function)k;
    }
    if (opt.kernel) {
        int k = sph_kernel_find(opt.kernel);
        if (k < 0 || k == SPH_KERNEL_VISCOSITY) {
            fprintf(stderr, "sphlab estimate: --kernel '%s': %s (accepted: poly6, spiky, cubic, wendland)\n",
                    opt.kernel, k < 0 ? "unknown" : "meant for its Laplacian, singular at r = 0");
            return 2;
        }
        eo.kernel = (sph_kernel_kind)k;
    }
    if (opt.samples) {
        int k = -1;
        for (int s = 0; s < STUDY_SAMPLES_COUNT; s++)
            if (strcmp(opt.samples, study_samples_names[s]) == 0) k = s;
        if (k < 0) {
            fprintf(stderr, "sphlab estimate: --samples '%s': unknown (accepted: lattice, jitter, random)\n",
                    opt.samples);
            return 2;
        }
        eo.samples = (study_samples)k;
    }
    if (opt.jitter >= 0) eo.jitter = opt.jitter;
    if (opt.jitter >= 0 && eo.samples != STUDY_SAMPLES_JITTER) /* it changed nothing, unsaid */
        fprintf(stderr, "sphlab estimate: warning: --jitter %g is read only with --samples jitter (now %s)\n",
                opt.jitter, study_samples_names[eo.samples]);
    if (opt.seed >= 0) eo.seed = (uint64_t)opt.seed;
    double hv[MAX_LIST], nv[MAX_LIST];
    int nh = 0, nn = 0;
    if (hs) nh = parse_list("--h", hs, 1e-6, STUDY_EST_H_MAX, false, hv);
    if (ns) nn = parse_list("--n", ns, 2, eo.dim == 1 ? 1e7 : 4000, true, nv);
    if (nh < 0 || nn < 0) return 2;
    return study_estimate_write(&eo, hs ? hv : NULL, nh, ns ? nv : NULL, nn, out, base, quiet);
}

int study_estimate_write(const study_est_opts *opts, const double *h_list, int nh, const double *n_list, int nn,
                         const char *out, const char *base, bool quiet)
{
    const study_est_opts eo = *opts;
    double hv[MAX_LIST], nv[MAX_LIST];
    if (nh > MAX_LIST || nn > MAX_LIST) {
        fprintf(stderr, "sphlab estimate: at most %d values of h and of n\n", MAX_LIST);
        return 2;
    }
    if (h_list)
        memcpy(hv, h_list, (size_t)nh * sizeof *hv);
    else if (eo.dim == 1) {
        const double d1[] = {0.005, 0.01, 0.02, 0.04, 0.08, 0.125};
        nh = 6;
        memcpy(hv, d1, sizeof d1);
    } else {
        const double d2[] = {0.01, 0.02, 0.04, 0.08, 0.125};
        nh = 5;
        memcpy(hv, d2, sizeof d2);
    }
    if (n_list)
        memcpy(nv, n_list, (size_t)nn * sizeof *nv);
    else if (eo.dim == 1) {
        const double d1[] = {100, 1000, 10000};
        nn = 3;
        memcpy(nv, d1, sizeof d1);
    } else {
        const double d2[] = {50, 100, 200};
        nn = 3;
        memcpy(nv, d2, sizeof d2);
    }
    plot_out_command("estimate");
    if (out && !plot_out_dir(out)) return 1;

    static double err[MAX_LIST][MAX_LIST], bias[MAX_LIST];
    study_est_result res[MAX_LIST][MAX_LIST];
    bool progress = !quiet && isatty(STDERR_FILENO);
    /* the work, said before a long one: each sample within h of the centre sums its density over the 2 h n
     * (1D) or pi h^2 n^2 (2D) samples of its support (n = 1000, h = 0.125 in 2D: 3e10 kernel terms, minutes on
     * 2 cores, and nothing printed off a terminal) */
    double pairs = 0;
    for (int a = 0; a < nn; a++)
        for (int b = 0; b < nh; b++) {
            const double reach = fmin(1.0, 0.5 + 2 * hv[b]);
            pairs += eo.dim == 1 ? reach * nv[a] * 2 * hv[b] * nv[a]
                                 : reach * reach * nv[a] * nv[a] * 3.14159265358979 * hv[b] * hv[b] * nv[a] * nv[a];
        }
    const bool long_run = pairs > 2e9;
    if (long_run && !quiet)
        fprintf(stderr,
                "sphlab estimate: note: about %.1e kernel terms over the %d combination%s (the largest n and h "
                "cost most: n^(2 dim) h^dim): expect minutes; a line follows each combination\n",
                pairs, nn * nh, nn * nh == 1 ? "" : "s");
    for (int a = 0; a < nn; a++)
        for (int b = 0; b < nh; b++) {
            char why[512];
            if (long_run && !quiet && !progress)
                fprintf(stderr, "sphlab estimate: n = %g, h = %g (%d of %d)\n", nv[a], hv[b], a * nh + b + 1, nn * nh);
            if (progress) fprintf(stderr, "\r  n = %g, h = %g   ", nv[a], hv[b]);
            if (!study_estimate(&eo, hv[b], (int)nv[a], &res[a][b], why, sizeof why)) {
                if (progress) fprintf(stderr, "\r%60s\r", "");
                fprintf(stderr, "sphlab estimate: %s\n", why);
                return 1;
            }
            err[a][b] = res[a][b].error;
            bias[b] = res[a][b].bias;
        }
    if (progress) fprintf(stderr, "\r%60s\r", "");
    const char *fname = eo.fn == STUDY_FN_SIN ? (eo.dim == 1 ? "sin(2 pi x)" : "sin(2 pi x) sin(2 pi y)")
                                              : "exp(-|x - c|^2 / (2 0.1^2))";
    if (!quiet) {
        printf("estimate of f = %s in %dD from %s samples, kernel %s (RMS error over [0.25, 0.75]^%d)\n", fname,
               eo.dim, study_samples_names[eo.samples], sph_kernel_names[eo.kernel], eo.dim);
        printf("%9s %10s %9s %8s %11s %11s %11s %11s\n", "n", "samples", "h", "h/s", "neighbours", "error",
               "max error", "bias pred");
        for (int a = 0; a < nn; a++)
            for (int b = 0; b < nh; b++) {
                const study_est_result *r = &res[a][b];
                printf("%9g %10.0f %9g %8.3g %11.1f %11.4g %11.4g %11.4g\n", nv[a], r->samples, hv[b], hv[b] * nv[a],
                       r->neighbours, r->error, r->max_error, r->bias);
            }
    }
    if (!out) return 0;

    char csv_name[256];
    snprintf(csv_name, sizeof csv_name, "%s.csv", base);
    FILE *f = plot_out_stage_csv(out, csv_name);
    if (!f) return 1;
    fprintf(f, "dim,n,samples,h,h_over_spacing,neighbours,error,max_error,bias_predicted\n");
    for (int a = 0; a < nn; a++)
        for (int b = 0; b < nh; b++) {
            const study_est_result *r = &res[a][b];
            fprintf(f, "%d,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g\n", eo.dim, nv[a], r->samples, hv[b], hv[b] * nv[a],
                    r->neighbours, r->error, r->max_error, r->bias);
        }
    if (!plot_out_close_csv(f, out, csv_name)) {
        plot_out_abort();
        return 1;
    }
    study_chart ch;
    memset(&ch, 0, sizeof ch);
    snprintf(ch.title, sizeof ch.title, "Kernel estimate of a known function, %dD, %s kernel", eo.dim,
             sph_kernel_names[eo.kernel]);
    snprintf(ch.subtitle, sizeof ch.subtitle, "f = %s from %s samples, n per unit length; RMS error over [0.25, 0.75]%s",
             fname, study_samples_names[eo.samples], eo.dim == 2 ? "#u2#d" : "");
    snprintf(ch.xlabel, sizeof ch.xlabel, "support radius h [unit length]");
    snprintf(ch.ylabel, sizeof ch.ylabel, "RMS error of <f> [-]");
    for (int a = 0; a < nn && ch.nc < STUDY_MAX_CURVES - 1; a++) {
        study_curve *c = &ch.c[ch.nc];
        snprintf(c->label, sizeof c->label, "n = %g", nv[a]);
        c->x = hv, c->y = err[a], c->n = nh, c->style = (ch.nc + 1) % 8, c->line = true, c->markers = true;
        ch.nc++;
    }
    study_curve *c = &ch.c[ch.nc++];
    snprintf(c->label, sizeof c->label, "bias (M2/2d) |#gD f|");
    c->x = hv, c->y = bias, c->n = nh, c->style = 0, c->line = true;
    snprintf(ch.note[ch.nn++], sizeof ch.note[0], "slope 2 at large h: the bias");
    snprintf(ch.note[ch.nn++], sizeof ch.note[0], "rising at small h: too few samples");
    if (!study_chart_loglog(&ch, out, base, 1000, 700) || !plot_out_commit(quiet)) {
        plot_out_abort();
        return 1;
    }
    return 0;
}
