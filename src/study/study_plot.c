/* Log-log charts for the study, in the style of sphlab plot (docs/figures.md):
 * white background, black axes and text, a light grey grid, a title and a
 * subtitle, the legend beside the plot area; curves told apart by colour,
 * line style and marker. Axes are logarithmic and span whole decades, so
 * every axis carries at least two labelled powers of ten.
 *
 * The colours, dashes and markers repeat src/plot/plot_draw.c's tables
 * (that module has no log-log chart; they would move there with one). */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <plplot.h>

#include "plot.h"
#include "study_plot.h"

enum { COL_BG = 0, COL_FG = 1, COL_GRID = 2, COL_CURVE = 4, N_COLOURS = 12 };

static const unsigned char curve_rgb[8][3] = {
    {0, 0, 0}, {0, 84, 166}, {190, 30, 45}, {0, 120, 60}, {120, 50, 150}, {190, 100, 0}, {80, 80, 80}, {0, 130, 140},
};

static const struct {
    int n;
    PLINT mark[3], space[3];
} line_style[8] = {
    {0, {0}, {0}},
    {1, {4500}, {2200}},
    {1, {600}, {1400}},
    {2, {4500, 600}, {1600, 1600}},
    {1, {9000}, {2600}},
    {3, {4500, 600, 600}, {1400, 1400, 1400}},
    {1, {1800}, {1500}},
    {2, {9000, 2500}, {2000, 2000}},
};

/* open markers, and the filled ones used for emphasis */
static const char *const marker[8] = {
    "#[0x25cb]", "#[0x25a1]", "#[0x25b3]", "#[0x25c7]", "#[0x00d7]", "+", "#[0x25cf]", "#[0x25bd]",
};
static const char *const marker_filled[8] = {
    "#[0x25cf]", "#[0x25a0]", "#[0x25b2]", "#[0x25c6]", "#[0x00d7]", "+", "#[0x25cf]", "#[0x25bc]",
};

static double g_scale = 1.0;

static void set_width(double w) { plwidth(w * g_scale); }

static void set_line_style(int style)
{
    int s = ((style % 8) + 8) % 8;
    if (line_style[s].n == 0) {
        pllsty(1);
        return;
    }
    PLINT mark[3], space[3];
    for (int i = 0; i < line_style[s].n; i++) {
        mark[i] = (PLINT)(line_style[s].mark[i] * g_scale);
        space[i] = (PLINT)(line_style[s].space[i] * g_scale);
    }
    plstyl(line_style[s].n, mark, space);
}

static void setup_colours(void)
{
    plscmap0n(N_COLOURS);
    plscol0(COL_BG, 255, 255, 255);
    plscol0(COL_FG, 0, 0, 0);
    plscol0(COL_GRID, 215, 215, 215);
    plscol0(3, 110, 110, 110);
    for (int i = 0; i < 8; i++) plscol0(COL_CURVE + i, curve_rgb[i][0], curve_rgb[i][1], curve_rgb[i][2]);
    plscolbg(255, 255, 255);
}

/* Page-relative text: the scale at which s fits in `width` (fraction of the page). */
static double fit_scale(const char *s, double scale, double width)
{
    PLFLT def, ht, x0, x1, y0, y1;
    plgchr(&def, &ht);
    plgspa(&x0, &x1, &y0, &y1);
    int n = 0;
    for (const char *p = s; *p; p++) {
        if (p[0] == '#' && p[1] == '[') {
            const char *e = strchr(p, ']');
            if (e) p = e;
            n++;
        } else if (p[0] == '#' && (p[1] == 'u' || p[1] == 'd')) {
            p++;
        } else {
            n += ((unsigned char)*p & 0xC0) != 0x80;
        }
    }
    double est = n * 0.7 * def * scale / (x1 - x0);
    return est > width ? scale * width / est : scale;
}

static double line_height(void)
{
    PLFLT def, ht, x0, x1, y0, y1;
    plgchr(&def, &ht);
    plgspa(&x0, &x1, &y0, &y1);
    return ht / (y1 - y0);
}

static void page_text(double x, double y, double scale, double just, const char *s)
{
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1);
    plschr(0, fit_scale(s, scale, 0.97));
    plcol0(COL_FG);
    plptex(x, y, 1, 0, just, s);
    plschr(0, 1.0);
}

