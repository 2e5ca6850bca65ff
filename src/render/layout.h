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

/* ---- the HUD's box ----------------------------------------------------------------------------------- */

enum { SPH_HUD_MAX_ROWS = 64 };

/* Width [px] of the string s in the font and size ctx stands for. */
typedef float (*sph_text_width_fn)(const void *ctx, const char *s);

/* Where the HUD's rows go in a box of at most max_w x max_h pixels: text
 * rows (lines wrapped at spaces to the box, continuations indented), then the
 * timing rows. The spacing shrinks from 1.2 (text) and 1.25 (timings) times
 * the font size down to 1.0 when the rows would not fit; rows that still do
 * not fit are left out from the end and counted in hidden (the caller says
 * so in the last row). */
typedef struct sph_hud_fit {
    char row[SPH_HUD_MAX_ROWS][128]; /* the text rows drawn */
    int n_rows;                      /* [1] text rows drawn */
    int n_bars;                      /* [1] timing rows drawn */
    int hidden;                      /* [1] rows (text or timings) left out, and the last text row says so */
    float text_pitch, bar_pitch;     /* [px] from one row's top to the next */
    float gap;                       /* [px] between the text and the timing rows */
    float w, h;                      /* [px] the box, margins (6 px left and right, 4 px top and bottom) included */
} sph_hud_fit;

/* The box the HUD or the text panel may take, room = x, y (top-left), width,
 * height [px]: in the side column below the side_used pixels already drawn
 * there (the window), else inside the view (`sphlab render`, side width 0).
 * keep [px]: kept free at the column's bottom for the window's parameter panel
 * (sph_layout_panel_keep; 0: none), half the column at most; reserve [px]:
 * kept free below the box for the text panel, half of what keep leaves at most.
 * What no longer fits, the HUD and the text panel leave out and count. */
void sph_layout_hud_room(const int view[4], const int side[4], float side_used, float reserve, float keep,
                         float room[4]);
/* The least height [px] of the window's parameter panel (Dear ImGui) at its font size font_px [px]: seven
 * ImGui rows (the font, 2 x 3 px frame padding and 4 px item spacing: about 1.65 fonts each), so its title
 * bar, the save row and about four rows of widgets; it scrolls inside for the rest. More took the last
 * timing rows of lessons 7, 8, 9 and 11 in a 1024 x 720 window (tests/test_render_layout.c). */
static inline float sph_layout_panel_keep(float font_px)
{
    return 7.0f * 1.65f * font_px;
}
/* The reserve [px] for a text panel of n rows at the small size fs [px] (0 without one). */
static inline float sph_hud_panel_reserve(int n, float fs)
{
    return n > 0 ? (float)n * fs + 12 : 0;
}

/* lines: n_lines text lines, each measured by width(ctx, .) at the text size
 * ft [px]; n_bars timing rows of bar_w pixels each at the small size fs [px];
 * fn [px]: the normal size (the gap before the timings). */
void sph_hud_fit_compute(const char (*lines)[128], int n_lines, int n_bars, float bar_w, float max_w, float max_h,
                         float ft, float fs, float fn, sph_text_width_fn width, const void *ctx, sph_hud_fit *out);

#endif
