/* The video writer's front (video.h): picks the format by extension, writes
 * to a temporary and renames it when the video is complete. */
#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#include "video_internal.h"

const char sph_video_extensions[] = ".mp4 (H.264), .gif";

struct sph_video {
    const sph_video_ops *ops;
    void *st;
    int w, h;
    long frames;
    const char *codec;
    uint8_t *scaled; /* a frame of another size, scaled to w x h */
    char path[1024], tmp[1040];
};

sph_video_format sph_video_format_of(const char *path)
{
    const char *dot = path ? strrchr(path, '.') : NULL;
    if (!dot || strchr(dot, '/')) return SPH_VIDEO_NONE;
    if (strcasecmp(dot, ".mp4") == 0) return SPH_VIDEO_MP4;
    if (strcasecmp(dot, ".gif") == 0) return SPH_VIDEO_GIF;
    return SPH_VIDEO_NONE;
}

sph_video *sph_video_open(const char *path, int w, int h, int fps, char *err, size_t n)
{
    sph_video_format f = sph_video_format_of(path);
    if (f == SPH_VIDEO_NONE) {
        snprintf(err, n, "video '%s': unknown extension (accepted: %s)", path ? path : "", sph_video_extensions);
        return NULL;
    }
    if (strlen(path) >= sizeof ((sph_video *)0)->path) {
        snprintf(err, n, "video '%.60s...': path too long", path);
        return NULL;
    }
    if (w < 16 || h < 16 || fps < 1 || fps > 120) {
        snprintf(err, n, "video '%s': %dx%d at %d frames/s (accepted: 16 pixels a side or more, 1 to 120 frames/s)",
                 path, w, h, fps);
        return NULL;
    }
    sph_video *v = calloc(1, sizeof *v);
    if (!v) {
        snprintf(err, n, "video '%s': out of memory", path);
        return NULL;
    }
    snprintf(v->path, sizeof v->path, "%s", path);
    /* the temporary keeps the extension: libavformat picks the container by it */
    const char *dot = strrchr(path, '.');
    snprintf(v->tmp, sizeof v->tmp, "%.*s.part%s", (int)(dot - path), path, dot);
    /* a path that cannot be written is found here, before any frame is drawn */
    FILE *probe = fopen(v->tmp, "wb");
    if (!probe) {
        snprintf(err, n, "video '%s': cannot create it: %s", path, strerror(errno));
        free(v);
        return NULL;
    }
    fclose(probe);
    v->w = w;
    v->h = h;
    v->ops = f == SPH_VIDEO_MP4 ? &sph_video_mp4_ops : &sph_video_gif_ops;
    char why[512] = "";
    v->st = f == SPH_VIDEO_MP4 ? sph_video_mp4_open(v->tmp, w, h, fps, &v->codec, why, sizeof why)
                               : sph_video_gif_open(v->tmp, w, h, fps, &v->codec, why, sizeof why);
    if (!v->st) {
        snprintf(err, n, "video '%s': %s", path, why);
        remove(v->tmp);
        free(v);
        return NULL;
    }
    return v;
}

/* nearest-neighbour: a resized window's frame brought to the video's size */
static void scale_rgb(const uint8_t *src, int sw, int sh, uint8_t *dst, int dw, int dh)
{
    for (int y = 0; y < dh; y++) {
        const uint8_t *row = src + (size_t)((long)y * sh / dh) * sw * 3;
        for (int x = 0; x < dw; x++) memcpy(dst + ((size_t)y * dw + x) * 3, row + (size_t)((long)x * sw / dw) * 3, 3);
    }
}

bool sph_video_add(sph_video *v, const uint8_t *rgb, int fw, int fh, char *err, size_t n)
{
    if (fw != v->w || fh != v->h) {
        if (fw < 1 || fh < 1) {
            snprintf(err, n, "video '%s': empty frame", v->path);
            return false;
        }
        if (!v->scaled && !(v->scaled = malloc((size_t)v->w * v->h * 3))) {
            snprintf(err, n, "video '%s': out of memory", v->path);
            return false;
        }
        scale_rgb(rgb, fw, fh, v->scaled, v->w, v->h);
        rgb = v->scaled;
    }
    char why[512] = "";
    if (!v->ops->add(v->st, rgb, why, sizeof why)) {
        snprintf(err, n, "video '%s': frame %ld: %s", v->path, v->frames, why);
        return false;
    }
    v->frames++;
    return true;
}

bool sph_video_close(sph_video *v, char *err, size_t n)
{
    if (!v) return true;
    char why[512] = "";
    bool ok = v->ops->finish(v->st, why, sizeof why);
    if (!ok)
        snprintf(err, n, "video '%s': %s", v->path, why);
    else if (rename(v->tmp, v->path) != 0) {
        snprintf(err, n, "video '%s': cannot rename %s to it: %s", v->path, v->tmp, strerror(errno));
        ok = false;
    }
    if (!ok) remove(v->tmp);
    free(v->scaled);
    free(v);
    return ok;
}

void sph_video_abort(sph_video *v)
{
    if (!v) return;
    v->ops->drop(v->st);
    remove(v->tmp);
    free(v->scaled);
    free(v);
}

long sph_video_frames(const sph_video *v)
{
    return v ? v->frames : 0;
}

const char *sph_video_codec(const sph_video *v)
{
    return v ? v->codec : "";
}

void sph_video_size(const sph_video *v, int *w, int *h)
{
    /* H.264's 4:2:0 chroma halves each axis: the MP4 is cut to even sizes (video_mp4.c); a GIF keeps any */
    const bool even = v && sph_video_format_of(v->path) == SPH_VIDEO_MP4;
    *w = v ? (even ? v->w & ~1 : v->w) : 0;
    *h = v ? (even ? v->h & ~1 : v->h) : 0;
}
