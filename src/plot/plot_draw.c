/* The chart types, drawn with PLplot's cairo driver (pngcairo, pdfcairo).
 *
 * Style, for print in black and white: white background, black axes and
 * text, light grey grid; curves differ by line style (solid, dashed, dotted,
 * dash-dot, ...) and by marker (circle, square, triangle, ...) as well as by
 * colour; filled areas and bars differ by grey level and hatching. Legends
 * are drawn beside the plot area, never over the data. The study's and the
 * bench's charts are drawn here too (log-log) or with the public pieces
 * (plot_page, plot_fill, plot_legend, ...), so that the tables below are
 * the only ones. The pages and their files (PNG, PDF, SVG) are plot_page.c. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include <plplot.h>

#include "plot.h"

/* ---- palette and styles ---------------------------------------------------- */

enum { N_COLOURS = PLOT_FILL + 12 }; /* the colour indices are in plot.h */

static const unsigned char curve_rgb[8][3] = {
    {0, 0, 0}, {0, 84, 166}, {190, 30, 45}, {0, 120, 60}, {120, 50, 150}, {190, 100, 0}, {80, 80, 80}, {0, 130, 140},
};

/* Line styles as PLplot mark/space lengths in micrometres (0 marks: solid). */
static const struct {
    int n;
    PLINT mark[3], space[3];
} line_style[8] = {
    {0, {0}, {0}},                                /* solid */
    {1, {4500}, {2200}},                          /* dashed */
    {1, {600}, {1400}},                           /* dotted */
    {2, {4500, 600}, {1600, 1600}},               /* dash-dot */
    {1, {9000}, {2600}},                          /* long dashes */
    {3, {4500, 600, 600}, {1400, 1400, 1400}},    /* dash-dot-dot */
    {1, {1800}, {1500}},                          /* short dashes */
    {2, {9000, 2500}, {2000, 2000}},              /* long-short */
};

/* Markers: circle, square, triangle, diamond, cross, plus, filled circle, down
 * triangle (style % 8), drawn as shapes centred on their point. They were the
 * font's glyphs (plstring), whose em box, not the shape, is centred: a circle
 * at u = 0 sat 2 to 3 pixels below the line it marks. */
static void draw_marker_at(PLFLT x, PLFLT y, int style, bool filled, double kx, double ky)
{
    enum { RING = 24 };
    const double two_pi = 6.283185307179586;
    PLFLT px[RING + 1], py[RING + 1];
    int n = 0, shape = ((style % 8) + 8) % 8;
    filled |= shape == 6;
    switch (shape) {
    case 0:
    case 6:
        for (int i = 0; i <= RING; i++) px[n] = x + kx * cos(two_pi * i / RING), py[n++] = y + ky * sin(two_pi * i / RING);
        break;
    case 1: { /* the square's area near the circle's */
        const PLFLT sx[5] = {-0.85, 0.85, 0.85, -0.85, -0.85}, sy[5] = {-0.85, -0.85, 0.85, 0.85, -0.85};
        for (int i = 0; i < 5; i++) px[n] = x + kx * sx[i], py[n++] = y + ky * sy[i];
        break;
    }
    case 2:
    case 7: { /* the triangle's centroid on the point; 7 points down */
        const double up = shape == 2 ? 1.0 : -1.0;
        const PLFLT sx[4] = {0, 0.95, -0.95, 0}, sy[4] = {1.1, -0.55, -0.55, 1.1};
        for (int i = 0; i < 4; i++) px[n] = x + kx * sx[i], py[n++] = y + up * ky * sy[i];
        break;
    }
    case 3: {
        const PLFLT sx[5] = {0, 1.1, 0, -1.1, 0}, sy[5] = {1.1, 0, -1.1, 0, 1.1};
        for (int i = 0; i < 5; i++) px[n] = x + kx * sx[i], py[n++] = y + ky * sy[i];
        break;
    }
    default: { /* 4: a cross, 5: a plus: two strokes, never filled */
        const double d = shape == 4 ? 0.75 : 1.05, c = shape == 4 ? 1.0 : 0.0;
        PLFLT ax[2] = {x - kx * d, x + kx * d}, ay[2] = {y - c * ky * d, y + c * ky * d};
        PLFLT bx[2] = {x - c * kx * d, x + c * kx * d}, by[2] = {y + ky * d, y - ky * d};
        plline(2, ax, ay);
        plline(2, bx, by);
        return;
    }
    }
    if (filled) {
        plpsty(0); /* solid, whatever hatch a bar left set */
        plfill(n - 1, px, py);
    }
    plline(n, px, py);
}

/* n markers at (x, y) in the current viewport's world units (log10 values on
 * a log axis), as large as a glyph at the character height times size. */
