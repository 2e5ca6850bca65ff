/* sphlab plot WHAT ...: charts for a report, each as PNG and PDF beside the
 * CSV that holds the data it shows (docs/figures.md).
 *   passes STATS.csv     median milliseconds per pass (bars), and per pass over time (stacked)
 *   series STATS.csv     columns of --stats against time
 *   kernel NAME          a kernel, its gradient dW/dr and its Laplacian against r/h
 *   kernels              every kernel, one chart each, and all of them compared */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "plot.h"
#include "sph_kernel.h"
#include "sph_scene.h"

static const app_cmd_spec spec = {
    .name = "plot",
    .cmd = APP_CMD(plot),
    .synopsis = "usage: sphlab plot WHAT [options]\n"
                "  passes STATS.csv         milliseconds per pass from `sphlab run --stats`: median per step\n"
                "                           (bars, BASE = passes) and over time (stacked, BASE-time)\n"
                "  series STATS.csv --y C[,C...]\n"
                "                           columns of the stats CSV against t (one panel per unit)\n"
                "  kernel NAME              a kernel W, dW/dr and its Laplacian against r/h\n"
                "  kernels                  every kernel (one chart each) and all five compared\n"
                "options:\n",
    .footer = "Each chart is written as BASE.png and BASE.pdf (and BASE.svg) beside BASE.csv, the data it shows.\n",
    .max_pos = 2,
};


static int parse_args(int argc, char **argv, plot_opts *o)
{
    app_opts opt;
    app_opts_init(&opt);
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    o->what = opt.pos[0];
    o->input = opt.pos[1];
    o->out = opt.out;
    o->name = opt.name;
    o->ycols = opt.ycols;
    o->xcol = opt.xcol;
    o->width = (int)opt.size[0];
    o->height = (int)opt.size[1];
    o->dim = opt.dim < 0 ? 0 : (int)opt.dim;
    o->bins = opt.bins < 0 ? 0 : (int)opt.bins;
    o->h = opt.h < 0 ? 0 : opt.h;
    o->quiet = opt.quiet;
    if (opt.svg) plot_set_svg(true);
    return -1; /* go on */
}

/* The directory part of a path ("." if none). */
static void dir_of(char *dst, size_t cap, const char *path)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dst, cap, ".");
    else if (slash == path)
        snprintf(dst, cap, "/");
    else
        snprintf(dst, cap, "%.*s", (int)(slash - path), path);
}

static const char *base_of(const char *path)
{
    const char *slash = strrchr(path, '/');
    return slash ? slash + 1 : path;
}

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return (x > y) - (x < y);
}

/* Median of v[0..n) (finite values only; NaN if none); scratch holds n doubles. */
static double median(const double *v, size_t n, double *scratch)
{
    size_t m = 0;
    for (size_t i = 0; i < n; i++)
        if (isfinite(v[i])) scratch[m++] = v[i];
    if (!m) return NAN;
    qsort(scratch, m, sizeof *scratch, cmp_double);
    return m % 2 ? scratch[m / 2] : 0.5 * (scratch[m / 2 - 1] + scratch[m / 2]);
}

/* ---- passes ---------------------------------------------------------------- */

