/* The benchmark's charts, drawn with PLplot's cairo driver as PNG and PDF and
 * staged through the plot module's output files (src/plot/plot_out.c).
 * They need what the plot module's chart types do not have yet: logarithmic
 * axes and stacked bars. Same look as the plot module's charts: white
 * background, black text, grey grid, curves told apart by line style and
 * marker as well as colour. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include <plplot.h>

#include "bench.h"
#include "plot.h"

enum { COL_BG = 0, COL_FG = 1, COL_GRID = 2, COL_REF = 3, COL_CURVE = 4, COL_FILL = 12, N_COLOURS = 28 };

static const unsigned char curve_rgb[8][3] = {
    {0, 0, 0}, {0, 84, 166}, {190, 30, 45}, {0, 120, 60}, {120, 50, 150}, {190, 100, 0}, {80, 80, 80}, {0, 130, 140},
};
/* Fills of the stacked bars: light, distinct colours (and hatching on every other). */
static const unsigned char fill_rgb[16][3] = {
    {166, 206, 227}, {31, 120, 180}, {178, 223, 138}, {51, 160, 44}, {251, 154, 153}, {227, 26, 28},
    {253, 191, 111}, {255, 127, 0},  {202, 178, 214}, {106, 61, 154}, {255, 255, 153}, {177, 89, 40},
    {200, 200, 200}, {120, 120, 120}, {141, 211, 199}, {190, 186, 218},
};
static const char *const marker[8] = {"#[0x25cb]", "#[0x25a1]", "#[0x25b3]", "#[0x25c7]",
                                      "#[0x00d7]", "+",         "#[0x25cf]", "#[0x25bd]"};
static const struct {
    int n;
    PLINT mark[2], space[2];
} dash[8] = {
    {0, {0}, {0}},           {1, {4500}, {2200}},       {1, {600}, {1400}},   {2, {4500, 600}, {1600, 1600}},
    {1, {9000}, {2600}},     {2, {9000, 2500}, {2000, 2000}}, {1, {1800}, {1500}}, {2, {4500, 1800}, {1400, 1400}},
};

static double g_scale = 1.0; /* the PDF is drawn at half the PNG's size: absolute lengths scale with it */

static void set_width(double w) { plwidth(w * g_scale); }

static void set_dash(int style)
{
    int s = ((style % 8) + 8) % 8;
    if (dash[s].n == 0) {
        pllsty(1);
        return;
    }
    PLINT mark[2], space[2];
    for (int i = 0; i < dash[s].n; i++) {
        mark[i] = (PLINT)(dash[s].mark[i] * g_scale);
        space[i] = (PLINT)(dash[s].space[i] * g_scale);
    }
    plstyl(dash[s].n, mark, space);
}

static void setup_colours(void)
{
    plscmap0n(N_COLOURS);
    plscol0(COL_BG, 255, 255, 255);
    plscol0(COL_FG, 0, 0, 0);
    plscol0(COL_GRID, 215, 215, 215);
    plscol0(COL_REF, 120, 120, 120);
    for (int i = 0; i < 8; i++) plscol0(COL_CURVE + i, curve_rgb[i][0], curve_rgb[i][1], curve_rgb[i][2]);
    for (int i = 0; i < 16; i++) plscol0(COL_FILL + i, fill_rgb[i][0], fill_rgb[i][1], fill_rgb[i][2]);
    plscolbg(255, 255, 255);
}

static void text_at(double x, double y, double scale, double just, const char *s)
{
    plschr(0, scale);
    plcol0(COL_FG);
    plptex(x, y, 1, 0, just, s);
    plschr(0, 1.0);
}

static void titles(const char *title, const char *subtitle)
{
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1);
    text_at(0.5, 0.965, 1.25, 0.5, title);
    if (subtitle && *subtitle) text_at(0.5, 0.932, 0.9, 0.5, subtitle);
}

