/* The frame's layout (layout.h): arithmetic on pixel rectangles only. */
#include "layout.h"

#include <math.h>
#include <stdio.h>
#include <string.h>

void sph_legend_label(char *out, size_t n, float v, float lo, float hi)
{
    /* the digits that tell the half range apart at the values' magnitude: log10(max |value| / (half range)),
     * plus one; 4 at least (a wide range), 9 at most (a float's digits) */
    const double big = fmax(fabs((double)lo), fabs((double)hi)), half = 0.5 * fabs((double)hi - (double)lo);
    int digits = 4;
    if (half > 0 && big > 0) digits = (int)ceil(log10(big / half)) + 2;
    digits = digits < 4 ? 4 : digits > 9 ? 9 : digits;
    /* from 10^digits to 10^7 %g writes an exponent ("1.804e+04": nine characters, past the legend's column in
     * 400 px wide frames); the whole number is shorter and says more */
    const double a = fabs((double)v);
    if (a >= pow(10.0, digits) && a < 1e7)
        snprintf(out, n, "%.0f", (double)v);
    else
        snprintf(out, n, "%.*g", digits, (double)v);
}

void sph_layout_font_sizes(int h, float *small, float *normal)
{
    float nm = roundf((float)h / 42.0f);
    nm = nm < 11 ? 11 : nm > 24 ? 24 : nm;
    *normal = nm;
    *small = roundf(nm * 0.85f) < 10 ? 10 : roundf(nm * 0.85f);
}

void sph_layout_compute(int w, int h, int side_w, bool legend, bool strip, sph_layout *out)
{
    float fs, fn;
    sph_layout_font_sizes(h, &fs, &fn);
    memset(out, 0, sizeof *out);
    if (side_w < 0) side_w = 0;
    if (side_w > w / 2) side_w = w / 2; /* the view keeps at least half of the width */
    const int pad = (int)roundf(0.6f * fn);
    const int lw = legend ? (int)roundf(6.0f * fn) : 0;
    const int row_h = (int)roundf(1.5f * fs);
    const int strip_h = strip ? 6 * row_h + pad : 0;
    const int right = w - side_w; /* everything but the column lies left of it */
    out->view[0] = pad;
    out->view[1] = pad;
    out->view[2] = right - lw - 2 * pad;
    out->view[3] = h - strip_h - 2 * pad;
    out->legend[0] = right - lw;
    out->legend[1] = pad;
    out->legend[2] = legend ? lw - pad / 2 : 0;
    out->legend[3] = h - strip_h - 2 * pad;
    out->strip[0] = pad;
    out->strip[1] = h - strip_h;
    out->strip[2] = right - 2 * pad;
    out->strip[3] = strip ? strip_h - pad : 0;
    out->side[0] = right;
    out->side[1] = 0;
    out->side[2] = side_w;
    out->side[3] = side_w ? h : 0;
}

int sph_layout_side_width(int w, int h)
{
    float fs, fn;
    sph_layout_font_sizes(h, &fs, &fn);
    int want = (int)roundf(21.0f * fn);
    int most = (int)(0.45f * (float)w);
    return want < most ? want : most;
}

void sph_layout_hud_room(const int view[4], const int side[4], float side_used, float reserve, float keep,
                         float room[4])
{
    if (side[2] > 0) {
        room[0] = (float)side[0] + 4;
        room[1] = (float)side[1] + (side_used > 0 ? side_used + 4 : (float)view[1]);
        room[2] = (float)side[2] - 8;
        /* the parameter panel's least height first: the HUD and the text panel shrink (their rows left out and
         * counted), the panel's widgets would otherwise get a strip of a title bar (~30 px) */
        const float bottom = (float)(side[1] + side[3]) - fminf(fmaxf(keep, 0), 0.5f * (float)side[3]);
        room[3] = fmaxf(bottom - 4 - room[1], 0);
        room[3] -= fminf(reserve, 0.5f * room[3]);
    } else {
        room[0] = (float)view[0] + 4;
        room[1] = (float)view[1] + 4;
        room[2] = (float)view[2] - 8;
        room[3] = (float)view[3] - 8;
    }
}

