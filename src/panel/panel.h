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

/* [px, window units] the panel's font size; the side column keeps room for
 * the panel's first rows at it (sph_layout_panel_keep, src/render/layout.h). */
#define SPH_PANEL_FONT_PX 15.0f

struct SDL_Window;
union SDL_Event;
typedef struct sph_panel sph_panel;

/* What the user asked for in one frame; empty strings: nothing. */
typedef struct sph_panel_out {
    char set[320];   /* "section.key=value" (fluid keys: "fluid NAME.key=value") */
    char save[1024]; /* save the scene to this path */
    /* the ladder section (sph_panel_set_ladder) */
    int level;       /* the row of the level chosen, -1: none */
    int pass;        /* the pass row switched (its number - 1), -1: none */
    int particles;   /* +1: twice as many, -1: half as many, 0: no change */
    int validate;    /* 1: validate against the first level (L0), 2: against the third (L2), 0: no */
} sph_panel_out;

/* The ladder section's rows, made by the window each frame: the levels of
 * the optimisation ladder and the passes of the pipeline in their order
 * (row k is the pass `sphlab check` numbers k + 1). The strings are the
 * caller's and must live until the frame is built. */
enum { SPH_PANEL_ROWS = 40 };
typedef struct sph_panel_ladder {
    int n_levels, level; /* the current level's row, -1: none of them */
    const char *level_name[SPH_PANEL_ROWS], *level_about[SPH_PANEL_ROWS];
    int n_passes;
    const char *pass_name[SPH_PANEL_ROWS];
    bool pass_on[SPH_PANEL_ROWS];
    unsigned particles;  /* [1] the particle count now */
} sph_panel_ladder;
/* The section the next frames show (NULL: none); the panel keeps the pointer. */
void sph_panel_set_ladder(sph_panel *p, const sph_panel_ladder *ladder);

/* Makes the panel's ImGui context in the window's current OpenGL (3.3 core
 * or later) context. save_path: the "Save scene as…" field's first value;
 * font_path: a TrueType face (the renderer's, so both read alike; NULL or
 * missing: ImGui's own). NULL with the reason in err on failure. */
sph_panel *sph_panel_create(struct SDL_Window *win, void *gl_context, const char *save_path, const char *font_path,
                            char *err, size_t n);
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
