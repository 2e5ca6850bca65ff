/* The benchmark's charts, in the plot module's look and through its output
 * (PNG + PDF, staged; src/plot/plot.h). The scaling chart is the plot
 * module's log-log chart; the ladder, two panels of horizontal bars (log
 * scale, stacked), is drawn here with the module's drawing kit. */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <plplot.h>

#include "bench.h"
#include "plot.h"

/* A bar: its fill, outlined. */
static void fill_rect(double x0, double x1, double y0, double y1, int style)
{
    PLFLT fx[5] = {x0, x1, x1, x0, x0}, fy[5] = {y0, y0, y1, y1, y0};
    plot_width(0.8);
    plot_fill(4, fx, fy, style);
    plcol0(PLOT_FG);
    plline(5, fx, fy);
}

/* ---- the ladder: max N per level (log bars), ms per pass (stacked bars) ------ */

static double ladder_text_scale = 1.0; /* the page's text at the size it has on a 1000-pixel page */

static void draw_ladder(const void *chart)
{
    const bench_ladder_chart *c = chart;
    PLFLT def_mm, cur_mm;
    plgchr(&def_mm, &cur_mm);
    plschr(def_mm * ladder_text_scale, 1.0); /* PLplot's text grows with the page: a taller page keeps it */
    plot_titles(c->title, c->subtitle);
    const int nl = c->nl > 0 ? c->nl : 1;
    /* the labels' column: the longest level name ("L8 L7 + pressure and viscosity in one walk") ran past the
     * page's left edge at 0.37 */
    const double vx0 = 0.41, vx1 = 0.80;

    /* top: largest N at the frame rate, log scale */
    double lo = INFINITY, hi = 0;
    for (int i = 0; i < c->nl; i++)
        if (c->max_n[i] > 0) lo = fmin(lo, c->max_n[i]), hi = fmax(hi, c->max_n[i]);
    if (c->target_n > 0) lo = fmin(lo, c->target_n), hi = fmax(hi, c->target_n);
    if (!(hi > 0)) lo = 1, hi = 10;
    double xl = floor(log10(lo)), xh = ceil(log10(hi * 2.5));
    if (xh <= xl) xh = xl + 1;
    plvpor(vx0, vx1, 0.56, 0.87);
    plwind(xl, xh, 0, nl);
    plcol0(PLOT_GRID);
    plot_width(1.0);
    pllsty(1);
    plbox("gl", 1, 0, "", 0, 0);
    for (int i = 0; i < c->nl; i++) {
        double yc = nl - 1 - i + 0.5, hh = 0.33;
        if (c->max_n[i] > 0) fill_rect(xl, log10(c->max_n[i]), yc - hh, yc + hh, 1);
        plschr(0, 0.8);
        plcol0(PLOT_FG);
        plptex((c->max_n[i] > 0 ? log10(c->max_n[i]) : xl) + 0.02 * (xh - xl), yc, 1, 0, 0.0, c->note[i]);
        plschr(0, 0.72);
        plmtex("lv", 0.8, yc / nl, 1.0, c->level[i]);
        plschr(0, 1.0);
    }
    if (c->target_n > 0) {
        PLFLT tx[2] = {log10(c->target_n), log10(c->target_n)}, ty[2] = {0, nl};
        plcol0(PLOT_CURVE + 2);
        plot_width(1.6);
        plot_dash(1);
        plline(2, tx, ty);
        pllsty(1);
        plschr(0, 0.72);
        plcol0(PLOT_FG);
        plmtex("t", 0.9, (tx[0] - xl) / (xh - xl), 0.5, c->target_label);
        plschr(0, 1.0);
    }
    plcol0(PLOT_FG);
    plot_width(1.4);
    plbox("bclnst", 1, 0, "bc", 0, 0);
    plot_width(1.0);
    plschr(0, 0.9);
    plmtex("b", 2.8, 0.5, 0.5, c->bars_title);
    plschr(0, 1.0);

    /* bottom: ms per pass at the fixed N, stacked. Bars more than 10 times the
     * median (brute force, on the CPU and on the GL device) are cut, so that
     * the axis shows the others' passes; their totals are written in. */
    double total[BENCH_MAX_LEVELS] = {0}, sorted[BENCH_MAX_LEVELS];
    int nt = 0;
    for (int i = 0; i < c->nl; i++) {
        for (int p = 0; p < c->np; p++)
            if (isfinite(c->ms[i][p]) && c->ms[i][p] > 0) total[i] += c->ms[i][p];
        if (total[i] > 0) sorted[nt++] = total[i];
    }
    for (int i = 1; i < nt; i++) /* insertion sort: a few dozen levels at most */
        for (int j = i; j > 0 && sorted[j] < sorted[j - 1]; j--) {
            double t = sorted[j];
            sorted[j] = sorted[j - 1];
            sorted[j - 1] = t;
        }
    double keep = 0; /* the longest bar drawn whole */
    for (int i = 0; i < nt; i++)
        if (sorted[i] <= 10 * sorted[(nt - 1) / 2]) keep = sorted[i];
    double xmax = keep < (nt ? sorted[nt - 1] : 0) ? 1.3 * keep : 1.25 * keep;
    if (!(xmax > 0)) xmax = 1;
    plvpor(vx0, vx1, 0.10, 0.45);
    plwind(0, xmax, 0, nl);
    plcol0(PLOT_GRID);
    plot_width(1.0);
    plbox("g", 0, 0, "", 0, 0);
    for (int i = 0; i < c->nl; i++) {
        double yc = nl - 1 - i + 0.5, hh = 0.33, x = 0;
        for (int p = 0; p < c->np; p++) {
            double v = isfinite(c->ms[i][p]) && c->ms[i][p] > 0 ? c->ms[i][p] : 0;
            if (v <= 0 || x >= xmax) {
                x += v;
                continue;
            }
            fill_rect(x, fmin(x + v, xmax), yc - hh, yc + hh, p);
            x += v;
        }
        char label[64];
        if (total[i] > 0)
            snprintf(label, sizeof label, total[i] > xmax ? "%.4g ms (cut)" : "%.3g ms", total[i]);
        else
            snprintf(label, sizeof label, "not measured");
        plschr(0, 0.75);
        plcol0(PLOT_FG);
        if (total[i] > xmax)
            plptex(0.98 * xmax, yc, 1, 0, 1.0, label);
        else
            plptex(fmin(total[i], xmax) + 0.01 * xmax, yc, 1, 0, 0.0, label);
        plschr(0, 0.72);
        plmtex("lv", 0.8, yc / nl, 1.0, c->level[i]);
        plschr(0, 1.0);
    }
    plcol0(PLOT_FG);
    plot_width(1.4);
    plbox("bcnst", 0, 0, "bc", 0, 0);
    plot_width(1.0);
    plschr(0, 0.8); /* smaller than the top's: at 0.9 it ran under the legend */
    plmtex("b", 2.8, 0.5, 0.5, c->stack_title);
    plschr(0, 1.0);

    plot_key key[BENCH_CHART_PASSES];
    for (int p = 0; p < c->np; p++) key[p] = (plot_key){.text = c->pass[p], .style = p, .fill = true};
    plot_legend(key, c->np, NULL, 0, vx1 + 0.015, 0.992, 0.45);
}