/* Whole decades around the positive finite values of the curves. */
static void decades(const study_chart *c, bool x, double *lo, double *hi)
{
    double mn = INFINITY, mx = -INFINITY;
    for (int k = 0; k < c->nc; k++)
        for (int i = 0; i < c->c[k].n; i++) {
            double v = x ? c->c[k].x[i] : c->c[k].y[i], other = x ? c->c[k].y[i] : c->c[k].x[i];
            if (!(v > 0) || !isfinite(v) || !(other > 0) || !isfinite(other)) continue;
            mn = fmin(mn, v);
            mx = fmax(mx, v);
        }
    if (!(mn <= mx)) {
        *lo = 0;
        *hi = 1;
        return;
    }
    *lo = floor(log10(mn) + 1e-9);
    *hi = ceil(log10(mx) - 1e-9);
    if (*hi <= *lo) *hi = *lo + 1;
}

static bool point_ok(const study_curve *s, int i)
{
    return s->x[i] > 0 && s->y[i] > 0 && isfinite(s->x[i]) && isfinite(s->y[i]);
}

static void draw(const study_chart *c)
{
    const double vx0 = 0.11, vx1 = 0.66, vy0 = 0.11, vy1 = 0.875;
    double xlo, xhi, ylo, yhi;
    decades(c, true, &xlo, &xhi);
    decades(c, false, &ylo, &yhi);
    page_text(0.5, 0.962, 1.3, 0.5, c->title);
    if (c->subtitle[0]) page_text(0.5, 0.922, 0.95, 0.5, c->subtitle);

    plvpor(vx0, vx1, vy0, vy1);
    plwind(xlo, xhi, ylo, yhi);
    plcol0(COL_GRID);
    set_width(1.0);
    pllsty(1);
    plbox("gl", 1, 0, "gl", 1, 0);
    for (int k = 0; k < c->nc; k++) {
        const study_curve *s = &c->c[k];
        PLFLT *px = malloc((size_t)(s->n ? s->n : 1) * sizeof *px), *py = malloc((size_t)(s->n ? s->n : 1) * sizeof *py);
        if (!px || !py) {
            free(px);
            free(py);
            continue;
        }
        int m = 0;
        for (int i = 0; i < s->n; i++)
            if (point_ok(s, i)) px[m] = log10(s->x[i]), py[m++] = log10(s->y[i]);
        plcol0(COL_CURVE + s->style % 8);
        if (s->line && m > 1) {
            set_width(2.2);
            set_line_style(s->solid ? 0 : s->style);
            plline(m, px, py);
            pllsty(1);
        }
        if (s->markers) {
            plschr(0, s->filled ? 1.0 : 0.9);
            for (int i = 0; i < m; i++) plstring(1, &px[i], &py[i], (s->filled ? marker_filled : marker)[s->style % 8]);
        }
        if (s->numbers) {
            plschr(0, 0.62);
            plcol0(COL_FG);
            int j = 0;
            double dx = 0.012 * (xhi - xlo), dy = 0.012 * (yhi - ylo);
            for (int i = 0; i < s->n; i++) {
                if (!point_ok(s, i)) continue;
                char num[16];
                snprintf(num, sizeof num, "%d", s->numbers[i]);
                plptex(px[j] + dx, py[j] + dy, 1, 0, 0.0, num);
                j++;
            }
        }
        plschr(0, 1.0);
        free(px);
        free(py);
    }
    plcol0(COL_FG);
    set_width(1.6);
    pllsty(1);
    plbox("bclnst", 1, 0, "bclnstv", 1, 0);
    set_width(1.0);
    plmtex("l", 4.2, 0.5, 0.5, c->ylabel);
    plmtex("b", 3.0, 0.5, 0.5, c->xlabel);

    /* legend and notes, right of the plot area */
    const double lx0 = vx1 + 0.02, lx1 = 0.992, ts = 0.8;
    double row = 1.8 * ts * line_height(), pad = 0.5 * row;
    int rows = c->nc + c->nn;
    double y1 = vy1, y0 = y1 - rows * row - 2 * pad;
    if (y0 < 0.01) y0 = 0.01;
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1);
    PLFLT bx[5] = {lx0, lx1, lx1, lx0, lx0}, by[5] = {y0, y0, y1, y1, y0};
    plcol0(COL_BG);
    plpsty(0);
    plfill(4, bx, by);
    plcol0(COL_FG);
    set_width(1.0);
    plline(5, bx, by);
    double w = lx1 - lx0, sx0 = lx0 + 0.04 * w, sx1 = lx0 + 0.2 * w, tx = lx0 + 0.24 * w;
    for (int k = 0; k < c->nc; k++) {
        const study_curve *s = &c->c[k];
        double y = y1 - pad - (k + 0.5) * row;
        plcol0(COL_CURVE + s->style % 8);
        if (s->line) {
            PLFLT lx[2] = {sx0, sx1}, ly[2] = {y, y};
            set_width(2.2);
            set_line_style(s->solid ? 0 : s->style);
            plline(2, lx, ly);
            pllsty(1);
        }
        if (s->markers) {
            PLFLT mx = 0.5 * (sx0 + sx1), my = y;
            plschr(0, 0.9);
            plstring(1, &mx, &my, (s->filled ? marker_filled : marker)[s->style % 8]);
        }
        plcol0(COL_FG);
        plschr(0, fit_scale(s->label, ts, lx1 - tx - 0.005));
        plptex(tx, y, 1, 0, 0.0, s->label);
    }
    for (int i = 0; i < c->nn; i++) {
        double y = y1 - pad - (c->nc + i + 0.5) * row;
        plcol0(COL_FG);
        plschr(0, fit_scale(c->note[i], 0.7, lx1 - sx0 - 0.005));
        plptex(sx0, y, 1, 0, 0.0, c->note[i]);
    }
    plschr(0, 1.0);
}