static void draw_markers_at(int n, const PLFLT *x, const PLFLT *y, int style, bool filled, double size)
{
    PLFLT vx0, vx1, vy0, vy1, wx0, wx1, wy0, wy1, sx0, sx1, sy0, sy1, ch_def, ch;
    plgvpd(&vx0, &vx1, &vy0, &vy1); /* the viewport on the page, 0 to 1 */
    plgvpw(&wx0, &wx1, &wy0, &wy1); /* its world window */
    plgspa(&sx0, &sx1, &sy0, &sy1); /* the page in mm */
    plgchr(&ch_def, &ch);
    const double mmx = (vx1 - vx0) * (sx1 - sx0), mmy = (vy1 - vy0) * (sy1 - sy0);
    if (!(mmx > 0) || !(mmy > 0)) return;
    const double r = 0.36 * ch_def * size; /* mm */
    const double kx = r * (wx1 - wx0) / mmx, ky = r * (wy1 - wy0) / mmy;
    plot_width(1.3);
    for (int i = 0; i < n; i++)
        if (isfinite(x[i]) && isfinite(y[i])) draw_marker_at(x[i], y[i], style, filled, kx, ky);
}

/* Fills: a grey level (0-255) and a PLplot hatch pattern (0: none), all
 * combinations distinct; hatching is drawn in black over the grey. */
static const struct {
    unsigned char grey;
    int pattern;
} fill_style[12] = {
    {225, 0}, {255, 3}, {140, 0}, {205, 4}, {255, 8}, {90, 0},
    {235, 1}, {175, 3}, {255, 7}, {205, 2}, {120, 0}, {255, 5},
};

/* PLplot's PDF page is half the PNG's size in mm (same layout); lengths that
 * PLplot keeps absolute (line widths, dashes, hatch spacing) are scaled by
 * this so that the PDF looks like the PNG. */
static double g_scale = 1.0;

void plot_width(double w) { plwidth(w * g_scale); }

void plot_dash(int style)
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

/* PLplot's hatch patterns 1-8 (angle in tenths of a degree, spacing in
 * micrometres), with the spacing scaled; 0: solid. */
static void set_pattern(int pattern)
{
    static const struct {
        int n;
        PLINT inc[2], del[2];
    } pat[9] = {
        {0, {0, 0}, {0, 0}},       {1, {0, 0}, {2000, 0}},       {1, {900, 0}, {2000, 0}},
        {1, {450, 0}, {2000, 0}},  {1, {-450, 0}, {2000, 0}},    {1, {300, 0}, {2000, 0}},
        {1, {-300, 0}, {2000, 0}}, {2, {0, 900}, {2000, 2000}}, {2, {450, -450}, {2000, 2000}},
    };
    if (pattern <= 0 || pattern > 8) {
        plpsty(0);
        return;
    }
    PLINT del[2] = {(PLINT)(pat[pattern].del[0] * g_scale), (PLINT)(pat[pattern].del[1] * g_scale)};
    PLINT inc[2] = {pat[pattern].inc[0], pat[pattern].inc[1]};
    plpat(pat[pattern].n, inc, del);
}

/* A curve's colour and dashes (solid: none); style -1 is a guide's grey dots. */
static void pen(int style, bool solid)
{
    plcol0(style < 0 ? PLOT_REF : PLOT_CURVE + style % 8);
    plot_dash(style < 0 ? 2 : solid ? 0 : style);
}

void plot_fill(int n, const double *x, const double *y, int style)
{
    int f = ((style % 12) + 12) % 12;
    plcol0(PLOT_FILL + f);
    set_pattern(0);
    plfill(n, x, y);
    if (fill_style[f].pattern) {
        plcol0(PLOT_FG);
        set_pattern(fill_style[f].pattern);
        plfill(n, x, y);
        set_pattern(0);
    }
}

/* Before plinit: the page's colour map, and the scale of the lengths
 * PLplot keeps absolute (the PDF's page is half the PNG's). */
void plot_style_start(double scale)
{
    g_scale = scale;
    plscmap0n(N_COLOURS);
    plscol0(PLOT_BG, 255, 255, 255);
    plscol0(PLOT_FG, 0, 0, 0);
    plscol0(PLOT_GRID, 215, 215, 215);
    plscol0(PLOT_REF, 110, 110, 110);
    for (int i = 0; i < 8; i++) plscol0(PLOT_CURVE + i, curve_rgb[i][0], curve_rgb[i][1], curve_rgb[i][2]);
    for (int i = 0; i < 12; i++) plscol0(PLOT_FILL + i, fill_style[i].grey, fill_style[i].grey, fill_style[i].grey);
    plscolbg(255, 255, 255);
}