static void fill_rect(double x0, double x1, double y0, double y1, int style)
{
    PLFLT fx[5] = {x0, x1, x1, x0, x0}, fy[5] = {y0, y0, y1, y1, y0};
    plcol0(COL_FILL + style % 16);
    plpsty(0);
    plfill(4, fx, fy);
    if (style % 2) { /* hatching on every other fill: tells neighbours apart in grey print */
        PLINT inc = style % 4 == 1 ? 450 : -450, del = (PLINT)(2500 * g_scale);
        plcol0(COL_FG);
        set_width(0.5);
        plpat(1, &inc, &del);
        plfill(4, fx, fy);
        plpsty(0);
    }
    plcol0(COL_FG);
    set_width(0.8);
    plline(5, fx, fy);
}

/* ---- the ladder: max N per level (log bars), ms per pass (stacked bars) ------ */

static void draw_ladder(const bench_ladder_chart *c)
{
    titles(c->title, c->subtitle);
    const int nl = c->nl > 0 ? c->nl : 1;
    const double vx0 = 0.37, vx1 = 0.80;

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
    plcol0(COL_GRID);
    set_width(1.0);
    pllsty(1);
    plbox("gl", 1, 0, "", 0, 0);
    for (int i = 0; i < c->nl; i++) {
        double yc = nl - 1 - i + 0.5, hh = 0.33;
        if (c->max_n[i] > 0) fill_rect(xl, log10(c->max_n[i]), yc - hh, yc + hh, 1);
        plschr(0, 0.8);
        plcol0(COL_FG);
        plptex((c->max_n[i] > 0 ? log10(c->max_n[i]) : xl) + 0.02 * (xh - xl), yc, 1, 0, 0.0, c->note[i]);
        plschr(0, 0.72);
        plmtex("lv", 0.8, yc / nl, 1.0, c->level[i]);
        plschr(0, 1.0);
    }
    if (c->target_n > 0) {
        PLFLT tx[2] = {log10(c->target_n), log10(c->target_n)}, ty[2] = {0, nl};
        plcol0(COL_CURVE + 2);
        set_width(1.6);
        set_dash(1);
        plline(2, tx, ty);
        pllsty(1);
        plschr(0, 0.72);
        plcol0(COL_FG);
        plmtex("t", 0.9, (tx[0] - xl) / (xh - xl), 0.5, c->target_label);
        plschr(0, 1.0);
    }
    plcol0(COL_FG);
    set_width(1.4);
    plbox("bclnst", 1, 0, "bc", 0, 0);
    set_width(1.0);
    plschr(0, 0.9);
    plmtex("b", 2.8, 0.5, 0.5, c->bars_title);
    plschr(0, 1.0);

    /* bottom: ms per pass at the fixed N, stacked; a bar far longer than the others is cut */
    double total[BENCH_MAX_LEVELS] = {0}, big = 0, second = 0;
    for (int i = 0; i < c->nl; i++) {
        for (int p = 0; p < c->np; p++)
            if (isfinite(c->ms[i][p]) && c->ms[i][p] > 0) total[i] += c->ms[i][p];
        if (total[i] > big) second = big, big = total[i];
        else if (total[i] > second) second = total[i];
    }
    double xmax = big > 3 * second && second > 0 ? 1.3 * second : 1.25 * big;
    if (!(xmax > 0)) xmax = 1;
    plvpor(vx0, vx1, 0.10, 0.45);
    plwind(0, xmax, 0, nl);
    plcol0(COL_GRID);
    set_width(1.0);
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
        plcol0(COL_FG);
        if (total[i] > xmax)
            plptex(0.98 * xmax, yc, 1, 0, 1.0, label);
        else
            plptex(fmin(total[i], xmax) + 0.01 * xmax, yc, 1, 0, 0.0, label);
        plschr(0, 0.72);
        plmtex("lv", 0.8, yc / nl, 1.0, c->level[i]);
        plschr(0, 1.0);
    }
    plcol0(COL_FG);
    set_width(1.4);
    plbox("bcnst", 0, 0, "bc", 0, 0);
    set_width(1.0);
    plschr(0, 0.9);
    plmtex("b", 2.8, 0.5, 0.5, c->stack_title);
    plschr(0, 1.0);

    /* legend of the passes, beside the stacked bars */
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1);
    double row = 0.029, x0 = vx1 + 0.015, y = 0.45 - 0.5 * row;
    for (int p = 0; p < c->np; p++, y -= row) {
        fill_rect(x0, x0 + 0.035, y - 0.35 * row, y + 0.35 * row, p);
        text_at(x0 + 0.045, y, 0.75, 0.0, c->pass[p]);
    }
}

