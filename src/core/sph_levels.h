/* The optimisation ladder's levels, defined once: `sphlab bench` measures
 * them and the window (`sphlab view`) switches between them live. A level
 * is a set of scene keys and a thread count; the keys of the ingredients
 * (search method, sort, reorder, vector loops, backend) are named on every
 * line, so a level does not change when a default does. */
#ifndef SPH_LEVELS_H
#define SPH_LEVELS_H

#include <stdbool.h>

#include "sph_error.h"
#include "sph_scene.h"

typedef struct sph_level {
    const char *name;  /* short name, e.g. "L3" */
    const char *about; /* what it is, in a few words (no commas: it goes into CSV files) */
    const char *sets;  /* scene overrides "section.key=value", separated by spaces */
    int threads;       /* 1, or 0: one per core */
    const char *about_fr; /* about, in French (lessons' French reports; no commas) */
} sph_level;

extern const sph_level sph_levels[];
extern const int sph_level_count;

/* Index of the level named `name` in sph_levels[], or -1. */
int sph_level_find(const char *name);
/* The level runs on the GL backend (compute.backend = gl). */
bool sph_level_gl(const sph_level *L);
/* Applies the level's scene keys to def (its thread count is the caller's). */
sph_error_code sph_level_apply(const sph_level *L, sph_scene_def *def, sph_error *err);
/* The level whose keys def already has and whose thread count is `threads`
 * (0 or the core count: one per core), or -1 if none matches: the window
 * names the level the user's ingredients amount to. */
int sph_level_of(const sph_scene_def *def, int threads, int cores);

#endif
