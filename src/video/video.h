/* Video files from RGB frames: H.264 in MP4 (libavcodec/libavformat, with
 * libswscale for the colour conversion) and animated GIF (giflib). The
 * format follows the file's extension. GL-free and core-free: the render
 * commands hand it frames they have read back. */
#ifndef SPH_VIDEO_H
#define SPH_VIDEO_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

typedef enum sph_video_format { SPH_VIDEO_NONE = -1, SPH_VIDEO_MP4, SPH_VIDEO_GIF } sph_video_format;

/* The format a path names by its extension (.mp4, .gif, any case), or
 * SPH_VIDEO_NONE; "the extensions accepted" for messages. */
sph_video_format sph_video_format_of(const char *path);
extern const char sph_video_extensions[];

typedef struct sph_video sph_video;

/* Starts a video of w x h frames at fps frames a second. It is written to
 * a temporary beside path and renamed at sph_video_close: a failed run
 * leaves no half file. NULL, with the reason naming the path, on an unknown
 * extension or a path that cannot be written. */
sph_video *sph_video_open(const char *path, int w, int h, int fps, char *err, size_t n);
/* Adds one frame: rgb is fw x fh pixels, rows from the top; a frame of
 * another size (a resized window) is scaled to the video's. */
bool sph_video_add(sph_video *v, const uint8_t *rgb, int fw, int fh, char *err, size_t n);
/* Finishes the file and frees v (NULL: nothing); false with the reason. */
bool sph_video_close(sph_video *v, char *err, size_t n);
/* Frees v and removes its temporary: nothing is written. */
void sph_video_abort(sph_video *v);
/* Frames added so far, and the codec used ("libx264 (H.264)", "mpeg4 ...", "giflib"). */
long sph_video_frames(const sph_video *v);
const char *sph_video_codec(const sph_video *v);
/* The size of the frames in the file: an MP4's is cut to even numbers (H.264's 4:2:0), a GIF's is the asked one. */
void sph_video_size(const sph_video *v, int *w, int *h);

#endif
