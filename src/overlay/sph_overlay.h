/* What the renderer draws over the particles, computed without GL.
 *
 * Like Box2D's b2DebugDraw, the content of every overlay (cell grid, keys,
 * colliding cells, the selected particle's cells and neighbours, force
 * arrows, the index/offsets strip) is built here as plain primitives: lines,
 * discs, boxes and text labels with positions and colours. The renderer
 * (src/render/) only turns them into pixels, and tests check them without a
 * GL context. The colour fields and colour maps live here for the same reason:
 * the legend and the tests read the same numbers the particles are drawn with.
 *
 * Positions are in world space [m] (SPH_SPACE_WORLD), or in "strip space" for
 * the index strip under the view (SPH_SPACE_STRIP: x counts boxes, y counts
 * rows, origin top-left; the renderer stretches it over the strip's pixels). */
#ifndef SPH_OVERLAY_H
#define SPH_OVERLAY_H

#include <stdbool.h>
#include <stdint.h>

#include "sph_sim.h"

/* Every overlay, written once: the window's toggles (keys 1..9), --overlay
 * names, the help text and the docs expand from this list. hud, timings and
 * legend are drawn by the renderer itself (they are text in pixel space). */
#define SPH_OVERLAYS(X)                                                                          \
    X(GRID, "grid", "cell borders: lines at x = k h")                                            \
    X(KEYS, "keys", "hash key written in each occupied cell")                                   \
    X(COLLISIONS, "collisions", "cells that share a key with another cell, marked red")          \
    X(NEIGHBOURS, "neighbours", "selected particle: its 3^d cells, neighbours, kernel weights")  \
    X(FORCES, "forces", "acceleration arrows: pressure (red), viscosity (blue), gravity (green)") \
    X(INDEX, "index", "sorted entries (particle, key) and offsets (start) as boxes under the view") \
    X(HUD, "hud", "particles, step, time, passes on, density error")                            \
    X(TIMINGS, "timings", "ms per pass as bars, steps per second (changes from run to run)")     \
    X(LEGEND, "legend", "colour bar: field, unit, min and max")

typedef enum sph_overlay_id {
#define SPH_OVERLAY_ENUM(id, name, about) SPH_OV_##id,
    SPH_OVERLAYS(SPH_OVERLAY_ENUM)
#undef SPH_OVERLAY_ENUM
    SPH_OV_COUNT
} sph_overlay_id;
#define SPH_OV_BIT(id) (1u << SPH_OV_##id)

extern const char *const sph_overlay_names[SPH_OV_COUNT];
extern const char *const sph_overlay_about[SPH_OV_COUNT];
/* Looks an overlay up by name; -1 if there is none. */
int sph_overlay_find(const char *name);

/* ---- colour fields ------------------------------------------------------- */

/* What particles can be coloured by: every field of the registry that has a
 * colour name (sph_fields.h; a vector by its length), numbered as the field,
 * then what the index gives each particle and what is made from fields. A colour number below
 * SPH_FIELD_COUNT whose field has no colour name is not a colour. */
typedef enum sph_color_field {
    SPH_COLOR_KEY = SPH_FIELD_COUNT, /* the cell's key in the hash table (categorical colours) */
    SPH_COLOR_NEIGHBOURS,            /* number of neighbours within h */
    SPH_COLOR_DFSPH_PRESSURE,        /* DFSPH's pressure rho (kappa + kappa_v) (sph_sim_pressure): kept as its two
                                        stiffnesses, not as a field */
    SPH_COLOR_COUNT
} sph_color_field;
#define SPH_COLOR_DENSITY ((sph_color_field)SPH_FIELD_RHO)
#define SPH_COLOR_PRESSURE ((sph_color_field)SPH_FIELD_P)
#define SPH_COLOR_SPEED ((sph_color_field)SPH_FIELD_VEL)
#define SPH_COLOR_ACC_P ((sph_color_field)SPH_FIELD_ACC_P)
#define SPH_COLOR_ACC_V ((sph_color_field)SPH_FIELD_ACC_V)

