/* `sphlab study` without its command line (cmd_study.c): what the command
 * does once its options are read, for the lessons, which run a study in
 * process and quote its table. */
#ifndef SPH_STUDY_CMD_H
#define SPH_STUDY_CMD_H

#include <stdio.h>

#include "app.h"
#include "study.h"

typedef struct study_cmd {
    app_scene_opts scene;            /* the scene file and its --set overrides */
    study_plan plan;                 /* the --vary knobs */
    const char *out, *metric, *base; /* --out DIR, --metric (NULL: guessed from the scene), --name */
    long repeats, steps, threads;    /* --repeats, --steps (< 0: none), --threads (0: one per core) */
    double until;                    /* [s] --time, or < 0 */
    bool quiet;                      /* no progress line, no list of files written */
    FILE *table;                     /* where the table goes (the command: stdout, or NULL with --quiet) */
} study_cmd;

/* Runs every combination, writes DIR/BASE.csv and the chart; the command's exit status. */
int study_cmd_run(const study_cmd *c);

#endif
