/* The window's record key (sphlab view, key v): a video of the frames on
 * screen through src/video/. Kept beside view_keys.c, which calls it. */
#ifndef SPH_VIEW_RECORD_H
#define SPH_VIEW_RECORD_H

#include <stdbool.h>
#include <stddef.h>

#include "render.h"
#include "video.h"

typedef struct view_rec {
    sph_video *video;  /* NULL: not recording */
    const char *path;  /* --video FILE, else sphlab-NNNN.mp4 in the current directory */
    int count;         /* videos started */
    int fps;           /* [frames/s] */
} view_rec;

/* Starts a video of r's frame size, or finishes the one recording; msg
 * gets what the window says (the file, or the reason it failed). */
void view_rec_toggle(view_rec *rec, const sph_renderer *r, char *msg, size_t n);
/* Adds the frame r has just drawn; false (the video dropped, msg says why) on an error. */
bool view_rec_frame(view_rec *rec, sph_renderer *r, char *msg, size_t n);

#endif