/* ---- scaling: ms per step against N, log-log ----------------------------------- */

static void draw_scaling(const bench_scaling_chart *c)
{
    titles(c->title, c->subtitle);
    double xlo = INFINITY, xhi = 0, ylo = INFINITY, yhi = 0;
    for (int s = 0; s < c->ns; s++)
        for (size_t i = 0; i < c->s[s].count; i++)
            if (c->s[s].n[i] > 0 && c->s[s].ms[i] > 0) {
                xlo = fmin(xlo, c->s[s].n[i]), xhi = fmax(xhi, c->s[s].n[i]);
                ylo = fmin(ylo, c->s[s].ms[i]), yhi = fmax(yhi, c->s[s].ms[i]);
            }
    if (!(xhi > 0)) xlo = 1, xhi = 10, ylo = 1, yhi = 10;
    if (c->fps > 0) ylo = fmin(ylo, 1000 / c->fps), yhi = fmax(yhi, 1000 / c->fps);
    double lx0 = floor(log10(xlo)), lx1 = ceil(log10(xhi)), ly0 = floor(log10(ylo)), ly1 = ceil(log10(yhi));
    if (lx1 <= lx0) lx1 = lx0 + 1;
    if (ly1 <= ly0) ly1 = ly0 + 1;
    const double vx0 = 0.10, vx1 = 0.62, vy0 = 0.10, vy1 = 0.89;
    plvpor(vx0, vx1, vy0, vy1);
    plwind(lx0, lx1, ly0, ly1);
    plcol0(COL_GRID);
    set_width(1.0);
    pllsty(1);
    plbox("gl", 1, 0, "gl", 1, 0);

    /* slopes 2 and 1: O(N^2) through the first series' last point (brute
     * force, where its pairs dominate), O(N) through the fastest series at
     * the largest N */
    for (int r = 0; r < 2; r++) {
        int best = -1;
        double bx = 0, by = 0;
        for (int s = 0; s < c->ns; s++) {
            const bench_scaling_series *S = &c->s[s];
            if (!S->count || !(S->n[S->count - 1] > 0) || !(S->ms[S->count - 1] > 0)) continue;
            double x = S->n[S->count - 1], y = S->ms[S->count - 1];
            if (r == 0 && best < 0) best = s, bx = x, by = y;
            if (r == 1 && (best < 0 || x > bx * 1.01 || (x > bx * 0.99 && y < by))) best = s, bx = x, by = y;
        }
        if (best < 0 || (r == 1 && best == 0)) continue;
        double slope = r == 0 ? 2 : 1, x0 = log10(bx), y0 = log10(by);
        PLFLT rx[2] = {lx0, lx1}, ry[2] = {y0 + slope * (lx0 - x0), y0 + slope * (lx1 - x0)};
        plcol0(COL_REF);
        set_width(1.0);
        set_dash(2);
        plline(2, rx, ry);
        pllsty(1);
        plschr(0, 1.0);
    }
    if (c->fps > 0) {
        char lab[64];
        double y = log10(1000 / c->fps);
        PLFLT fx[2] = {lx0, lx1}, fy[2] = {y, y};
        plcol0(COL_CURVE + 2);
        set_width(1.2);
        set_dash(1);
        plline(2, fx, fy);
        pllsty(1);
        snprintf(lab, sizeof lab, "%g steps/s", c->fps);
        plschr(0, 0.75);
        plptex(lx0 + 0.02 * (lx1 - lx0), y + 0.02 * (ly1 - ly0), 1, 0, 0.0, lab);
    }
    plschr(0, 1.0);
    for (int s = 0; s < c->ns; s++) {
        const bench_scaling_series *S = &c->s[s];
        PLFLT *px = malloc((S->count + 1) * sizeof *px), *py = malloc((S->count + 1) * sizeof *py);
        if (!px || !py) {
            free(px);
            free(py);
            continue;
        }
        int m = 0;
        for (size_t i = 0; i < S->count; i++)
            if (S->n[i] > 0 && S->ms[i] > 0) px[m] = log10(S->n[i]), py[m++] = log10(S->ms[i]);
        plcol0(COL_CURVE + s % 8);
        set_width(2.0);
        set_dash(s);
        if (m > 1) plline(m, px, py);
        pllsty(1);
        plschr(0, 0.8);
        plstring(m, px, py, marker[s % 8]);
        plschr(0, 1.0);
        free(px);
        free(py);
    }
    plcol0(COL_FG);
    set_width(1.4);
    plbox("bclnst", 1, 0, "bclnstv", 1, 0);
    set_width(1.0);
    plmtex("l", 4.2, 0.5, 0.5, "time per step [ms]");
    plmtex("b", 3.0, 0.5, 0.5, "particles N");

    /* legend */
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1);
    double row = 0.036, x0 = vx1 + 0.02, y = vy1 - 0.5 * row;
    for (int s = 0; s < c->ns; s++, y -= row) {
        PLFLT lx[2] = {x0, x0 + 0.05}, ly[2] = {y, y}, mx = x0 + 0.025, my = y;
        plcol0(COL_CURVE + s % 8);
        set_width(2.0);
        set_dash(s);
        plline(2, lx, ly);
        pllsty(1);
        plschr(0, 0.8);
        plstring(1, &mx, &my, marker[s % 8]);
        text_at(x0 + 0.06, y, 0.62, 0.0, c->s[s].label);
    }
    if (c->ns > 0) { /* the reference slopes */
        PLFLT lx[2] = {x0, x0 + 0.05}, ly[2] = {y, y};
        plcol0(COL_REF);
        set_width(1.0);
        set_dash(2);
        plline(2, lx, ly);
        pllsty(1);
        text_at(x0 + 0.06, y, 0.62, 0.0, "slopes 1 and 2: #[0x221d] N and #[0x221d] N#u2#d");
    }
}