static int plot_passes(const plot_opts *o, const char *dir)
{
    plot_table t;
    if (!plot_table_read(&t, o->input)) return 1;
    int rc = 1;
    double *scratch = NULL, *total = NULL, *bx = NULL, *by[PLOT_MAX_LAYERS] = {NULL};
    int tcol = plot_table_need(&t, "t", "simulated time, as `sphlab run --stats` writes it");
    int pc[PLOT_MAX_BARS], np = 0;
    for (int c = 0; c < t.ncols; c++) {
        size_t len = strlen(t.names[c]);
        if (len > 3 && strcmp(t.names[c] + len - 3, "_ms") == 0) {
            if (np == PLOT_MAX_BARS) {
                fprintf(stderr, "sphlab plot: %s: more than %d per-pass columns\n", t.path, PLOT_MAX_BARS);
                goto out;
            }
            pc[np++] = c;
        }
    }
    if (tcol < 0) goto out;
    if (np == 0) {
        fprintf(stderr,
                "sphlab plot: %s: no per-pass column (PASS_ms, e.g. 'density_ms', as `sphlab run --stats` writes)\n",
                t.path);
        goto out;
    }
    if (!plot_out_dir(dir)) goto out;
    size_t n = t.nrows;
    scratch = malloc(n * sizeof *scratch);
    total = calloc(n, sizeof *total);
    if (!scratch || !total) goto oom;

    /* bars: median ms per step of each pass */
    plot_bars bars = {0};
    double med[PLOT_MAX_BARS], sum_med = 0;
    for (int k = 0; k < np; k++) {
        med[k] = median(t.col[pc[k]], n, scratch);
        if (isfinite(med[k])) sum_med += med[k];
        for (size_t i = 0; i < n; i++)
            if (isfinite(t.col[pc[k]][i])) total[i] += t.col[pc[k]][i];
    }
    double med_total = median(total, n, scratch);
    char base[256], file[320], src[96];
    snprintf(base, sizeof base, "%s", o->name ? o->name : "passes");
    plot_escape(src, sizeof src, base_of(t.path));
    snprintf(bars.title, sizeof bars.title, "Time per pass");
    /* the shares are of the medians' sum, not of the median step (a step's passes are not each at their median;
     * the run's table shares the means): both totals named, so the percentages can be checked */
    snprintf(bars.subtitle, sizeof bars.subtitle,
             "median over %zu steps of %s; shares of the medians' sum, %.4g ms; the median step %.4g ms", n, src,
             sum_med, med_total);
    snprintf(bars.xlabel, sizeof bars.xlabel, "median time per step [ms]");
    bars.n = np;
    for (int k = 0; k < np; k++) {
        snprintf(bars.name[k], sizeof bars.name[k], "%.*s", (int)strlen(t.names[pc[k]]) - 3, t.names[pc[k]]);
        bars.value[k] = med[k];
        snprintf(bars.note[k], sizeof bars.note[k], "%.3g ms  (%.1f%%)", med[k],
                 sum_med > 0 ? 100 * med[k] / sum_med : 0.0);
    }
    snprintf(file, sizeof file, "%s.csv", base);
    FILE *f = plot_out_stage_csv(dir, file);
    if (!f) goto out;
    /* share_percent: of the sum of the passes' medians (the run's table gives shares of the means) */
    fprintf(f, "pass,median_ms,mean_ms,min_ms,max_ms,share_percent\n");
    for (int k = 0; k < np; k++) {
        const double *v = t.col[pc[k]];
        double sum = 0, lo = INFINITY, hi = -INFINITY;
        size_t m = 0;
        for (size_t i = 0; i < n; i++)
            if (isfinite(v[i])) sum += v[i], lo = fmin(lo, v[i]), hi = fmax(hi, v[i]), m++;
        fprintf(f, "%s,%.9g,%.9g,%.9g,%.9g,%.4f\n", bars.name[k], med[k], m ? sum / (double)m : NAN, lo, hi,
                sum_med > 0 ? 100 * med[k] / sum_med : 0.0);
    }
    if (!plot_out_close_csv(f, dir, file)) goto out;
    if (!plot_chart(PLOT_BARS, &bars, dir, base, o->width ? o->width : 1000, o->height ? o->height : 700)) goto out;

    /* stacked: median of each pass over bins of consecutive steps */
    int nb = o->bins ? o->bins : 100;
    if ((size_t)nb > n) nb = (int)n;
    bx = malloc((size_t)nb * sizeof *bx);
    if (!bx) goto oom;
    for (int k = 0; k < np; k++)
        if (!(by[k] = malloc((size_t)nb * sizeof *by[k]))) goto oom;
    int scol = plot_table_find(&t, "step");
    char tbase[300];
    snprintf(tbase, sizeof tbase, "%s-time", base);
    snprintf(file, sizeof file, "%s.csv", tbase);
    if (!(f = plot_out_stage_csv(dir, file))) goto out;
    fprintf(f, "t,step_first,step_last");
    for (int k = 0; k < np; k++) fprintf(f, ",%s", t.names[pc[k]]);
    fprintf(f, "\n");
    for (int b = 0; b < nb; b++) {
        size_t i0 = (size_t)b * n / (size_t)nb, i1 = (size_t)(b + 1) * n / (size_t)nb;
        bx[b] = t.col[tcol][(i0 + i1 - 1) / 2];
        double s0 = scol >= 0 ? t.col[scol][i0] : (double)(i0 + 1), s1 = scol >= 0 ? t.col[scol][i1 - 1] : (double)i1;
        fprintf(f, "%.9g,%.0f,%.0f", bx[b], s0, s1);
        for (int k = 0; k < np; k++) {
            by[k][b] = median(t.col[pc[k]] + i0, i1 - i0, scratch);
            fprintf(f, ",%.9g", by[k][b]);
        }
        fprintf(f, "\n");
    }
    if (!plot_out_close_csv(f, dir, file)) goto out;
    plot_stack st = {0};
    snprintf(st.title, sizeof st.title, "Time per pass over the run");
    snprintf(st.subtitle, sizeof st.subtitle, "medians over %d bins of about %zu steps each, stacked; from %s", nb,
             (n + (size_t)nb - 1) / (size_t)nb, src);
    snprintf(st.xlabel, sizeof st.xlabel, "t [s]");
    snprintf(st.ylabel, sizeof st.ylabel, "time per step [ms]");
    st.x = bx;
    st.n = (size_t)nb;
    st.nl = np;
    for (int k = 0; k < np; k++) {
        snprintf(st.name[k], sizeof st.name[k], "%s", bars.name[k]);
        st.y[k] = by[k];
    }
    if (!plot_chart(PLOT_STACK, &st, dir, tbase, o->width ? o->width : 1000, o->height ? o->height : 700)) goto out;
    rc = plot_out_commit(o->quiet) ? 0 : 1;
    goto out;
oom:
    fprintf(stderr, "sphlab plot: out of memory\n");
out:
    if (rc) plot_out_abort();
    free(scratch);
    free(total);
    free(bx);
    for (int k = 0; k < PLOT_MAX_LAYERS; k++) free(by[k]);
    plot_table_free(&t);
    return rc;
}