void plot_escape(char *dst, size_t cap, const char *s)
{
    size_t n = 0;
    for (; *s && n + 2 < cap; s++) {
        if (*s == '#') dst[n++] = '#';
        dst[n++] = *s;
    }
    if (cap) dst[n < cap ? n : cap - 1] = '\0';
}

/* ---- page geometry --------------------------------------------------------- */

/* Height of one line of text at scale 1, in normalised page coordinates. */
static double line_height(void)
{
    PLFLT def, ht, x0, x1, y0, y1;
    plgchr(&def, &ht);
    plgspa(&x0, &x1, &y0, &y1);
    return ht / (y1 - y0);
}

/* The bottom of the plot area: at least `frac` of the page, and room below
 * the axis for the x-axis title written `disp` character heights under it
 * (plmtex) and the title's own height. PLplot keeps the character height
 * in mm whatever the page, so a short page needs a larger fraction. */
static double bottom_room(double frac, double disp)
{
    return fmax(frac, (disp + 1.3) * line_height());
}

/* Visible characters of a PLplot string: #[0x...] and #gX count one, #u #d none. */
static int visible_chars(const char *s)
{
    int n = 0;
    while (*s) {
        if (s[0] == '#' && s[1] == '[') {
            const char *e = strchr(s, ']');
            s = e ? e + 1 : s + 2;
            n++;
        } else if (s[0] == '#' && (s[1] == 'u' || s[1] == 'd')) {
            s += 2;
        } else if (s[0] == '#' && s[1] == 'g' && s[2]) {
            s += 3;
            n++;
        } else if (s[0] == '#' && s[1] == '#') {
            s += 2;
            n++;
        } else {
            n += ((unsigned char)*s & 0xC0) != 0x80; /* UTF-8: count lead bytes */
            s++;
        }
    }
    return n;
}

/* The text scale, at most `scale`, at which s fits in `width` (a fraction of
 * the page width). Estimate: a DejaVu Sans character is about 0.7 of the
 * character height wide. */
static double fit_scale(const char *s, double scale, double width)
{
    PLFLT def, ht, x0, x1, y0, y1;
    plgchr(&def, &ht);
    plgspa(&x0, &x1, &y0, &y1);
    double est = visible_chars(s) * 0.7 * def * scale / (x1 - x0);
    return est > width ? scale * width / est : scale;
}

/* The same along the page's height: the scale, at most `scale`, at which a
 * y-axis title s fits in `height` (a fraction of the page height), so the
 * titles of stacked panels do not run into each other. */
static double fit_scale_height(const char *s, double scale, double height)
{
    PLFLT def, ht, x0, x1, y0, y1;
    plgchr(&def, &ht);
    plgspa(&x0, &x1, &y0, &y1);
    double est = visible_chars(s) * 0.7 * def * scale / (y1 - y0);
    return est > height ? scale * height / est : scale;
}

static void page_text(double x, double y, double scale, double just, const char *s)
{
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1);
    plschr(0, fit_scale(s, scale, 0.97));
    plcol0(PLOT_FG);
    plptex(x, y, 1, 0, just, s);
    plschr(0, 1.0);
}

void plot_titles(const char *title, const char *subtitle)
{
    page_text(0.5, 0.962, 1.3, 0.5, title);
    /* a superscript (PLplot's #u, as in 16^2) rises into the title's line: such a subtitle sits a little lower */
    if (subtitle && *subtitle) page_text(0.5, strstr(subtitle, "#u") ? 0.914 : 0.922, 0.95, 0.5, subtitle);
}

/* ---- data ranges ----------------------------------------------------------- */

typedef struct range {
    double lo, hi;
} range;

static range range_empty(void) { return (range){INFINITY, -INFINITY}; }
static void range_add(range *r, double v)
{
    if (!isfinite(v)) return;
    if (v < r->lo) r->lo = v;
    if (v > r->hi) r->hi = v;
}
static range range_pad(range r, double frac)
{
    if (!(r.lo <= r.hi)) return (range){0, 1};
    if (r.hi - r.lo <= 1e-300 * (fabs(r.lo) + 1)) {
        double d = r.lo != 0 ? 0.1 * fabs(r.lo) : 1.0;
        return (range){r.lo - d, r.hi + d};
    }
    double d = (r.hi - r.lo) * frac;
    return (range){r.lo - d, r.hi + d};
}

/* Whether a series runs off the scale near x = xlo: its values in the first
 * tenth of the x range exceed 3 times the largest magnitude elsewhere. */
static bool singular_near_lo(const plot_series *s, double xlo, double xhi)
{
    double cut = xlo + 0.1 * (xhi - xlo), far = 0, near = 0;
    for (size_t i = 0; i < s->n; i++) {
        double v = fabs(s->y[i]);
        if (!isfinite(v)) continue;
        if (s->x[i] >= cut)
            far = fmax(far, v);
        else
            near = fmax(near, v);
    }
    return far > 0 && near > 3 * far;
}