/* Appends text to the rows, wrapped to avail pixels: greedy at spaces,
 * continuation rows indented by two spaces; a word wider than a row is cut. */
static void wrap_line(const char *text, float avail, sph_text_width_fn width, const void *ctx, sph_hud_fit *out)
{
    const char *s = text;
    bool first = true;
    while (*s && out->n_rows < SPH_HUD_MAX_ROWS) {
        char row[128];
        const char *indent = first ? "" : "  ";
        snprintf(row, sizeof row, "%s%s", indent, s);
        if (width(ctx, row) <= avail) {
            snprintf(out->row[out->n_rows++], sizeof out->row[0], "%s", row);
            return;
        }
        /* the longest prefix ending before a space that fits, after a ',', ';', ':' or between fields
         * ("   ") when that keeps half the row; else the most characters that fit */
        const size_t ind = strlen(indent), len = strlen(row);
        size_t cut = 0, cut_sep = 0, chars = ind + 1;
        for (size_t k = ind + 1; k < len; k++) {
            char keep = row[k];
            row[k] = '\0';
            bool fits = width(ctx, row) <= avail;
            row[k] = keep;
            if (!fits) break;
            chars = k;
            if (keep == ' ' && row[k - 1] != ' ') {
                cut = k;
                if (strchr(",;:", row[k - 1]) || (row[k + 1] == ' ')) cut_sep = k;
            }
        }
        if (cut_sep > ind && 2 * (cut_sep - ind) >= cut - ind) cut = cut_sep;
        if (!cut) cut = chars;
        row[cut] = '\0';
        snprintf(out->row[out->n_rows++], sizeof out->row[0], "%s", row);
        s += cut - ind;
        while (*s == ' ') s++;
        first = false;
    }
}

void sph_hud_fit_compute(const char (*lines)[128], int n_lines, int n_bars, float bar_w, float max_w, float max_h,
                         float ft, float fs, float fn, sph_text_width_fn width, const void *ctx, sph_hud_fit *out)
{
    memset(out, 0, sizeof *out);
    const float margin_x = 12, margin_y = 8; /* 6 px each side, 4 px above and below */
    const float avail = fmaxf(max_w - margin_x, 4 * ft);
    for (int i = 0; i < n_lines; i++) wrap_line(lines[i], avail, width, ctx, out);
    float w = n_bars ? bar_w : 0;
    for (int i = 0; i < out->n_rows; i++) w = fmaxf(w, width(ctx, out->row[i]));
    out->w = fminf(w, avail) + margin_x;
    out->n_bars = n_bars;
    out->gap = n_bars ? 0.3f * fn : 0;
    /* the spacing that fits: 1.2 and 1.25 times the sizes, down to 1.0 (rows touching, not overlapping) */
    const float rows_px = (float)out->n_rows * ft + (float)n_bars * fs;
    const float room = max_h - margin_y - out->gap;
    float f = rows_px > 0 ? room / rows_px : 1.25f;
    out->text_pitch = ft * fminf(1.2f, fmaxf(f, 1.0f));
    out->bar_pitch = fs * fminf(1.25f, fmaxf(f, 1.0f));
    /* what still does not fit is left out from the end, timings first, keeping one text row to say so */
    float h = (float)out->n_rows * out->text_pitch + (float)out->n_bars * out->bar_pitch + out->gap;
    if (h > room) {
        while (h + out->text_pitch > room && (out->n_bars || out->n_rows)) {
            out->hidden++;
            if (out->n_bars) {
                out->n_bars--;
                h -= out->bar_pitch;
                if (!out->n_bars) h -= out->gap, out->gap = 0;
            } else {
                out->n_rows--;
                h -= out->text_pitch;
            }
        }
        if (out->n_rows == SPH_HUD_MAX_ROWS) out->n_rows--, out->hidden++;
        snprintf(out->row[out->n_rows++], sizeof out->row[0], "(%d more rows: enlarge the window)", out->hidden);
        out->w = fminf(fmaxf(out->w, width(ctx, out->row[out->n_rows - 1]) + margin_x), avail + margin_x);
        h += out->text_pitch;
    }
    out->h = h + margin_y;
}