/* ---- series ------------------------------------------------------------------ */

/* Axis label (quantity [unit]) of a --stats column; columns with the same
 * label share a panel. dim 0: not known, both units named. */
static void column_axis(const char *name, int dim, char *dst, size_t cap)
{
    size_t len = strlen(name);
    if (strcmp(name, "t") == 0)
        snprintf(dst, cap, "t [s]");
    else if (strcmp(name, "dt") == 0)
        snprintf(dst, cap, "time step [s]");
    else if (strcmp(name, "step") == 0)
        snprintf(dst, cap, "step [-]");
    else if (strcmp(name, "n") == 0)
        snprintf(dst, cap, "particles [-]");
    else if (strcmp(name, "ekin") == 0)
        snprintf(dst, cap, "kinetic energy [%s]", dim == 2 ? "J/m" : dim == 3 ? "J" : "J/m or J");
    else if (strncmp(name, "rho_", 4) == 0)
        snprintf(dst, cap, "density [%s]",
                 dim == 2 ? "kg/m#u2#d" : dim == 3 ? "kg/m#u3#d" : "kg/m#u2#d or kg/m#u3#d");
    else if (strcmp(name, "max_speed") == 0)
        snprintf(dst, cap, "speed [m/s]");
    else if (len > 3 && strcmp(name + len - 3, "_ms") == 0)
        snprintf(dst, cap, "time per step [ms]");
    else if (len > 12 && strncmp(name, "obstacle_", 9) == 0 && name[len - 3] == '_' && name[len - 2] == 'f' &&
             strchr("xyz", name[len - 1])) {
        /* obstacle_NAME_fx, _fy, _fz: the force the fluid exerts on it (per metre of depth in 2D) */
        char obstacle[48], esc[64]; /* names are up to 40 characters */
        snprintf(obstacle, sizeof obstacle, "%.*s", (int)(len - 12 < 40 ? len - 12 : 40), name + 9);
        plot_escape(esc, sizeof esc, obstacle);
        snprintf(dst, cap, "force on %.64s [%s]", esc, dim == 2 ? "N/m" : dim == 3 ? "N" : "N/m in 2D, N in 3D");
    } else
        plot_escape(dst, cap, name);
}