/* ---- curves ---------------------------------------------------------------- */

/* Draws a series as a polyline; breaks it at non-finite values; above 3000
 * points keeps the min and max of each bin so that spikes still show. */
static void draw_polyline(const double *x, const double *y, size_t n, double scale)
{
    size_t bin = n > 3000 ? (n + 1499) / 1500 : 1;
    size_t cap = 2 * (n / bin + 2);
    PLFLT *px = malloc(cap * sizeof *px), *py = malloc(cap * sizeof *py);
    if (!px || !py) {
        free(px);
        free(py);
        return;
    }
    size_t m = 0;
    for (size_t i = 0; i < n; i += bin) {
        size_t end = i + bin < n ? i + bin : n, imin = n, imax = n;
        bool broken = false;
        for (size_t j = i; j < end; j++) {
            if (!isfinite(x[j]) || !isfinite(y[j])) {
                broken = true;
                continue;
            }
            if (imin == n || y[j] < y[imin]) imin = j;
            if (imax == n || y[j] > y[imax]) imax = j;
        }
        if (broken || imin == n) {
            if (m > 1) plline((PLINT)m, px, py);
            m = 0;
            if (imin == n) continue;
        }
        size_t a = imin < imax ? imin : imax, b = imin < imax ? imax : imin;
        px[m] = x[a], py[m++] = scale * y[a];
        if (b != a) px[m] = x[b], py[m++] = scale * y[b];
    }
    if (m > 1) plline((PLINT)m, px, py);
    free(px);
    free(py);
}

static void draw_markers(const plot_series *s, int k, int count, range xr, range yr, double scale)
{
    const int per_curve = 8;
    if (s->n == 0) return;
    for (int j = 0; j < per_curve; j++) {
        double f = (j + (k + 1.0) / (count + 1.0)) / per_curve;
        size_t i = (size_t)(f * (double)(s->n - 1) + 0.5);
        if (i >= s->n) i = s->n - 1;
        PLFLT x = s->x[i], y = scale * s->y[i];
        if (!isfinite(x) || !isfinite(y) || x < xr.lo || x > xr.hi || y < yr.lo || y > yr.hi) continue;
        draw_markers_at(1, &x, &y, s->style, false, 0.85);
    }
}

/* ---- legends --------------------------------------------------------------- */

void plot_legend(const plot_key *k, int n, const char *const *notes, int nn, double x0, double x1, double top)
{
    if (n + nn <= 0) return;
    double ts = 0.85, lh = line_height();
    /* a long legend shrinks rather than runs off the page */
    if ((n + nn + 1) * 1.9 * ts * lh > top - 0.01) ts = (top - 0.01) / ((n + nn + 1) * 1.9 * lh);
    double row = 1.9 * ts * lh, pad = 0.5 * row;
    double y1 = top, y0 = top - (n + nn) * row - 2 * pad;
    plvpor(0, 1, 0, 1);
    plwind(0, 1, 0, 1); /* world = page coordinates */
    PLFLT bx[5] = {x0, x1, x1, x0, x0}, by[5] = {y0, y0, y1, y1, y0};
    plcol0(PLOT_BG);
    set_pattern(0);
    plfill(4, bx, by);
    plcol0(PLOT_FG);
    pllsty(1);
    plot_width(1.0);
    plline(5, bx, by);
    double w = x1 - x0, sx0 = x0 + 0.05 * w, sx1 = x0 + 0.24 * w, tx = x0 + 0.285 * w, text = ts;
    for (int i = 0; i < n; i++) text = fmin(text, fit_scale(k[i].text, ts, x1 - tx - 0.01)); /* one size for all */
    for (int i = 0; i < n; i++) {
        double y = y1 - pad - (i + 0.5) * row;
        if (k[i].fill) {
            double hh = 0.36 * row;
            PLFLT fx[5] = {sx0, sx1, sx1, sx0, sx0}, fy[5] = {y - hh, y - hh, y + hh, y + hh, y - hh};
            plot_fill(4, fx, fy, k[i].style);
            plcol0(PLOT_FG);
            plot_width(1.0);
            plline(5, fx, fy);
        } else {
            PLFLT lx[2] = {sx0, sx1}, ly[2] = {y, y}, mx = 0.5 * (sx0 + sx1), my = y;
            pen(k[i].style, k[i].solid);
            if (k[i].line) {
                plot_width(k[i].style < 0 ? 1.2 : 2.2); /* a guide is drawn thin */
                plline(2, lx, ly);
            }
            pllsty(1);
            if (k[i].marker) draw_markers_at(1, &mx, &my, k[i].style, k[i].filled, 0.85);
        }
        plcol0(PLOT_FG);
        plschr(0, text);
        plptex(tx, y, 1, 0, 0.0, k[i].text);
    }
    for (int j = 0; j < nn; j++) {
        plschr(0, fit_scale(notes[j], 0.75 * ts / 0.85, x1 - sx0 - 0.01));
        plptex(sx0, y1 - pad - (n + j + 0.5) * row, 1, 0, 0.0, notes[j]);
    }
    plschr(0, 1.0);
    plot_width(1.0);
}