/* ---- devices and files --------------------------------------------------------- */

static int on_plplot_exit(PLCHAR_VECTOR msg)
{
    fprintf(stderr, "sphlab bench: PLplot stopped: %s\n", msg ? msg : "");
    plot_out_abort();
    return 1;
}

static bool have_device(const char *name)
{
    const char *menu_a[64], *devs_a[64];
    const char **menu = menu_a, **devs = devs_a;
    int n = 64;
    plgDevs(&menu, &devs, &n);
    for (int i = 0; i < n; i++)
        if (strcmp(devs[i], name) == 0) return true;
    return false;
}

typedef void (*draw_fn)(const void *chart);
static void draw_ladder_v(const void *c) { draw_ladder(c); }
static void draw_scaling_v(const void *c) { draw_scaling(c); }

static bool chart(draw_fn draw, const void *c, const char *dir, const char *base, int w, int h)
{
    for (int i = 0; i < 2; i++)
        if (!have_device(i ? "pdfcairo" : "pngcairo")) {
            fprintf(stderr, "sphlab bench: PLplot has no %s driver (Debian: apt-get install plplot-driver-cairo)\n",
                    i ? "pdfcairo" : "pngcairo");
            return false;
        }
    for (int i = 0; i < 2; i++) {
        char file[300];
        snprintf(file, sizeof file, "%s.%s", base, i ? "pdf" : "png");
        const char *tmp = plot_out_stage(dir, file);
        if (!tmp) return false;
        g_scale = i ? 0.5 : 1.0;
        plsexit(on_plplot_exit);
        plsdev(i ? "pdfcairo" : "pngcairo");
        plsfnam(tmp);
        if (i)
            plspage(0, 0, (w + 1) / 2, (h + 1) / 2, 0, 0); /* points: the PNG is the PDF at 144 dpi */
        else
            plspage(0, 0, w, h, 0, 0);
        setup_colours();
        plinit();
        pladv(0);
        plschr(0, 1.0);
        draw(c);
        plend();
    }
    return true;
}

bool bench_chart_ladder(const bench_ladder_chart *c, const char *dir, const char *base)
{
    return chart(draw_ladder_v, c, dir, base, 1400, 1000);
}

bool bench_chart_scaling(const bench_scaling_chart *c, const char *dir, const char *base)
{
    return chart(draw_scaling_v, c, dir, base, 1400, 900);
}
