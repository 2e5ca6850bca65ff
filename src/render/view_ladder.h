/* The window's ladder (sphlab view): which level of the optimisation ladder
 * (src/core/sph_levels.h) the running simulation is at, its speed measured
 * live per level, the validate mode's last result, the particle count's
 * scaling, and the passes numbered as `sphlab check` numbers them. No SDL,
 * no GL: the window's keys (view_keys.c) switch the simulation, this file does the arithmetic
 * and the HUD's lines. */
#ifndef SPH_VIEW_LADDER_H
#define SPH_VIEW_LADDER_H

#include <stdbool.h>
#include <stddef.h>

#include "sph_compare.h"
#include "sph_levels.h"
#include "sph_sim.h"

enum { VIEW_LEVELS_MAX = 32, VIEW_MEASURE_STEPS = 30 };
/* Above this many particles validate refuses a brute-force reference: 6
 * steps of N^2 / 2 pairs on one thread (about 1e8 pairs/s) take seconds. */
#define VIEW_VALIDATE_BRUTE_MAX 20000u

typedef struct view_ladder {
    double ms[VIEW_LEVELS_MAX]; /* [ms] mean step time measured live at each level, at n; 0: not visited */
    uint32_t n;                 /* [1] the particle count the times are for (a new N clears them) */
    bool validated;             /* a validate result is held */
    sph_compare_result val;
    char val_ref[8];            /* the reference level's name */
    uint64_t val_step;          /* the step it was taken at */
    /* the last `sphlab bench ladder` CSV of this dimension, if one was found:
     * each level's ms per step at the bench's own N (its scene, not this one) */
    double csv_ms[VIEW_LEVELS_MAX]; /* [ms] 0: not in it */
    double csv_n[VIEW_LEVELS_MAX];  /* [1] the N it was measured at */
    char csv_path[256];             /* "" if none */
} view_ladder;

/* Reads the ladder CSV at path (`sphlab bench ladder` writes ladder-2d.csv
 * and ladder-3d.csv): the columns level, n_at and ms_per_step. False (and
 * nothing kept) if it cannot be read or lacks them. */
bool view_ladder_load_csv(view_ladder *l, const char *path);

/* The level sim is at (its keys and threads), or -1. */
int view_ladder_level(const sph_sim *sim);
/* Records the mean step time of the current level once SPH_STEP_WINDOW
 * steps (at least VIEW_MEASURE_STEPS) were timed at this N. */
void view_ladder_record(view_ladder *l, const sph_sim *sim);
/* The HUD's ladder lines: the level and its ingredients, the speed-ups
 * against the level below and L0, the largest N at 60 steps/s, the last
 * validate result. Returns the number of lines. */
int view_ladder_lines(const view_ladder *l, const sph_sim *sim, char lines[][128], int max_lines);
/* def at another resolution: every block's spacing, h (and a fixed dt)
 * times factor, so N changes by factor^-dim and h / spacing is kept. False
 * with the reason if the scene it makes is refused. */
bool view_scene_rescaled(const sph_scene_def *def, float factor, sph_scene_def *out, char *why, size_t n);
/* The running simulation *sim (of *def, on *threads threads, 0: one per
 * core) carried into a simulation of next on next_threads: the particles,
 * velocities and time kept (sph_sim_clone), so a level or thread switch
 * goes on where the flow is. On failure (a GL level where no OpenGL 4.3
 * device can be made, a scene refused) nothing changes. The message (to
 * show) in msg either way; true if switched. */
bool view_switch(sph_sim **sim, sph_scene_def *def, int *threads, const sph_scene_def *next, int next_threads,
                 const char *what, char *msg, size_t n);
/* The level's keys and threads applied to the running simulation. */
bool view_go_level(sph_sim **sim, sph_scene_def *def, int *threads, int level, char *msg, size_t n);
/* The next (dir = 1) or previous (-1) level; a GL level that cannot be made is passed over (its reason kept). */
bool view_next_level(sph_sim **sim, sph_scene_def *def, int *threads, int dir, char *msg, size_t n);
/* Validate mode: sim against the reference level named ref for 5 steps from
 * its state (sph_sim_validate); the result kept in l. The message in msg. */
bool view_validate(view_ladder *l, const sph_sim *sim, const char *ref, char *msg, size_t n);

/* Pass numbers as `sphlab check` prints them: 1 for the first pass in the
 * pipeline. 0 for a pass not in it; the pass of number k, or -1. */
int view_pass_number(const sph_sim *sim, int pass);
int view_pass_of_number(const sph_sim *sim, int number);
/* The next (dir = 1) or previous (-1) pass in the pipeline after `pass` (-1: the first or last). */
int view_pass_next(const sph_sim *sim, int pass, int dir);

#endif