static int plot_series_cmd(const plot_opts *o, const char *dir)
{
    if (!o->ycols || !*o->ycols) {
        fprintf(stderr, "sphlab plot series: --y is missing: name the columns to plot, e.g. --y ekin,rho_max\n");
        return 2;
    }
    const char *xname = o->xcol ? o->xcol : "t";
    if (strcmp(xname, "t") != 0 && strcmp(xname, "step") != 0) {
        fprintf(stderr, "sphlab plot series: --x '%s': want t or step\n", xname);
        return 2;
    }
    plot_table t;
    if (!plot_table_read(&t, o->input)) return 1;
    int rc = 1;
    int xc = plot_table_need(&t, xname, xname[0] == 't' ? "simulated time, the x axis" : "step number, the x axis");
    if (xc < 0) goto out;

    int yc[PLOT_MAX_SERIES], ny = 0;
    char list[1024];
    snprintf(list, sizeof list, "%s", o->ycols);
    for (char *tok = strtok(list, ","); tok; tok = strtok(NULL, ",")) {
        while (*tok == ' ') tok++;
        if (!*tok) continue;
        int c = plot_table_find(&t, tok);
        if (c < 0) {
            fprintf(stderr, "sphlab plot: %s: no column '%s' (--y); the columns are:", t.path, tok);
            for (int k = 0; k < t.ncols; k++) fprintf(stderr, "%s%s", k ? "," : " ", t.names[k]);
            fprintf(stderr, "\n");
            rc = 2; /* --y names what the command line asks for: a bad command line, as figures.md says */
            goto out;
        }
        if (ny == PLOT_MAX_SERIES) {
            fprintf(stderr, "sphlab plot: --y: at most %d columns\n", PLOT_MAX_SERIES);
            rc = 2;
            goto out;
        }
        yc[ny++] = c;
    }
    if (!ny) {
        fprintf(stderr, "sphlab plot series: --y '%s': no column named\n", o->ycols);
        rc = 2;
        goto out;
    }

    plot_lines L = {0};
    char axis[PLOT_MAX_SERIES][128];
    const char *axis_of_panel[PLOT_MAX_PANELS] = {NULL};
    for (int k = 0; k < ny; k++) {
        column_axis(t.names[yc[k]], o->dim, axis[k], sizeof axis[k]);
        int p = 0;
        while (p < L.np && strcmp(L.p[p].ylabel, axis[k]) != 0) p++;
        if (p == L.np) {
            if (L.np == PLOT_MAX_PANELS) {
                fprintf(stderr, "sphlab plot: --y: the columns have more than %d different units\n", PLOT_MAX_PANELS);
                rc = 2;
                goto out;
            }
            axis_of_panel[L.np] = axis[k];
            snprintf(L.p[L.np++].ylabel, sizeof L.p[0].ylabel, "%s", axis[k]);
        }
        plot_series *s = &L.p[p].s[L.p[p].n++];
        plot_escape(s->label, sizeof s->label, t.names[yc[k]]);
        s->x = t.col[xc];
        s->y = t.col[yc[k]];
        s->n = t.nrows;
        s->style = k;
    }
    if (!plot_out_dir(dir)) goto out;
    char base[256], file[320], src[96];
    if (o->name)
        snprintf(base, sizeof base, "%s", o->name);
    else {
        size_t m = (size_t)snprintf(base, sizeof base, "series");
        for (int k = 0; k < ny && m + strlen(t.names[yc[k]]) + 2 < 120; k++)
            m += (size_t)snprintf(base + m, sizeof base - m, "-%s", t.names[yc[k]]);
        for (char *c = base; *c; c++)
            if (*c == '/' || *c == ' ') *c = '_';
    }
    plot_escape(src, sizeof src, base_of(t.path));
    /* title: the quantities, without their units */
    char title[sizeof L.title];
    size_t m = 0;
    for (int p = 0; p < L.np && m < sizeof title; p++) {
        const char *lab = axis_of_panel[p], *br = strstr(lab, " [");
        int len = br ? (int)(br - lab) : (int)strlen(lab);
        m += (size_t)snprintf(title + m, sizeof title - m, "%s%.*s", p == 0 ? "" : p == L.np - 1 ? " and " : ", ",
                              len, lab);
    }
    if (m < sizeof title) snprintf(title + m, sizeof title - m, " over %s", xname[0] == 't' ? "time" : "steps");
    if (title[0] >= 'a' && title[0] <= 'z') title[0] = (char)(title[0] - 'a' + 'A');
    memcpy(L.title, title, sizeof title);
    snprintf(L.subtitle, sizeof L.subtitle, "%zu step%s from %s", t.nrows, t.nrows == 1 ? "" : "s", src);
    column_axis(xname, o->dim, L.xlabel, sizeof L.xlabel);

    snprintf(file, sizeof file, "%s.csv", base);
    FILE *f = plot_out_stage_csv(dir, file);
    if (!f) goto out;
    fprintf(f, "%s", t.names[xc]);
    for (int k = 0; k < ny; k++) fprintf(f, ",%s", t.names[yc[k]]);
    fprintf(f, "\n");
    for (size_t i = 0; i < t.nrows; i++) {
        fprintf(f, "%.9g", t.col[xc][i]);
        for (int k = 0; k < ny; k++) fprintf(f, ",%.9g", t.col[yc[k]][i]);
        fprintf(f, "\n");
    }
    if (!plot_out_close_csv(f, dir, file)) goto out;
    int h = o->height ? o->height : 550 + 150 * L.np;
    if (!plot_chart(PLOT_LINES, &L, dir, base, o->width ? o->width : 1000, h)) goto out;
    rc = plot_out_commit(o->quiet) ? 0 : 1;
out:
    if (rc) plot_out_abort();
    plot_table_free(&t);
    return rc;
}

