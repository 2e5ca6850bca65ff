/* Shared by the sphlab commands. */
#ifndef SPH_APP_H
#define SPH_APP_H

#include <stdbool.h>
#include <stdio.h>

#include "app_options.h"
#include "sph_memory.h"
#include "sph_sim.h"
#include "../io/io.h"

#define APP_MAX_SETS 64

/* Options that several commands take. */
typedef struct app_scene_opts {
    const char *path;                 /* scene file */
    const char *sets[APP_MAX_SETS];   /* --set section.key=value, in order */
    int n_sets;
} app_scene_opts;

/* Adds a --set override; false (with a message) past APP_MAX_SETS. */
bool app_scene_add_set(app_scene_opts *o, const char *set);
/* The scene of a command's options: its one positional argument and its
 * --set list, then the override --backend (cpu or gl, checked by the option
 * table) stands for, after the --set options so that it wins over a --set
 * of the same key. False (with a message) past APP_MAX_SETS. */
bool app_scene_from_opts(app_scene_opts *so, const app_opts *o);
bool app_scene_add_backend(app_scene_opts *o, const char *value);

/* Loads the scene, applies the --set overrides, validates; prints the error
 * and returns false on failure. */
bool app_load_scene(const app_scene_opts *o, sph_scene_def *def);
/* The same, returning the exit status: 0 loaded, 1 a bad scene, 2 a bad --set. */
int app_load_scene_status(const app_scene_opts *o, sph_scene_def *def);
/* The exit status for an error: 2 for the command line, SPH_EXIT_MEMORY (5)
 * for a scene that does not fit in memory, 1 for any other. */
int app_error_status(sph_error_code code);


/* Output files go through the I/O layer's atomic writer (src/io/io.h): a
 * unique temporary beside the target, renamed on success, so a failed or
 * interrupted run never leaves a half-written file; a target that is not a
 * regular file, or is one of the command's inputs, is refused. These print
 * the reason ("sphlab: PATH: ...") where the layer returns it. */
typedef sph_out app_out;
bool app_out_open(app_out *o, const char *path);
bool app_out_commit(app_out *o); /* closes and renames; false (and message) on a write error */
void app_out_abort(app_out *o);  /* closes and removes the temporary */


void app_print_pipeline(FILE *f, const sph_sim *sim);
/* Hash health of the scene as created: table size, load, collisions, candidates (see sph_hash_health.h). */
void app_print_hash_health(FILE *f, const sph_sim *sim);
/* What `sphlab check` prints about a scene: its size, effects and pipeline. */
void app_check_report(FILE *f, const char *path, const sph_sim *sim);

/* What `sphlab run` writes (cmd_run.c), for the commands that run a
 * simulation themselves (the lessons): the --stats header and one row per
 * step, the --dump of the particles in id order, and its tables. */
void app_stats_header(FILE *f, const sph_sim *sim);
void app_stats_row(FILE *f, const sph_sim *sim, double dt);
void app_dump_write(FILE *f, const sph_sim *sim);
void app_run_report(FILE *out, const sph_sim *sim, double wall_ms);

#endif
