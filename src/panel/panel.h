/* The window's parameter panel: Dear ImGui (Debian's libimgui-dev, with its
 * SDL2 and OpenGL 3 backends) behind a C interface, so the rest of sphlab
 * stays C. It lists every key of the scene key table (sph_scene_keys),
 * grouped by section, as widgets made from the key's type and range: numbers
 * as sliders (logarithmic where the range spans decades), choices as combo
 * boxes, flags (effects, periodic axes) as check boxes, the fluid blocks'
 * keys once per block. It changes nothing itself: each edit comes back as a
 * "section.key=value" assignment, which the window applies as it applies its
 * keys' variants (sph_scene_set, then sph_sim_reconfigure or a new scene),
 * and "Save scene as…" as a path. */
#ifndef SPH_PANEL_H
#define SPH_PANEL_H

#include <stdbool.h>
#include <stddef.h>

#include "sph_scene.h"

#ifdef __cplusplus
extern "C" {
#endif

struct SDL_Window;
union SDL_Event;
typedef struct sph_panel sph_panel;

/* What the user asked for in one frame; empty strings: nothing. */
typedef struct sph_panel_out {
    char set[320];   /* "section.key=value" (fluid keys: "fluid NAME.key=value") */
    char save[1024]; /* save the scene to this path */
} sph_panel_out;

/* Makes the panel's ImGui context in the window's current OpenGL (3.3 core
 * or later) context. save_path: the "Save scene as…" field's first value.
 * NULL with the reason in err on failure. */
sph_panel *sph_panel_create(struct SDL_Window *win, void *gl_context, const char *save_path, char *err, size_t n);
void sph_panel_destroy(sph_panel *p);
/* Hands the panel an event; true if it takes it (the mouse is over the
 * panel, or a text field has the keyboard): the window then ignores it. */
bool sph_panel_event(sph_panel *p, const union SDL_Event *e);
/* Builds one frame of the panel for def in rect (x, y, width, height in the
 * window's coordinates, as SDL's mouse events give them), with the window's
 * last message under it; fills out. */
void sph_panel_frame(sph_panel *p, const sph_scene_def *def, const int rect[4], const char *message, sph_panel_out *out);
/* Draws the frame just built into the current framebuffer (the window's). */
void sph_panel_draw(sph_panel *p);

#ifdef __cplusplus
}
#endif

#endif