/* ---- kernels ------------------------------------------------------------------ */

enum { KPOINTS = 221 };         /* r/h = 0, 0.005, ..., 1.1: past the support, where W = 0 */
static const double KSTEP = 0.005;

typedef struct kernel_curves {
    double q[KPOINTS], r[KPOINTS], w[KPOINTS], dw[KPOINTS], lap[KPOINTS];
} kernel_curves;

static void kernel_eval(sph_kernel_kind kind, int dim, double h, kernel_curves *c)
{
    sph_kernel k = sph_kernel_make(kind, dim, (float)h);
    for (int i = 0; i < KPOINTS; i++) {
        float r = (float)(i * KSTEP * h);
        c->q[i] = i * KSTEP;
        c->r[i] = r;
        c->w[i] = sph_kernel_w(&k, r);
        c->dw[i] = sph_kernel_dw(&k, r);
        c->lap[i] = sph_kernel_lap(&k, r);
    }
}

static void kernel_axes(plot_lines *L, int dim)
{
    snprintf(L->xlabel, sizeof L->xlabel, "r/h [-]");
    L->xlo = 0;
    L->xhi = KSTEP * (KPOINTS - 1);
    L->np = 3;
    snprintf(L->p[0].ylabel, sizeof L->p[0].ylabel, "W [1/m#u%d#d]", dim);
    snprintf(L->p[1].ylabel, sizeof L->p[1].ylabel, "dW/dr [1/m#u%d#d]", dim + 1);
    snprintf(L->p[2].ylabel, sizeof L->p[2].ylabel, "#[0x2207]#u2#dW [1/m#u%d#d]", dim + 2);
    for (int p = 0; p < 3; p++) L->p[p].zero_line = L->p[p].clip_singular = true;
}

