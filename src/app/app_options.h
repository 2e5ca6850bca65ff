/* The command-line options of every sphlab command, declared once.
 *
 * One table (app_options.c) holds a row per option: its name, the placeholder
 * of its value, its help line, the commands that take it and how its value is
 * parsed and where it is stored in an app_opts. One function parses a
 * command's argv from it ("--name value" and "--name=value"), and the option
 * part of every command's --help is printed from it, so the help cannot
 * forget an option nor list one the parser does not know. */
#ifndef SPH_APP_OPTIONS_H
#define SPH_APP_OPTIONS_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include "commands.h"

/* One bit per command of SPH_COMMANDS: APP_CMD(run) | APP_CMD(render). */
enum {
#define APP_CMD_INDEX(name, args, about) APP_CMD_INDEX_##name,
    SPH_COMMANDS(APP_CMD_INDEX)
#undef APP_CMD_INDEX
    APP_CMD_COUNT
};
#define APP_CMD(name) (1u << APP_CMD_INDEX_##name)

#define APP_LIST_MAX 64 /* values of one repeatable option */
#define APP_POS_MAX 4   /* positional arguments a command keeps */
#define APP_REST_MAX 128

/* A repeatable option's values, in the order given. */
typedef struct app_list {
    const char *v[APP_LIST_MAX];
    int n;
} app_list;

/* Every option's value, whichever command takes it. A command sets its
 * defaults after app_opts_init and before app_opts_parse. */
typedef struct app_opts {
    /* flags */
    bool quiet, quick, verbose, list, paused, svg, watchdog, trace, dry_run, panel;
    /* whole numbers */
    long steps, every, threads, frames, steps_per_frame, repeats, dim, bins, seed, at, select;
    long size[2];            /* --size WxH [px], 0 if not given */
    /* numbers */
    double time;             /* --time [s] */
    double h;                /* plot --h [m] */
    double jitter;           /* estimate --jitter [spacings] */
    double fps;              /* bench --fps [steps/s] */
    double slice;            /* --slice [m], NAN if not given */
    /* words, as given (a choice is checked against its accepted words) */
    const char *backend, *gl, *stats, *dump, *vtk, *out, *name, *only, *screenshot, *keys, *metric, *ycols, *xcol,
        *h_list, *n_list, *function, *kernel, *samples, *levels, *solvers, *export_dir, *color, *range, *camera,
        *center, *save_scene, *resolution,
        *video, *format;
    /* repeatable */
    app_list sets, vary, overlay, no_overlay;
    /* positional arguments, in order */
    const char *pos[APP_POS_MAX];
    int n_pos;
    /* with APP_SPEC_PASS_ON: the arguments this command does not know, in order */
    char *rest[APP_REST_MAX];
    int n_rest;
} app_opts;

typedef enum app_opt_kind {
    APP_OPT_HELP,   /* prints the help and stops: exit status 0 */
    APP_OPT_FLAG,   /* bool, no value */
    APP_OPT_INT,    /* long within [lo, hi] */
    APP_OPT_DOUBLE, /* double within [lo, hi] */
    APP_OPT_STRING, /* const char *, at least lo characters */
    APP_OPT_CHOICE, /* const char *, one of the words of `choices` ("cpu|gl") */
    APP_OPT_BASENAME, /* const char *, a file name without '/' (up to 200 characters) */
    APP_OPT_SIZE,   /* long[2] from WxH, each within [lo, hi] */
    APP_OPT_LIST,   /* app_list: each occurrence adds its value */
} app_opt_kind;

typedef struct app_opt {
    const char *name;    /* "--steps" */
    const char *alias;   /* another spelling ("-q", "--colour"), or NULL */
    const char *arg;     /* placeholder of the value in the help ("N"); NULL for a flag */
    const char *help;    /* what it does; "\n" starts a continuation line */
    unsigned cmds;       /* APP_CMD bits of the commands that take it */
    app_opt_kind kind;
    size_t at;           /* offsetof(app_opts, field) */
    double lo, hi;       /* range of INT, DOUBLE and SIZE; STRING: least length */
    const char *choices; /* CHOICE: accepted words, '|' between */
} app_opt;

extern const app_opt app_options[];
/* In an option's help, the place of the pass fields' colour names, which the
 * printers fill from the field registry (app_opt_help). */
#define APP_HELP_PASS_COLOURS "{pass colours}"
/* An option's help as printed: r->help, or a copy in buf with its
 * APP_HELP_PASS_COLOURS filled in. */
const char *app_opt_help(const app_opt *r, char *buf, size_t n);
extern const int app_option_count;

/* How a command takes its arguments, and the prose of its help around the
 * options the table gives it. */
enum {
    APP_SPEC_PASS_ON = 1, /* unknown options and extra arguments go to rest[] (lesson N: to view) */
};
typedef struct app_cmd_spec {
    const char *name;       /* "run" */
    unsigned cmd;           /* APP_CMD(run) */
    const char *synopsis;   /* "usage: sphlab run SCENE.ini [options]\n..." (before the options) */
    const char *footer;     /* after the options, or NULL */
    void (*more)(FILE *f);  /* prints more after the footer (view: the keys), or NULL */
    int max_pos;            /* positional arguments taken */
    const char *extra_pos;  /* message for one more: "more than one scene file" (default: unexpected argument) */
    unsigned flags;         /* APP_SPEC_* */
} app_cmd_spec;

/* Sets every value to "not given": numbers -1 (threads 0), words NULL, lists empty. */
void app_opts_init(app_opts *o);
/* Parses argv[1..argc) (argv[0] is the command) for the command of `spec`
 * into *o. Returns -1 to go on; 0 after printing the help (--help, -h);
 * 2 on a command-line error, message printed ("sphlab CMD: ..."); an unknown
 * option names the closest known one and a hint (app_opts_usage_error). */
int app_opts_parse(const app_cmd_spec *spec, int argc, char **argv, app_opts *o);
/* The command's help: synopsis, its options from the table, footer. */
void app_opts_usage(const app_cmd_spec *spec, FILE *f);
/* A usage error, short, on stderr: "sphlab CMD: WHAT" (if what), the
 * synopsis's usage line, and "see `sphlab CMD --help`" -- not the whole help,
 * which would bury the error. */
void app_opts_usage_error(const app_cmd_spec *spec, const char *what);
/* The known option of the command closest to `arg` (a typo's likely meaning), or NULL. */
const char *app_opts_closest(unsigned cmd, const char *arg);
/* The option of command cmd that arg names (its name or alias, "=VALUE" allowed), or NULL. */
const app_opt *app_opts_find(unsigned cmd, const char *arg);
/* Every command's options as a Markdown reference (docs/commands.md). */
void app_opts_markdown(FILE *f);
/* One line per command and option it takes: "run --steps". */
void app_opts_list(FILE *f);

/* Parses a whole number / a number for option `opt`; prints the error and returns false on failure. */
bool app_parse_int(const char *opt, const char *s, long lo, long hi, long *out);
bool app_parse_double(const char *opt, const char *s, double lo, double hi, double *out);

#endif