/* Names by colour number ("" for a field without a colour). */
extern const char *const sph_color_field_names[SPH_COLOR_COUNT];
int sph_color_field_find(const char *name);
const char *sph_color_field_unit(sph_color_field f, int dim);
/* NULL if the simulation has the field, else why not (a sentence). */
const char *sph_color_field_missing(const sph_sim *sim, sph_color_field f);
/* The field the simulation shows first: density if computed, else speed. */
sph_color_field sph_color_field_default(const sph_sim *sim);
/* The field a pass writes, for highlighting after one pass; -1 if none. */
int sph_color_field_of_pass(const sph_sim *sim, sph_pass_id p);
/* Fills out[n] with the field (0 where the sim has no such data) and its
 * range over finite values; returns false if the field is missing. */
bool sph_color_field_values(const sph_sim *sim, sph_color_field f, float *out, float *lo, float *hi);
bool sph_color_field_categorical(sph_color_field f);

/* Colours are packed so that their bytes in memory are R, G, B, A. */
#define SPH_RGBA(r, g, b, a) \
    ((uint32_t)(r) | ((uint32_t)(g) << 8) | ((uint32_t)(b) << 16) | ((uint32_t)(a) << 24))
#define SPH_RGBA_ALPHA(c, a) (((c) & 0x00FFFFFFu) | ((uint32_t)(a) << 24))

/* Viridis, t in [0, 1] (clamped; NaN gives grey). */
uint32_t sph_colormap_viridis(float t);
/* Tableau's ten categorical colours; equal keys give equal colours. */
uint32_t sph_colormap_category(uint32_t key);
/* The colour of a value of field f with the given range. */
uint32_t sph_color_of(sph_color_field f, float v, float lo, float hi);
/* A wall particle's colour (fixed walls and obstacles): c's channels
 * SPH_WALL_DIM_PERCENT % of the way to grey SPH_WALL_GREY, rounded, in
 * integers so that particles_direct.vert computes the same bytes. */
#define SPH_WALL_DIM_PERCENT 55
#define SPH_WALL_GREY 128
uint32_t sph_color_dimmed(uint32_t c);

/* ---- primitives ---------------------------------------------------------- */

typedef enum sph_space { SPH_SPACE_WORLD, SPH_SPACE_STRIP } sph_space;
typedef enum sph_text_size { SPH_TEXT_SMALL, SPH_TEXT_NORMAL } sph_text_size;
typedef enum sph_align { SPH_ALIGN_CENTER, SPH_ALIGN_LEFT, SPH_ALIGN_RIGHT } sph_align;

typedef struct sph_ov_line {
    float a[3], b[3];
    uint32_t rgba;
    float width;     /* [px] */
    uint8_t space;   /* sph_space */
    uint8_t arrow;   /* 1: an arrow head at b */
} sph_ov_line;

typedef struct sph_ov_disc {
    float c[3];
    float r;          /* [m] radius in world space */
    float r_min_px;   /* [px] drawn at least this big */
    uint32_t fill, edge; /* alpha 0: none */
    uint8_t space;
} sph_ov_disc;

/* An axis-aligned rectangle in the x-y plane at height z (a cell; in 3D on the slice). */
typedef struct sph_ov_box {
    float min[2], max[2], z;
    uint32_t fill, edge;
    uint8_t space;
} sph_ov_box;

typedef struct sph_ov_label {
    float pos[3];    /* anchor: centre of the text for SPH_ALIGN_CENTER */
    char text[24];
    uint32_t rgba;
    uint8_t space, size, align;
    float fit[2];    /* [m] the box (width, height) around pos the label must fit in, as the view shows it
                        (a cell: 3D skips a key label whose cell is drawn narrower than its text); 0: always */
} sph_ov_label;

/* An occupied cell, as the hash pass filed it. */
typedef struct sph_ov_cell {
    int32_t c[3];    /* cell coordinates, as the hash pass computes them (sph_cells_coord) */
    uint32_t hash, key;
    uint32_t count;  /* particles in it */
    bool collides;   /* another occupied cell has the same key */
} sph_ov_cell;

typedef struct sph_overlay_opts {
    unsigned layers;    /* SPH_OV_BIT(...) */
    int32_t selected;   /* particle index, or -1 */
    float slice_z;      /* [m] 3D: the plane the grid, keys and collisions show on */
    float px_per_m;     /* [px/m] scale of the view; 0: unknown (every label is made) */
    int strip_cols;     /* boxes in the index strip (0: 24) */
    int max_arrows;     /* particles that get force arrows (0: 400); a regular subset */
} sph_overlay_opts;