/* One kernel: CSV and chart DIR/BASE.{csv,png,pdf}. */
static bool one_kernel(const plot_opts *o, const char *dir, sph_kernel_kind kind, int dim, double h, const char *base)
{
    kernel_curves *c = malloc(sizeof *c);
    if (!c) return false;
    kernel_eval(kind, dim, h, c);
    char file[300];
    snprintf(file, sizeof file, "%s.csv", base);
    FILE *f = plot_out_stage_csv(dir, file);
    bool ok = f != NULL;
    if (ok) {
        fprintf(f, "r_over_h,r,w,dw_dr,lap\n");
        for (int i = 0; i < KPOINTS; i++)
            fprintf(f, "%.6g,%.9g,%.9g,%.9g,%.9g\n", c->q[i], c->r[i], c->w[i], c->dw[i], c->lap[i]);
        ok = plot_out_close_csv(f, dir, file);
    }
    if (ok) {
        plot_lines L = {0};
        kernel_axes(&L, dim);
        snprintf(L.title, sizeof L.title, "%s kernel, %dD, h = %g m", sph_kernel_names[kind], dim, h);
        plot_escape(L.subtitle, sizeof L.subtitle, sph_kernel_about[kind]);
        const char *label[3] = {"W", "dW/dr", "#[0x2207]#u2#dW"};
        const double *y[3] = {c->w, c->dw, c->lap};
        for (int p = 0; p < 3; p++) {
            plot_series *s = &L.p[p].s[L.p[p].n++];
            snprintf(s->label, sizeof s->label, "%s", label[p]);
            s->x = c->q;
            s->y = y[p];
            s->n = KPOINTS;
            s->style = p;
        }
        ok = plot_chart(PLOT_LINES, &L, dir, base, o->width ? o->width : 1000, o->height ? o->height : 1000);
    }
    free(c);
    return ok;
}

static double kernel_h(const plot_opts *o)
{
    return o->h > 0 ? o->h : (double)sph_default_scene_def().h;
}

static int plot_kernel_cmd(const plot_opts *o, const char *dir)
{
    if (!o->input) {
        fprintf(stderr, "sphlab plot kernel: name a kernel:");
        for (int k = 0; k < SPH_KERNEL_COUNT; k++) fprintf(stderr, " %s", sph_kernel_names[k]);
        fprintf(stderr, "\n");
        return 2;
    }
    int kind = sph_kernel_find(o->input);
    if (kind < 0) {
        fprintf(stderr, "sphlab plot kernel: unknown kernel '%s' (known:", o->input);
        for (int k = 0; k < SPH_KERNEL_COUNT; k++) fprintf(stderr, " %s", sph_kernel_names[k]);
        fprintf(stderr, ")\n");
        return 2; /* a bad command line, as `plot bogus` */
    }
    int dim = o->dim ? o->dim : 2;
    char base[256];
    if (o->name)
        snprintf(base, sizeof base, "%s", o->name);
    else
        snprintf(base, sizeof base, "kernel-%s-%dd", sph_kernel_names[kind], dim);
    if (!plot_out_dir(dir)) return 1;
    if (!one_kernel(o, dir, (sph_kernel_kind)kind, dim, kernel_h(o), base) || !plot_out_commit(o->quiet)) {
        plot_out_abort();
        return 1;
    }
    return 0;
}

