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
