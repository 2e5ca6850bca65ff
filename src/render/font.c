/* Text through stb_truetype (see font.h). libstb-dev ships the implementation
 * in libstb, so only the declarations are included here. */
#include "font.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <stb_truetype.h>

const char *sph_font_path(void)
{
    const char *p = getenv("SPHLAB_FONT");
    return p && *p ? p : SPH_FONT_DEFAULT;
}

static unsigned char *read_file(const char *path, size_t *len)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    unsigned char *buf = NULL;
    long n = -1;
    if (fseek(f, 0, SEEK_END) == 0) n = ftell(f);
    if (n > 0 && n < (64L << 20) && fseek(f, 0, SEEK_SET) == 0 && (buf = malloc((size_t)n))) {
        if (fread(buf, 1, (size_t)n, f) != (size_t)n) {
            free(buf);
            buf = NULL;
        }
    }
    fclose(f);
    *len = buf ? (size_t)n : 0;
    return buf;
}

bool sph_font_load(sph_font *f, float px_small, float px_normal, char *err, size_t n)
{
    memset(f, 0, sizeof *f);
    snprintf(f->path, sizeof f->path, "%s", sph_font_path());
    size_t len;
    unsigned char *ttf = read_file(f->path, &len);
    if (!ttf) {
        snprintf(err, n, "cannot read the font %s: %s (Debian package fonts-dejavu-core; or set SPHLAB_FONT)", f->path,
                 errno ? strerror(errno) : "empty or too large");
        return false;
    }
    const int A = SPH_FONT_ATLAS, half = A / 2;
    f->atlas = calloc((size_t)A * A, 1);
    if (!f->atlas) {
        free(ttf);
        snprintf(err, n, "out of memory for the font atlas");
        return false;
    }
    /* normal size in the top half, small size below it, white patch in the corner */
    float px[2] = {px_small, px_normal};
    int y0[2] = {half, 0};
    for (int s = 0; s < 2; s++) {
        stbtt_bakedchar bc[95];
        int r = stbtt_BakeFontBitmap(ttf, stbtt_GetFontOffsetForIndex(ttf, 0), px[s], f->atlas + (size_t)y0[s] * A, A,
                                     half - 8, 32, 95, bc);
        if (r <= 0) {
            free(ttf);
            sph_font_free(f);
            snprintf(err, n, "%s: %s", f->path, r == 0 ? "not a TrueType font stb_truetype can read" : "glyphs do not fit the atlas");
            return false;
        }
        for (int c = 0; c < 95; c++)
            f->glyphs[s][c] = (sph_glyph){bc[c].x0, (unsigned short)(bc[c].y0 + y0[s]), bc[c].x1,
                                          (unsigned short)(bc[c].y1 + y0[s]), bc[c].xoff, bc[c].yoff, bc[c].xadvance};
        f->px[s] = px[s];
    }
    free(ttf);
    for (int y = A - 4; y < A; y++) memset(f->atlas + (size_t)y * A + (A - 4), 255, 4);
    f->white_uv[0] = f->white_uv[1] = ((float)A - 2.0f) / (float)A;
    return true;
}

void sph_font_free(sph_font *f)
{
    free(f->atlas);
    f->atlas = NULL;
}

float sph_font_width(const sph_font *f, int size, const char *s)
{
    float w = 0;
    for (; *s; s++) {
        int c = (unsigned char)*s;
        if (c < 32 || c > 126) c = '?';
        w += f->glyphs[size][c - 32].xadvance;
    }
    return w;
}

int sph_font_quads(const sph_font *f, int size, float x, float y, const char *s, sph_glyph_quad *out, int max)
{
    /* baseline at 0.8 of the line height below the top; positions on whole
     * pixels so glyphs are sampled texel for texel (crisp and reproducible) */
    float base = roundf(y + 0.8f * f->px[size]);
    float pen = roundf(x);
    const float inv = 1.0f / SPH_FONT_ATLAS;
    int k = 0;
    for (; *s && k < max; s++) {
        int c = (unsigned char)*s;
        if (c < 32 || c > 126) c = '?';
        const sph_glyph *g = &f->glyphs[size][c - 32];
        if (g->x1 > g->x0) {
            float gx = roundf(pen + g->xoff), gy = roundf(base + g->yoff);
            out[k++] = (sph_glyph_quad){gx, gy, gx + (float)(g->x1 - g->x0), gy + (float)(g->y1 - g->y0),
                                        g->x0 * inv, g->y0 * inv, g->x1 * inv, g->y1 * inv};
        }
        pen += g->xadvance;
    }
    return k;
}
