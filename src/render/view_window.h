/* The live window of sphlab view: its state (cmd_view.c runs it) and the
 * actions its keys and its parameter panel take (view_keys.c). */
#ifndef SPH_VIEW_WINDOW_H
#define SPH_VIEW_WINDOW_H

#include <SDL.h>
#include <stdbool.h>
#include <stdio.h>

#include "cmd_common.h"
#include "panel.h"
#include "view_ladder.h"
#include "view_record.h"

typedef struct viewer {
    sph_scene_def def;   /* current definition: variants switched here */
    sph_scene_def start; /* as loaded, for messages */
    sph_sim *sim;
    sph_renderer *r;
    sph_view v;
    int threads;
    bool paused, help, quit;
    sph_color_field user_field; /* the field chosen by the user, restored after pass stepping */
    long sel_id;         /* the selected particle's id (its index changes when particles are reordered), or -1 */
    int last_pass;
    char msg[200];
    double msg_until;
    double sps;          /* steps per second, smoothed */
    /* mouse */
    bool down[3];
    float press[2];
    bool dragging;
    int shots;
    char panel[24][128];
    bool scripted;
    /* the parameter panel (src/panel/) beside the view */
    sph_panel *params;
    bool params_open;
    char save_path[1024]; /* where Save scene as and the key w write */
    float cursor[2];      /* [px] the mouse in the frame, or -1 when outside the window */
    /* the ladder (view_ladder.h): live speed per level, validate, the chosen pass */
    view_ladder ladder;
    int pass_cursor;      /* the pass the keys n and d act on, or -1 */
    char ladder_lines[8][128];
    view_rec rec; /* the record key: a video of what is on screen */
} viewer;


/* The key bindings, written once: the help panel, `--help` and
 * docs/rendering.md list them from here (view_keys.c). */
extern const char *const viewer_key_names[];
extern const char *const viewer_key_about[];
extern const int viewer_key_count;
/* The bindings, one a line, for `sphlab view --help`. */
void viewer_keys_print(FILE *f);

/* A key pressed in the window (SDL_KEYDOWN), with its modifiers. */
void viewer_key_down(viewer *w, SDL_Keycode k, Uint16 mod);
/* Scripted keys: one character each ('.', ' ', digits, letters; '\n' is enter, '\t' tab). */
void viewer_key_char(viewer *w, char c);

/* The message line (the HUD and the panel show it for 4 s; a scripted run prints it). */
void viewer_say(viewer *w, const char *fmt, ...) __attribute__((format(printf, 2, 3)));

/* The actions the parameter panel takes too (view_keys.c). */
/* A change given as a --set option ("section.key=value"): checked, then
 * applied to the running simulation, or as a new scene where it must. */
void viewer_apply_change(viewer *w, const char *assignment);
void viewer_save_scene(viewer *w, const char *path);
/* Zooms by factor towards the world point at (camera.c). */
void viewer_zoom_at(viewer *w, float factor, const float at[3]);
/* A PNG of what is on screen; path NULL: sphlab-NNNN.png in the current directory. */
void viewer_screenshot(viewer *w, const char *path);
void viewer_record_toggle(viewer *w);
/* Pass p (an sph_pass_id) on or off; the reason said when it is not in the pipeline. */
void viewer_toggle_pass(viewer *w, int p);
/* The ladder's level l (sph_levels[]), validate mode against ref ("L0", "L2"). */
void viewer_go_level(viewer *w, int l);
void viewer_validate(viewer *w, const char *ref);
/* Twice (more) or half as many particles, the scene filled again. */
void viewer_rescale(viewer *w, bool more);

#endif