/* "Q [U]" with values scaled by 10^-e: "Q [10^e U]", or "Q [10^e/m]" for U = 1/m. */
static void scale_label(char *dst, size_t cap, const char *label, int e)
{
    const char *open = strstr(label, " ["), *close = strrchr(label, ']');
    if (!open || !close || close < open) {
        snprintf(dst, cap, "%s [10#u%d#d]", label, e);
        return;
    }
    const char *unit = open + 2;
    int qlen = (int)(open - label), ulen = (int)(close - unit);
    if (strncmp(unit, "1/", 2) == 0)
        snprintf(dst, cap, "%.*s [10#u%d#d/%.*s]", qlen, label, e, ulen - 2, unit + 2);
    else
        snprintf(dst, cap, "%.*s [10#u%d#d %.*s]", qlen, label, e, ulen, unit);
}

/* ---- line charts ----------------------------------------------------------- */

static void draw_lines(const void *chart)
{
    const plot_lines *c = chart;
    /* 0.135: room left of the y-axis titles for a superscript (10#u7#d/m#u4#d), which stood at the page's edge */
    const double vx0 = 0.135, vx1 = 0.75, vy0 = bottom_room(0.10, 3.2), vy1 = 0.885, gap = 0.035;
    int np = c->np > 0 ? c->np : 1;
    double ph = (vy1 - vy0 - gap * (np - 1)) / np;

    range xr = {c->xlo, c->xhi};
    if (!(c->xlo < c->xhi)) {
        xr = range_empty();
        for (int p = 0; p < c->np; p++)
            for (int k = 0; k < c->p[p].n; k++)
                for (size_t i = 0; i < c->p[p].s[k].n; i++) range_add(&xr, c->p[p].s[k].x[i]);
        if (!(xr.lo < xr.hi)) xr = range_pad(xr, 0.05);
        if (xr.lo > 0 && xr.lo < 0.05 * (xr.hi - xr.lo)) xr.lo = 0; /* time from 0 */
    }

    plot_titles(c->title, c->subtitle);
    for (int p = 0; p < c->np; p++) {
        const plot_panel *P = &c->p[p];
        double top = vy1 - p * (ph + gap), bottom = top - ph;

        /* y range, leaving out the near-x0 part of curves that blow up there */
        bool singular[PLOT_MAX_SERIES] = {false}, any_singular = false;
        range yr = range_empty();
        for (int k = 0; k < P->n; k++) {
            const plot_series *s = &P->s[k];
            singular[k] = P->clip_singular && singular_near_lo(s, xr.lo, xr.hi);
            any_singular |= singular[k];
            double cut = xr.lo + 0.1 * (xr.hi - xr.lo);
            for (size_t i = 0; i < s->n; i++)
                if (s->x[i] >= xr.lo && s->x[i] <= xr.hi && (!singular[k] || s->x[i] >= cut)) range_add(&yr, s->y[i]);
        }
        if (P->zero_line) range_add(&yr, 0.0);
        /* large or small values: scale by a power of ten, named in the unit */
        double mag = fmax(fabs(yr.lo), fabs(yr.hi)), scale = 1;
        char ylabel[192];
        snprintf(ylabel, sizeof ylabel, "%s", P->ylabel);
        const int exponent = plot_axis_exponent(mag);
        if (exponent != 0) {
            scale = pow(10, -exponent);
            yr.lo *= scale;
            yr.hi *= scale;
            scale_label(ylabel, sizeof ylabel, P->ylabel, exponent);
        }
        yr = range_pad(yr, 0.07);

        plvpor(vx0, vx1, bottom, top);
        plwind(xr.lo, xr.hi, yr.lo, yr.hi);
        plcol0(PLOT_GRID);
        plot_width(1.0);
        pllsty(1);
        plbox("g", 0, 0, "g", 0, 0);
        if (P->zero_line && yr.lo < 0 && yr.hi > 0) {
            PLFLT zx[2] = {xr.lo, xr.hi}, zy[2] = {0, 0};
            plcol0(PLOT_REF);
            plline(2, zx, zy);
        }
        for (int k = 0; k < P->n; k++) {
            const plot_series *s = &P->s[k];
            pen(s->style, s->reference);
            plot_width(s->reference ? 1.2 : 2.2);
            draw_polyline(s->x, s->y, s->n, scale);
            pllsty(1);
            if (!s->reference) draw_markers(s, k, P->n, xr, yr, scale);
        }
        plcol0(PLOT_FG);
        plot_width(1.6);
        pllsty(1);
        /* "f": fixed-point tick labels. The values are scaled above to
         * [1e-1, 1e4), which fixed point writes in at most 6 characters;
         * PLplot's own exponent (e.g. a range from just below 0 to 0.09)
         * would go in the corner above the axis, over the panel above's
         * lowest tick label or the y-axis title. */
        plbox(p == c->np - 1 ? "bcnst" : "bcst", 0, 0, "bcnstvf", 0, 0);
        plot_width(1.0);
        const double ys = fit_scale_height(ylabel, 1.0, 0.98 * ph);
        plschr(0, ys);
        plmtex("l", 5.2 / ys, 0.5, 0.5, ylabel); /* the displacement counts character heights: kept in mm */
        plschr(0, 1.0);
        if (p == c->np - 1) plmtex("b", 3.2, 0.5, 0.5, c->xlabel);

        plot_key e[PLOT_MAX_SERIES];
        char text[PLOT_MAX_SERIES][72];
        for (int k = 0; k < P->n; k++) {
            snprintf(text[k], sizeof text[k], "%s%s", P->s[k].label, singular[k] ? "*" : "");
            e[k] = (plot_key){.text = text[k], .style = P->s[k].style, .line = true, .solid = P->s[k].reference,
                              .marker = !P->s[k].reference};
        }
        const char *note = "* off scale near 0";
        plot_legend(e, P->n, &note, any_singular, vx1 + 0.015, 0.992, top);
    }
}