static int on_plplot_exit(PLCHAR_VECTOR msg)
{
    fprintf(stderr, "sphlab study: PLplot stopped: %s\n", msg ? msg : "");
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

static void render(const study_chart *c, const char *dev, const char *file, int w, int h, double scale)
{
    g_scale = scale;
    plsexit(on_plplot_exit);
    plsdev(dev);
    plsfnam(file);
    plspage(0, 0, w, h, 0, 0);
    setup_colours();
    plinit();
    pladv(0);
    plschr(0, 1.0);
    draw(c);
    plend();
}

/* cairo writes the time of day into the PDF (/CreationDate (D:YYYYMMDDHHMMSS):
 * overwrite the 14 digits with SOURCE_DATE_EPOCH or 1970-01-01, as sphlab plot does. */
static bool fix_pdf_date(const char *path)
{
    FILE *f = fopen(path, "r+b");
    if (!f) return false;
    static char buf[1 << 20];
    size_t n = fread(buf, 1, sizeof buf - 1, f);
    buf[n] = '\0';
    const char key[] = "/CreationDate (D:";
    char *p = NULL;
    for (size_t i = 0; i + sizeof key <= n; i++)
        if (memcmp(buf + i, key, sizeof key - 1) == 0) p = buf + i + sizeof key - 1;
    bool ok = true;
    if (p && p + 14 <= buf + n) {
        time_t when = 0;
        const char *sde = getenv("SOURCE_DATE_EPOCH");
        if (sde && *sde) when = (time_t)strtoll(sde, NULL, 10);
        struct tm tm;
        char date[32];
        if (gmtime_r(&when, &tm) && strftime(date, sizeof date, "%Y%m%d%H%M%S", &tm) == 14)
            ok = fseek(f, (long)(p - buf), SEEK_SET) == 0 && fwrite(date, 1, 14, f) == 14;
    }
    ok &= fclose(f) == 0;
    return ok;
}

bool study_chart_loglog(const study_chart *c, const char *dir, const char *base, int width, int height)
{
    for (int i = 0; i < 2; i++) {
        const char *dev = i ? "pdfcairo" : "pngcairo";
        if (!have_device(dev)) {
            fprintf(stderr, "sphlab study: PLplot has no %s driver (Debian: apt-get install plplot-driver-cairo)\n", dev);
            return false;
        }
    }
    char png[300], pdf[300];
    snprintf(png, sizeof png, "%s.png", base);
    snprintf(pdf, sizeof pdf, "%s.pdf", base);
    const char *png_tmp = plot_out_stage(dir, png);
    if (!png_tmp) return false;
    const char *pdf_tmp = plot_out_stage(dir, pdf);
    if (!pdf_tmp) return false;
    render(c, "pngcairo", png_tmp, width, height, 1.0);
    render(c, "pdfcairo", pdf_tmp, (width + 1) / 2, (height + 1) / 2, 0.5);
    if (!fix_pdf_date(pdf_tmp)) {
        fprintf(stderr, "sphlab study: %s/%s: cannot finish the PDF\n", dir, pdf);
        return false;
    }
    return true;
}
