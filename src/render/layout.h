/* The frame's layout, GL-free: where the view the domain is fitted into, the
 * colour legend, the index strip and the side column (HUD, timings, text
 * panel, the window's parameter panel) go in a w x h image. Pure arithmetic,
 * so the tests check it without a context (tests/test_render_layout.c). */
#ifndef SPH_LAYOUT_H
#define SPH_LAYOUT_H

#include <stdbool.h>
#include <stddef.h>

typedef struct sph_layout {
    int view[4];   /* [px] x, y (top-left), width, height: the domain is fitted into it, world drawing clipped to it */
    int legend[4]; /* [px] the colour legend, right of the view; width 0 without it */
    int strip[4];  /* [px] the index strip, below the view; height 0 without it */
    int side[4];   /* [px] the side column at the right edge; width 0 without it */
} sph_layout;

/* Font sizes [px] of the small and normal text for an image h pixels high. */
void sph_layout_font_sizes(int h, float *small, float *normal);

/* The layout of a w x h image with a side column side_w pixels wide (0:
 * none, and the HUD and text panel sit over the view's top corners, as
 * `sphlab render` draws them), with or without the legend and the strip.
 * Rectangles never overlap. */
void sph_layout_compute(int w, int h, int side_w, bool legend, bool strip, sph_layout *out);

/* The window's side column for a w x h window: wide enough for the HUD and
 * the parameter panel's sliders, at most 45% of the width. */
int sph_layout_side_width(int w, int h);

/* A colour legend's label for the value v of a scale from lo to hi: 4 significant digits, more when
 * the range is narrow against the values (a density from 999.2 to 1000.9 kg/m^3 read "1000" three
 * times), so that the labels at lo, the middle and hi differ where the range is not zero. */
void sph_legend_label(char *out, size_t n, float v, float lo, float hi);

#endif