/* ---- horizontal bars -------------------------------------------------------- */

static void draw_bars(const void *chart)
{
    const plot_bars *c = chart;
    const double vx0 = 0.20, vx1 = 0.955, vy0 = bottom_room(0.11, 3.2), vy1 = 0.875;
    double vmax = 0;
    for (int i = 0; i < c->n; i++)
        if (isfinite(c->value[i])) vmax = fmax(vmax, c->value[i]);
    if (vmax <= 0) vmax = 1;
    double xmax = vmax * 1.5;

    plot_titles(c->title, c->subtitle);
    plvpor(vx0, vx1, vy0, vy1);
    plwind(0, xmax, 0, c->n);
    plcol0(PLOT_GRID);
    plot_width(1.0);
    pllsty(1);
    plbox("g", 0, 0, "", 0, 0);
    for (int i = 0; i < c->n; i++) {
        double yc = c->n - 1 - i + 0.5, hh = 0.34, v = isfinite(c->value[i]) ? fmax(c->value[i], 0) : 0;
        PLFLT fx[5] = {0, v, v, 0, 0}, fy[5] = {yc - hh, yc - hh, yc + hh, yc + hh, yc - hh};
        plot_fill(4, fx, fy, i);
        plcol0(PLOT_FG);
        plot_width(1.2);
        plline(5, fx, fy);
        plot_width(1.0);
        plschr(0, 0.85);
        plptex(v + 0.012 * xmax, yc, 1, 0, 0.0, c->note[i]);
        plschr(0, 0.95);
        plmtex("lv", 0.8, yc / c->n, 1.0, c->name[i]);
        plschr(0, 1.0);
    }
    plcol0(PLOT_FG);
    plot_width(1.6);
    plbox("bcnst", 0, 0, "bc", 0, 0);
    plot_width(1.0);
    plmtex("b", 3.2, 0.5, 0.5, c->xlabel);
}

/* ---- stacked areas ---------------------------------------------------------- */