/* ---- scaling: ms per step against N, log-log ----------------------------------- */

bool bench_chart_scaling(const bench_scaling_chart *c, const char *dir, const char *base)
{
    static plot_loglog L; /* about 3 kB: kept off the stack */
    memset(&L, 0, sizeof L);
    snprintf(L.title, sizeof L.title, "%s", c->title);
    snprintf(L.subtitle, sizeof L.subtitle, "%s", c->subtitle);
    snprintf(L.xlabel, sizeof L.xlabel, "particles N");
    snprintf(L.ylabel, sizeof L.ylabel, "time per step [ms]");
    for (int s = 0; s < c->ns && s < PLOT_MAX_CURVES; s++, L.nc++) {
        /* 8 styles (colour, dashes, marker): the second 8 levels with filled markers, the third with markers
         * alone, so that no two of the ladder's 23 curves look alike (L8 was drawn as L0) */
        L.c[s] = (plot_curve){.x = c->s[s].n, .y = c->s[s].ms, .n = (int)c->s[s].count, .style = s, .line = s < 16,
                              .markers = true, .filled = (s / 8) % 2 == 1};
        snprintf(L.c[s].label, sizeof L.c[s].label, "%s", c->s[s].label);
    }
    /* slopes 2 and 1: O(N^2) through brute force's last point (L0 or G0, where the pairs dominate; none
     * without it: it was drawn through whichever level came first), O(N) through the fastest series at the
     * largest N */
    for (int r = 0; r < 2; r++) {
        int best = -1;
        double bx = 0, by = 0;
        for (int s = 0; s < c->ns; s++) {
            const bench_scaling_series *S = &c->s[s];
            if (!S->count || !(S->n[S->count - 1] > 0) || !(S->ms[S->count - 1] > 0)) continue;
            double x = S->n[S->count - 1], y = S->ms[S->count - 1];
            const bool brute = strncmp(c->s[s].label, "L0 ", 3) == 0 || strncmp(c->s[s].label, "G0 ", 3) == 0;
            if (r == 0 && best < 0 && brute) best = s, bx = x, by = y;
            if (r == 1 && (best < 0 || x > bx * 1.01 || (x > bx * 0.99 && y < by))) best = s, bx = x, by = y;
        }
        if (best < 0 || (r == 1 && L.ng == 1 && L.g[0].x0 == bx && L.g[0].y0 == by)) continue;
        L.g[L.ng++] = (plot_guide){.x0 = bx, .y0 = by, .slope = r == 0 ? 2 : 1, .style = -1};
    }
    if (L.ng == 2)
        snprintf(L.g[0].label, sizeof L.g[0].label, "slopes 1 and 2: #[0x221d] N and #[0x221d] N#u2#d");
    else if (L.ng == 1)
        snprintf(L.g[0].label, sizeof L.g[0].label, "slope %d: #[0x221d] N%s", L.g[0].slope == 2 ? 2 : 1,
                 L.g[0].slope == 2 ? "#u2#d" : "");
    if (c->fps > 0) {
        plot_guide *g = &L.g[L.ng++];
        *g = (plot_guide){.x0 = 1, .y0 = 1000 / c->fps, .style = 2, .on_line = true};
        snprintf(g->label, sizeof g->label, "%g steps/s", c->fps);
    }
    return plot_chart(PLOT_LOGLOG, &L, dir, base, 1400, 900);
}

bool bench_chart_ladder(const bench_ladder_chart *c, const char *dir, const char *base)
{
    /* a row of each panel at least as tall as its label: with the 23 levels of the full ladder at 1000 pixels
     * the labels and the bars' numbers overlapped (a student's review); 12 rows fit in 1000 */
    const int height = c->nl > 12 ? (int)(1000.0 * c->nl / 12.0) : 1000;
    ladder_text_scale = (1400.0 + 1000.0) / (1400.0 + height); /* PLplot's text follows (width + height) / 2 */
    return plot_page(draw_ladder, c, dir, base, 1400, height);
}