typedef struct sph_overlay {
    sph_ov_line *lines;
    sph_ov_disc *discs;
    sph_ov_box *boxes;
    sph_ov_label *labels;
    int n_lines, n_discs, n_boxes, n_labels;
    int cap_lines, cap_discs, cap_boxes, cap_labels;

    /* What was built, for the inspector and the tests. */
    int grid_lines[2];      /* lines across x and across y */
    float grid_origin[3];   /* [m] cell borders are at grid_origin + k (cell size) */
    sph_ov_cell *cells;     /* occupied cells (all of them, also in 3D) */
    int n_cells, cap_cells;
    int n_colliding;        /* cells with collides set */
    int32_t selected;       /* -1: none */
    int32_t sel_cell[3];
    uint32_t sel_key;       /* key of the selected particle's cell */
    const uint32_t *nbr;    /* the selected particle's neighbours (indices, whatever the lists' storage) */
    int n_nbr;
    uint32_t *nbr_rows;     /* [cap_nbr] where nbr points: the row copied out of the lists */
    int cap_nbr;
    float *weights;         /* [n_nbr] W(r_ij) / W(0) of the density kernel */
    int cap_weights;
    uint32_t strip_first_entry, strip_first_key; /* windows of the index strip */
    int strip_cols, strip_rows;   /* extent of strip space: boxes plus the title column */
    float arrow_m_per_acc;  /* [m per m/s^2] arrow length scale */
    char note[200];         /* what could not be shown, and why ("" if all) */
} sph_overlay;

/* Builds the overlays of the simulation's current state into ov (reusing its
 * arrays; zero-initialise it once). Returns false only when out of memory. */
bool sph_overlay_build(const sph_sim *sim, const sph_overlay_opts *o, sph_overlay *ov);
void sph_overlay_free(sph_overlay *ov);

/* Cell of particle i as the hash pass sees it: from pred once the external
 * pass of this state wrote it (after the first pass of the first step), else
 * from pos (at step 0 the search sees pos: pred = pos + v dt, dt = 0). */
void sph_overlay_cell_of(const sph_sim *sim, uint32_t i, int32_t c[3]);
/* Cell borders along axis d are at sph_grid_origin(sim, d) + k sph_grid_size(sim, d):
 * the search's cells (sim->S.cells), a hair above h wide. */
float sph_grid_origin(const sph_sim *sim, int d);
float sph_grid_size(const sph_sim *sim, int d);

/* ---- HUD ----------------------------------------------------------------- */

/* Density error shown in the HUD: (rho_max - held) / held over the fluid
 * particles (wall particles left out), held = sph_density_held (sph_sim.h): the largest
 * compression (what incompressible solvers bound); NaN without density, or
 * before the density pass has run. */
double sph_density_error(const sph_sim *sim);

typedef struct sph_hud_info {
    double steps_per_s;  /* measured by the caller; < 0: not shown, nor the ms per step */
    bool paused;
    int last_pass;       /* pass run last when stepping pass by pass; -1 none */
    const char *message; /* a line for the user (screenshot saved, variant changed), or NULL */
    double frames_per_s; /* frames drawn per second, measured by the renderer; <= 0: not shown */
    const char (*extra)[128]; /* the window's ladder lines, after the ms per step (with it only) */
    int n_extra;
    int pass_cursor;     /* the pass chosen in the window, + 1 (0: none): marked in the timings list */
} sph_hud_info;

/* The HUD's text lines (without timings). Returns the number of lines.
 * With steps_per_s >= 0, a line of ms per step (the mean over the last
 * SPH_STEP_WINDOW steps), steps/s and frames/s; with a hash table, two lines
 * of hash health (sph_hash_health.h), recomputed at each call (about a
 * millisecond at 60k particles, see docs/performance.md). */
int sph_hud_lines(const sph_sim *sim, const sph_hud_info *info, char lines[][128], int max_lines);

/* The inspector's lines for particle i: id, position, cell, hash, key,
 * neighbours, density, pressure and each acceleration term. */
int sph_inspect_lines(const sph_sim *sim, uint32_t i, char lines[][128], int max_lines);

#endif