static int plot_kernels_cmd(const plot_opts *o, const char *dir)
{
    if (o->input) {
        fprintf(stderr, "sphlab plot kernels: takes no name ('%s'); for one kernel: sphlab plot kernel NAME\n",
                o->input);
        return 2;
    }
    int dim = o->dim ? o->dim : 2;
    double h = kernel_h(o);
    char base[256], file[320];
    if (o->name)
        snprintf(base, sizeof base, "%s", o->name);
    else
        snprintf(base, sizeof base, "kernels-%dd", dim);
    if (!plot_out_dir(dir)) return 1;

    kernel_curves *c = malloc(SPH_KERNEL_COUNT * sizeof *c);
    bool ok = c != NULL;
    for (int k = 0; ok && k < SPH_KERNEL_COUNT; k++) {
        char one[300];
        snprintf(one, sizeof one, "kernel-%s-%dd", sph_kernel_names[k], dim);
        kernel_eval((sph_kernel_kind)k, dim, h, &c[k]);
        ok = one_kernel(o, dir, (sph_kernel_kind)k, dim, h, one);
    }
    FILE *f = NULL;
    if (ok) {
        snprintf(file, sizeof file, "%s.csv", base);
        ok = (f = plot_out_stage_csv(dir, file)) != NULL;
    }
    if (ok) {
        fprintf(f, "r_over_h,r");
        const char *what[3] = {"w", "dw_dr", "lap"};
        for (int p = 0; p < 3; p++)
            for (int k = 0; k < SPH_KERNEL_COUNT; k++) fprintf(f, ",%s_%s", what[p], sph_kernel_names[k]);
        fprintf(f, "\n");
        for (int i = 0; i < KPOINTS; i++) {
            fprintf(f, "%.6g,%.9g", c[0].q[i], c[0].r[i]);
            for (int p = 0; p < 3; p++)
                for (int k = 0; k < SPH_KERNEL_COUNT; k++)
                    fprintf(f, ",%.9g", p == 0 ? c[k].w[i] : p == 1 ? c[k].dw[i] : c[k].lap[i]);
            fprintf(f, "\n");
        }
        ok = plot_out_close_csv(f, dir, file);
    }
    if (ok) {
        plot_lines L = {0};
        kernel_axes(&L, dim);
        snprintf(L.title, sizeof L.title, "The %d kernels in %dD, h = %g m", SPH_KERNEL_COUNT, dim, h);
        snprintf(L.subtitle, sizeof L.subtitle, "value, gradient dW/dr and Laplacian against r/h");
        for (int p = 0; p < 3; p++)
            for (int k = 0; k < SPH_KERNEL_COUNT && k < PLOT_MAX_SERIES; k++) {
                plot_series *s = &L.p[p].s[L.p[p].n++];
                snprintf(s->label, sizeof s->label, "%s", sph_kernel_names[k]);
                s->x = c[k].q;
                s->y = p == 0 ? c[k].w : p == 1 ? c[k].dw : c[k].lap;
                s->n = KPOINTS;
                s->style = k;
            }
        ok = plot_chart(PLOT_LINES, &L, dir, base, o->width ? o->width : 1000, o->height ? o->height : 1000);
    }
    free(c);
    if (!ok || !plot_out_commit(o->quiet)) {
        plot_out_abort();
        return 1;
    }
    return 0;
}

/* ---- entry ------------------------------------------------------------------ */

int cmd_plot(int argc, char **argv)
{
    plot_opts o = {0};
    int rc = parse_args(argc, argv, &o);
    if (rc >= 0) return rc;
    return plot_run(&o);
}

int plot_run(const plot_opts *opts)
{
    const plot_opts o = *opts;
    if (!o.what) {
        app_opts_usage_error(&spec, "name a chart");
        return 2;
    }
    bool from_csv = strcmp(o.what, "passes") == 0 || strcmp(o.what, "series") == 0;
    bool kernels = strcmp(o.what, "kernel") == 0 || strcmp(o.what, "kernels") == 0;
    if (!from_csv && !kernels) {
        fprintf(stderr, "sphlab plot: unknown chart '%s' (known: passes, series, kernel, kernels)\n", o.what);
        return 2;
    }
    char dir[1024];
    if (from_csv) {
        if (!o.input) {
            fprintf(stderr, "sphlab plot %s: name the stats CSV (from `sphlab run SCENE --stats FILE.csv`)\n", o.what);
            return 2;
        }
        if (o.out)
            snprintf(dir, sizeof dir, "%s", o.out);
        else
            dir_of(dir, sizeof dir, o.input);
    } else {
        snprintf(dir, sizeof dir, "%s", o.out ? o.out : ".");
    }
    if (kernels) return strcmp(o.what, "kernel") == 0 ? plot_kernel_cmd(&o, dir) : plot_kernels_cmd(&o, dir);

    /* each reads and checks the CSV before it makes or writes into DIR */
    return strcmp(o.what, "passes") == 0 ? plot_passes(&o, dir) : plot_series_cmd(&o, dir);
}
