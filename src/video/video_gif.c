/* Animated GIF through giflib: each frame reduced to its own 256 colours
 * (giflib's median-cut GifQuantizeBuffer), looping forever. */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include <gif_lib.h>

#include "video_internal.h"

typedef struct gif {
    GifFileType *f;
    int w, h, delay_cs; /* [1/100 s] between frames */
    GifByteType *r, *g, *b, *idx;
} gif;

static void gif_free(gif *s)
{
    if (!s) return;
    free(s->r);
    free(s->g);
    free(s->b);
    free(s->idx);
    free(s);
}

static void say_gif(char *err, size_t n, const char *what, int code)
{
    const char *why = GifErrorString(code);
    snprintf(err, n, "%s: %s", what, why ? why : "giflib error");
}

void *sph_video_gif_open(const char *tmp, int w, int h, int fps, const char **codec, char *err, size_t n)
{
    *codec = "giflib (GIF89a, 256 colours a frame)";
    gif *s = calloc(1, sizeof *s);
    size_t px = (size_t)w * h;
    if (!s || !(s->r = malloc(px)) || !(s->g = malloc(px)) || !(s->b = malloc(px)) || !(s->idx = malloc(px))) {
        gif_free(s);
        snprintf(err, n, "out of memory");
        return NULL;
    }
    s->w = w;
    s->h = h;
    s->delay_cs = (100 + fps / 2) / fps;
    int code = 0;
    s->f = EGifOpenFileName(tmp, false, &code);
    if (!s->f) {
        say_gif(err, n, "cannot create it", code);
        gif_free(s);
        return NULL;
    }
    EGifSetGifVersion(s->f, true);
    if (EGifPutScreenDesc(s->f, w, h, 8, 0, NULL) == GIF_ERROR) goto fail;
    /* the Netscape application block: loop forever */
    static const GifByteType app[11] = {'N', 'E', 'T', 'S', 'C', 'A', 'P', 'E', '2', '.', '0'};
    static const GifByteType loop[3] = {1, 0, 0};
    if (EGifPutExtensionLeader(s->f, APPLICATION_EXT_FUNC_CODE) == GIF_ERROR ||
        EGifPutExtensionBlock(s->f, sizeof app, app) == GIF_ERROR ||
        EGifPutExtensionBlock(s->f, sizeof loop, loop) == GIF_ERROR || EGifPutExtensionTrailer(s->f) == GIF_ERROR)
        goto fail;
    return s;
fail:
    say_gif(err, n, "writing the header", s->f->Error);
    EGifCloseFile(s->f, &code);
    gif_free(s);
    return NULL;
}

static bool gif_add(void *st, const uint8_t *rgb, char *err, size_t n)
{
    gif *s = st;
    size_t px = (size_t)s->w * s->h;
    for (size_t i = 0; i < px; i++) {
        s->r[i] = rgb[3 * i];
        s->g[i] = rgb[3 * i + 1];
        s->b[i] = rgb[3 * i + 2];
    }
    GifColorType colours[256];
    int ncol = 256;
    if (GifQuantizeBuffer((unsigned)s->w, (unsigned)s->h, &ncol, s->r, s->g, s->b, s->idx, colours) == GIF_ERROR) {
        snprintf(err, n, "reducing the frame to 256 colours failed");
        return false;
    }
    ColorMapObject *map = GifMakeMapObject(256, colours);
    if (!map) {
        snprintf(err, n, "out of memory");
        return false;
    }
    GraphicsControlBlock gcb = {.DisposalMode = DISPOSE_DO_NOT, .UserInputFlag = false, .DelayTime = s->delay_cs,
                                .TransparentColor = NO_TRANSPARENT_COLOR};
    GifByteType ext[4];
    size_t len = EGifGCBToExtension(&gcb, ext);
    bool ok = EGifPutExtension(s->f, GRAPHICS_EXT_FUNC_CODE, (int)len, ext) != GIF_ERROR &&
              EGifPutImageDesc(s->f, 0, 0, s->w, s->h, false, map) != GIF_ERROR;
    for (int y = 0; ok && y < s->h; y++) ok = EGifPutLine(s->f, s->idx + (size_t)y * s->w, s->w) != GIF_ERROR;
    GifFreeMapObject(map);
    if (!ok) say_gif(err, n, "writing", s->f->Error);
    return ok;
}

static bool gif_finish(void *st, char *err, size_t n)
{
    gif *s = st;
    int code = 0;
    bool ok = EGifCloseFile(s->f, &code) != GIF_ERROR;
    if (!ok) say_gif(err, n, "closing", code);
    gif_free(s);
    return ok;
}

static void gif_drop(void *st)
{
    gif *s = st;
    int code;
    EGifCloseFile(s->f, &code);
    gif_free(s);
}

const sph_video_ops sph_video_gif_ops = {gif_add, gif_finish, gif_drop};
