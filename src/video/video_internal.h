/* What the two writers of src/video/ share (see video.h). */
#ifndef SPH_VIDEO_INTERNAL_H
#define SPH_VIDEO_INTERNAL_H

#include "video.h"

typedef struct sph_video_ops {
    bool (*add)(void *st, const uint8_t *rgb, char *err, size_t n); /* a frame of the video's size */
    bool (*finish)(void *st, char *err, size_t n);                 /* writes the trailer, frees st */
    void (*drop)(void *st);                                         /* frees st, nothing more written */
} sph_video_ops;

/* Each opens tmp (the temporary) for w x h frames; NULL with the reason. */
void *sph_video_mp4_open(const char *tmp, int w, int h, int fps, const char **codec, char *err, size_t n);
void *sph_video_gif_open(const char *tmp, int w, int h, int fps, const char **codec, char *err, size_t n);
extern const sph_video_ops sph_video_mp4_ops, sph_video_gif_ops;

#endif
