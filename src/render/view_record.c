/* The window's record key (view_record.h). */
#include "view_record.h"

#include <stdio.h>
#include <stdlib.h>

void view_rec_toggle(view_rec *rec, const sph_renderer *r, char *msg, size_t n)
{
    char err[1024], name[64];
    if (rec->video) {
        long frames = sph_video_frames(rec->video);
        snprintf(name, sizeof name, "sphlab-%04d.mp4", rec->count - 1);
        if (sph_video_close(rec->video, err, sizeof err))
            snprintf(msg, n, "recorded %s (%ld frames)", rec->path ? rec->path : name, frames);
        else
            snprintf(msg, n, "record: %s", err);
        rec->video = NULL;
        return;
    }
    int w, h;
    sph_renderer_size(r, &w, &h);
    snprintf(name, sizeof name, "sphlab-%04d.mp4", rec->count);
    const char *path = rec->path ? rec->path : name;
    rec->video = sph_video_open(path, w, h, rec->fps, err, sizeof err);
    if (!rec->video) {
        snprintf(msg, n, "record: %s", err);
        return;
    }
    rec->count++;
    snprintf(msg, n, "recording %s (v stops)", path);
}

bool view_rec_frame(view_rec *rec, sph_renderer *r, char *msg, size_t n)
{
    int w, h;
    sph_renderer_size(r, &w, &h);
    uint8_t *rgb = malloc((size_t)w * h * 3);
    char err[1024] = "out of memory";
    bool ok = rgb != NULL;
    if (ok) {
        sph_renderer_read_rgb(r, rgb);
        ok = sph_video_add(rec->video, rgb, w, h, err, sizeof err);
    }
    free(rgb);
    if (!ok) {
        snprintf(msg, n, "record: %s; stopped", err);
        sph_video_abort(rec->video);
        rec->video = NULL;
    }
    return ok;
}