static void draw_stack(const void *chart)
{
    const plot_stack *c = chart;
    const double vx0 = 0.11, vx1 = 0.74, vy0 = bottom_room(0.10, 3.2), vy1 = 0.885;
    size_t n = c->n;
    double *base = calloc(n ? n : 1, sizeof *base);
    PLFLT *px = malloc((2 * n + 1) * sizeof *px), *py = malloc((2 * n + 1) * sizeof *py);
    if (!base || !px || !py) goto out;

    range xr = range_empty(), yr = {0, 0};
    for (size_t i = 0; i < n; i++) {
        range_add(&xr, c->x[i]);
        double sum = 0;
        for (int l = 0; l < c->nl; l++) sum += isfinite(c->y[l][i]) ? fmax(c->y[l][i], 0) : 0;
        yr.hi = fmax(yr.hi, sum);
    }
    if (!(xr.lo < xr.hi)) xr = range_pad(xr, 0.05);
    if (yr.hi <= 0) yr.hi = 1;
    yr.hi *= 1.06;

    plot_titles(c->title, c->subtitle);
    plvpor(vx0, vx1, vy0, vy1);
    plwind(xr.lo, xr.hi, yr.lo, yr.hi);
    for (int l = 0; l < c->nl; l++) {
        size_t m = 0;
        for (size_t i = 0; i < n; i++) px[m] = c->x[i], py[m++] = base[i];
        for (size_t i = n; i-- > 0;) {
            double v = isfinite(c->y[l][i]) ? fmax(c->y[l][i], 0) : 0;
            base[i] += v;
            px[m] = c->x[i], py[m++] = base[i];
        }
        if (n >= 2) {
            plot_fill((int)m, px, py, l);
            plcol0(PLOT_FG);
            plot_width(0.8);
            plline((PLINT)n, c->x, base); /* the layer's upper edge */
        }
    }
    plcol0(PLOT_FG);
    plot_width(1.6);
    plbox("bcnst", 0, 0, "bcnstv", 0, 0);
    plot_width(1.0);
    plmtex("l", 5.2, 0.5, 0.5, c->ylabel);
    plmtex("b", 3.2, 0.5, 0.5, c->xlabel);

    plot_key e[PLOT_MAX_LAYERS];
    for (int l = 0; l < c->nl; l++) e[l] = (plot_key){.text = c->name[c->nl - 1 - l], .style = c->nl - 1 - l, .fill = true};
    plot_legend(e, c->nl, NULL, 0, vx1 + 0.015, 0.992, vy1);
out:
    free(base);
    free(px);
    free(py);
}

/* ---- log-log charts -------------------------------------------------------- */

static bool point_ok(const plot_curve *s, int i)
{
    return s->x[i] > 0 && s->y[i] > 0 && isfinite(s->x[i]) && isfinite(s->y[i]);
}

/* log10 of the axis ends: whole decades around the points (and the levels, on y), plot_log_axis_ends. */
static range decades(const plot_loglog *c, bool x)
{
    range r = range_empty();
    for (int k = 0; k < c->nc; k++)
        for (int i = 0; i < c->c[k].n; i++)
            if (point_ok(&c->c[k], i)) range_add(&r, log10(x ? c->c[k].x[i] : c->c[k].y[i]));
    for (int g = 0; g < c->ng && !x; g++)
        if (c->g[g].slope == 0 && c->g[g].y0 > 0) range_add(&r, log10(c->g[g].y0));
    if (!(r.lo <= r.hi)) return (range){0, 1};
    range d;
    plot_log_axis_ends(r.lo, r.hi, &d.lo, &d.hi);
    return d;
}

/* The numbers written beside points, so that one is not written over
 * another (two runs of nearly the same cost and error). Boxes in world
 * units: x0, x1, y0, y1. */
enum { MAX_NUMBERS = 256 };
typedef struct numbers {
    double box[MAX_NUMBERS][4];
    int n;
    double dx, dy;   /* the gap between a point and its number */
    double cw, ch;   /* a digit's width and height */
} numbers;

static numbers numbers_start(range xr, range yr, double vw, double vh, double scale)
{
    PLFLT def, ht, x0, x1, y0, y1;
    plgchr(&def, &ht);
    plgspa(&x0, &x1, &y0, &y1);
    numbers n = {.dx = 0.012 * (xr.hi - xr.lo), .dy = 0.012 * (yr.hi - yr.lo)};
    n.cw = 0.7 * def * scale / (x1 - x0) / vw * (xr.hi - xr.lo); /* as fit_scale's estimate */
    n.ch = def * scale / (y1 - y0) / vh * (yr.hi - yr.lo);
    return n;
}

static bool number_free(const numbers *n, const double b[4])
{
    for (int k = 0; k < n->n; k++)
        if (b[0] < n->box[k][1] && n->box[k][0] < b[1] && b[2] < n->box[k][3] && n->box[k][2] < b[3]) return false;
    return true;
}

/* Where to write s beside the point (x, y): up and to the right as always,
 * unless a number already written is there; then below, then to the left,
 * then further out. at: the reference point for plptex (left, middle). */
static void number_place(numbers *n, double x, double y, const char *s, double at[2])
{
    double w = visible_chars(s) * n->cw, h = n->ch;
    const double right = x + n->dx, left = x - n->dx - w;
    const double cand[][2] = {{right, y + n->dy},         {right, y - n->dy - h},         {left, y + n->dy},
                              {left, y - n->dy - h},      {right, y + n->dy + h},         {right, y - n->dy - 2 * h},
                              {left, y + n->dy + h},      {left, y - n->dy - 2 * h}};
    int pick = 0;
    for (int k = 0; k < (int)(sizeof cand / sizeof *cand); k++) {
        double b[4] = {cand[k][0], cand[k][0] + w, cand[k][1] - 0.5 * h, cand[k][1] + 0.5 * h};
        if (number_free(n, b)) {
            pick = k;
            break;
        }
    }
    at[0] = cand[pick][0];
    at[1] = cand[pick][1];
    if (n->n < MAX_NUMBERS) {
        double *b = n->box[n->n++];
        b[0] = at[0], b[1] = at[0] + w, b[2] = at[1] - 0.5 * h, b[3] = at[1] + 0.5 * h;
    }
}

