/* Text through stb_truetype, GL-free: a TrueType font (DejaVu Sans from
 * Debian's fonts-dejavu-core) baked at two pixel sizes into one 8-bit atlas,
 * and the quads that draw a string from it. The atlas also holds a small
 * white patch, so solid shapes and text share one texture and one draw call. */
#ifndef SPH_FONT_H
#define SPH_FONT_H

#include <stdbool.h>
#include <stddef.h>

#define SPH_FONT_DEFAULT "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf"
#define SPH_FONT_ATLAS 512

typedef struct sph_glyph {
    unsigned short x0, y0, x1, y1; /* in the atlas */
    float xoff, yoff, xadvance;
} sph_glyph;

typedef struct sph_font {
    unsigned char *atlas;          /* [SPH_FONT_ATLAS^2] coverage, row 0 at the top */
    sph_glyph glyphs[2][95];       /* [size][char - 32], sizes: small, normal */
    float px[2];                   /* [px] line height of each size */
    float white_uv[2];             /* texture coordinate inside the white patch */
    char path[256];
} sph_font;

/* The font file: $SPHLAB_FONT if set, else SPH_FONT_DEFAULT. */
const char *sph_font_path(void);
/* Loads and bakes; on failure writes why into err (file missing: which
 * package installs it) and returns false. */
bool sph_font_load(sph_font *f, float px_small, float px_normal, char *err, size_t n);
void sph_font_free(sph_font *f);

typedef struct sph_glyph_quad {
    float x0, y0, x1, y1; /* [px] top-left origin */
    float s0, t0, s1, t1; /* atlas coordinates in [0, 1] */
} sph_glyph_quad;

/* Width of a string [px]. */
float sph_font_width(const sph_font *f, int size, const char *s);
/* Quads of a string whose top-left is at (x, y); returns how many (<= max). */
int sph_font_quads(const sph_font *f, int size, float x, float y, const char *s, sph_glyph_quad *out, int max);

#endif