static void draw_loglog(const void *chart)
{
    const plot_loglog *c = chart;
    const double vx0 = 0.11, vx1 = 0.66, vy0 = bottom_room(0.11, 3.0), vy1 = 0.875;
    range xr = decades(c, true), yr = decades(c, false);
    static numbers nums; /* large: not on the stack */
    nums = numbers_start(xr, yr, vx1 - vx0, vy1 - vy0, 0.62);
    plot_titles(c->title, c->subtitle);
    plvpor(vx0, vx1, vy0, vy1);
    plwind(xr.lo, xr.hi, yr.lo, yr.hi);
    plcol0(PLOT_GRID);
    plot_width(1.0);
    pllsty(1);
    plbox("gl", 1, 0, "gl", 1, 0);
    for (int g = 0; g < c->ng; g++) {
        const plot_guide *G = &c->g[g];
        if (!(G->x0 > 0 && G->y0 > 0)) continue;
        double gx0 = log10(G->x0), gy0 = log10(G->y0);
        PLFLT gx[2] = {xr.lo, xr.hi}, gy[2] = {gy0 + G->slope * (xr.lo - gx0), gy0 + G->slope * (xr.hi - gx0)};
        pen(G->style, false);
        plot_width(1.2);
        plline(2, gx, gy);
        pllsty(1);
        if (G->on_line) {
            plschr(0, 0.75);
            plptex(xr.lo + 0.02 * (xr.hi - xr.lo), gy[0] + 0.02 * (yr.hi - yr.lo), 1, 0, 0.0, G->label);
            plschr(0, 1.0);
        }
    }
    for (int k = 0; k < c->nc; k++) {
        const plot_curve *s = &c->c[k];
        size_t cap = s->n > 0 ? (size_t)s->n : 1;
        PLFLT *px = malloc(2 * cap * sizeof *px); /* log10 of the usable points: x, then y */
        if (!px) continue;
        PLFLT *py = px + cap;
        int m = 0;
        for (int i = 0; i < s->n; i++)
            if (point_ok(s, i)) px[m] = log10(s->x[i]), py[m++] = log10(s->y[i]);
        pen(s->style, s->solid);
        if (s->line && m > 1) {
            plot_width(2.2);
            plline(m, px, py);
        }
        pllsty(1);
        if (s->markers) draw_markers_at(m, px, py, s->style, s->filled, s->filled ? 1.0 : 0.9);
        if (s->numbers) { /* beside each point: up and to the right, else where no other number is */
            plschr(0, 0.62);
            plcol0(PLOT_FG);
            for (int i = 0, j = 0; i < s->n; i++) {
                if (!point_ok(s, i)) continue;
                char num[16];
                snprintf(num, sizeof num, "%d", s->numbers[i]);
                double at[2];
                number_place(&nums, px[j], py[j], num, at);
                plptex(at[0], at[1], 1, 0, 0.0, num);
                j++;
            }
        }
        plschr(0, 1.0);
        free(px);
    }
    plcol0(PLOT_FG);
    plot_width(1.6);
    pllsty(1);
    plbox("bclnst", 1, 0, "bclnstv", 1, 0);
    plot_width(1.0);
    plmtex("l", 4.2, 0.5, 0.5, c->ylabel);
    plmtex("b", 3.0, 0.5, 0.5, c->xlabel);

    plot_key e[PLOT_MAX_CURVES + PLOT_MAX_GUIDES];
    const char *notes[PLOT_MAX_NOTES];
    int n = 0;
    for (int k = 0; k < c->nc; k++) {
        const plot_curve *s = &c->c[k];
        e[n++] = (plot_key){s->label, s->style, false, s->line, s->solid, s->markers, s->filled};
    }
    for (int g = 0; g < c->ng; g++)
        if (c->g[g].label[0] && !c->g[g].on_line) e[n++] = (plot_key){.text = c->g[g].label, .style = c->g[g].style, .line = true};
    for (int i = 0; i < c->nn; i++) notes[i] = c->note[i];
    plot_legend(e, n, notes, c->nn, vx1 + 0.02, 0.992, vy1);
}

bool plot_chart(plot_kind kind, const void *chart, const char *dir, const char *base, int width, int height)
{
    static plot_draw_fn *const draw[] = {
        [PLOT_LINES] = draw_lines, [PLOT_BARS] = draw_bars, [PLOT_STACK] = draw_stack, [PLOT_LOGLOG] = draw_loglog};
    return plot_page(draw[kind], chart, dir, base, width, height);
}
