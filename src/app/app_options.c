/* The option table of every sphlab command, its parser and its help (app_options.h). */
#include "app_options.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "sph_sim.h"
#include "sph_names.h"
#include "../overlay/sph_overlay.h" /* the overlay names, for --overlay's help */

/* The offset of a field of app_opts, and a compile-time check of its type:
 * comparing pointers to different types is an error, so a row cannot store
 * a long where a double is. */
#define AT(field, type) (offsetof(app_opts, field) + 0 * sizeof(&((app_opts *)0)->field == (type *)0))

#define HELP .kind = APP_OPT_HELP
#define FLAG(f) .kind = APP_OPT_FLAG, .at = AT(f, bool)
#define INT(f, l, u) .kind = APP_OPT_INT, .at = AT(f, long), .lo = (l), .hi = (u)
#define DOUBLE(f, l, u) .kind = APP_OPT_DOUBLE, .at = AT(f, double), .lo = (l), .hi = (u)
#define STRING(f) .kind = APP_OPT_STRING, .at = AT(f, const char *)
#define PATH(f) .kind = APP_OPT_STRING, .at = AT(f, const char *), .lo = 1 /* not empty */
#define CHOICE(f, words) .kind = APP_OPT_CHOICE, .at = AT(f, const char *), .choices = (words)
#define BASENAME(f) .kind = APP_OPT_BASENAME, .at = AT(f, const char *)
#define SIZE(f, l, u) .kind = APP_OPT_SIZE, .at = AT(f[0], long), .lo = (l), .hi = (u)
#define LIST(f) .kind = APP_OPT_LIST, .at = AT(f, app_list)

#define RUN APP_CMD(run)
#define CHECK APP_CMD(check)
#define PLOT APP_CMD(plot)
#define RENDER APP_CMD(render)
#define VIEW APP_CMD(view)
#define HARDCASES APP_CMD(hardcases)
#define STUDY APP_CMD(study)
#define ESTIMATE APP_CMD(estimate)
#define LESSON APP_CMD(lesson)
#define BENCH APP_CMD(bench)
#define VALIDATE APP_CMD(validate)
#define MANY 2000000000L

/* A command's --help lists its options in this order. Two rows may share a
 * name when no command takes both (tests/test_options.c checks it). */
const app_opt app_options[] = {
    /* the scene and the run */
    {"--set", NULL, "S.K=V", "override scene key K of section S (repeatable; `sphlab keys` lists them)",
     RUN | CHECK | RENDER | VIEW | STUDY, LIST(sets)},
    {"--save-scene", NULL, "FILE.ini",
     "write the scene, overrides applied, as a scene file (the keys that differ from their\n"
     "defaults); view: where the panel's \"Save scene as\" and the key w write it",
     CHECK | VIEW, STRING(save_scene)},
    {"--set", NULL, "[LEVEL:]S.K=V", "override scene key K of section S, for one level or all (repeatable)", BENCH,
     LIST(sets)},
    {"--steps", NULL, "N", "simulate N steps (default: the scene's duration or steps)", RUN | RENDER,
     INT(steps, 0, MANY)},
    {"--steps", NULL, "N", "run length in steps (default: the scene's duration or steps)", STUDY, INT(steps, 1, MANY)},
    {"--time", NULL, "T", "simulate until T seconds, the last step ending on T (instead of --steps)", RUN | RENDER | STUDY,
     DOUBLE(time, 0, 1e6)},
    {"--threads", NULL, "N", "worker threads (default: one per core)", RUN | RENDER | VIEW | STUDY | VALIDATE,
     INT(threads, 1, SPH_MAX_THREADS)},
    {"--threads", NULL, "N",
     "worker threads of bench pair (default 1: each step's CPU time); the other benchmarks run each level or\n"
     "setting with its own", BENCH,
     INT(threads, 1, SPH_MAX_THREADS)},
    {"--backend", NULL, "cpu|gl",
     "where the passes run (overrides [compute] backend): gl runs them as\n"
     "OpenGL 4.3 compute shaders (the GPU, or Mesa's llvmpipe without one)",
     RUN | CHECK | RENDER | VIEW, CHOICE(backend, "cpu|gl")},
    /* run's outputs */
    {"--stats", NULL, "FILE.csv",
     "one row per step: step,t,dt,n,ekin,rho_min,rho_mean,rho_max,max_speed\n"
     "(rho_*: with summation, the density pass's sums at x + dt v, before any pressure acts),\n"
     "then the milliseconds of each pass in the pipeline, then with [obstacle NAME]s\n"
     "the force the fluid exerts on each, obstacle_NAME_fx,obstacle_NAME_fy(,_fz) [N, N/m in 2D],\n"
     "then with pressure_solver pcisph or dfsph: iterations,density_error,div_iterations,divergence_error,capped,stopped\n"
     "(density_error: the solver's largest (rho - rho_rest)/rho_rest at the step's end;\n"
     "capped and stopped: running totals of the solves since step 0 that reached the iteration cap or were\n"
     "stopped rising; DFSPH's two solves count apart),\n"
     "then with [search] skin > 0: list_builds (the Verlet lists built so far, the start's included: rebuilt when a\n"
     "particle has moved half the skin) and skin_moved [m] (the largest move since their last build, read at this\n"
     "step; 0 at a step that rebuilt them),\n"
     "then with a hash table, its health: hash_keys,hash_load,hash_occupied,hash_colliding,hash_longest_run,\n"
     "hash_candidates,hash_share (empty with --backend gl,\n"
     "which builds no neighbour lists to count)",
     RUN, STRING(stats)},
    {"--dump", NULL, "FILE.csv",
     "final particles: id,x,y,z,vx,vy,vz,rho,p (the pressure the last step applied: the equation of state's, "
     "PCISPH's p_pci or DFSPH's rho (kappa + kappa_v)), then every other field the scene computes",
     RUN, STRING(dump)},
    {"--out", NULL, "DIR", "where the frames go, DIR/frame_NNNNN.png (made if missing)", RENDER, STRING(out)},
    {"--vtk", NULL, "DIR", "particles and all their fields as DIR/particles_NNNNN.vtk (ParaView)", RUN | RENDER,
     STRING(vtk)},
    {"--every", NULL, "K", "a frame (render) or a --vtk file every K steps, the first at step 0 and the last at the run's end (default 10)",
     RUN | RENDER, INT(every, 1, MANY)},
    {"--video", NULL, "FILE", "also write the frames as a video: FILE.mp4 (H.264) or FILE.gif", RENDER, STRING(video)},
    {"--video", NULL, "FILE", "where the record key v writes (.mp4 or .gif; default sphlab-NNNN.mp4)", VIEW,
     STRING(video)},
    {"--fps", NULL, "F", "frames a second of the video (default 25)", RENDER | VIEW, DOUBLE(fps, 1, 120)},
    {"--gl", NULL, "egl|osmesa", "GL context (default egl: EGL surfaceless; osmesa: Mesa's OSMesa)", RENDER,
     CHOICE(gl, "egl|osmesa")},
    /* what render and view draw */
    {"--size", NULL, "WxH", "image size in pixels (default: render 800x600, view 1024x720)", RENDER | VIEW,
     SIZE(size, 64, 8192)},
    {"--color", "--colour", "FIELD",
     "colour by: density pressure speed key neighbours, or a field of a pass the scene runs: " APP_HELP_PASS_COLOURS
     " (with pressure_solver = pcisph or dfsph, pcisph-pressure or dfsph-pressure is the pressure)",
     RENDER | VIEW, STRING(color)},
    {"--range", NULL, "LO,HI",
     "fixed colour range (LO:HI also); render: 'run' (default): one range for the whole\n"
     "run, found by simulating it once before drawing; 'frame': each frame's own min and max\n"
     "(the window's default)",
     RENDER | VIEW, STRING(range)},
    {"--overlay", NULL, "NAME,...", "switch overlays on (repeatable; 'all', 'none'); default: hud,legend (the window\n"
     "adds timings);\n"
     "render's 'all' leaves out timings (wall-clock: frames would differ run to run);\n"
     "the names:"
#define APP_OVERLAY_NAME(id, name, about) " " name
     SPH_OVERLAYS(APP_OVERLAY_NAME)
#undef APP_OVERLAY_NAME
     ,
     RENDER | VIEW, LIST(overlay)},
    {"--no-overlay", NULL, "NAME,...", "switch overlays off (repeatable)", RENDER | VIEW, LIST(no_overlay)},
    {"--select", NULL, "ID", "the particle the neighbours overlay and the index strip follow", RENDER | VIEW,
     INT(select, 0, MANY)},
    {"--slice", NULL, "Z", "3D: the plane z = Z [m] the grid, keys and collisions show on", RENDER | VIEW,
     DOUBLE(slice, -1e6, 1e6)},
    {"--camera", NULL, "Y:P[:Z]", "orbit yaw and pitch [deg] (3D) and zoom (default 30:25:1)", RENDER | VIEW,
     STRING(camera)},
    {"--center", NULL, "X:Y[:Z]", "the point [m] the view centres on (default: the domain's centre)", RENDER | VIEW,
     STRING(center)},
    /* the window */
    {"--paused", NULL, NULL, "start paused", VIEW, FLAG(paused)},
    {"--panel", NULL, NULL, "open the parameter panel (open by default, except in scripted runs; tab toggles it)", VIEW,
     FLAG(panel)},
    {"--steps-per-frame", NULL, "K", "steps between frames (default: as many as fit in 15 ms; 1 when scripted)", VIEW,
     INT(steps_per_frame, 0, 1000000)},
    {"--frames", NULL, "N", "scripted: draw N frames, then exit", VIEW, INT(frames, 1, 1000000)},
    {"--keys", NULL, "KEYS", "scripted: press one key of KEYS before each frame", VIEW, STRING(keys)},
    {"--screenshot", NULL, "FILE", "scripted: save the last frame as a PNG", VIEW, STRING(screenshot)},
    /* plot */
    {"--out", NULL, "DIR",
     "where to write (made if missing; default: the CSV's directory for\n"
     "passes and series, . for kernels)",
     PLOT, STRING(out)},
    {"--name", NULL, "BASE", "file name without extension (default: passes, series-COLS,\nkernel-NAME-2d, kernels-2d)",
     PLOT, BASENAME(name)},
    {"--size", NULL, "WxH", "PNG size in pixels (the PDF is WxH/2 points, same layout)", PLOT, SIZE(size, 200, 8000)},
    {"--dim", NULL, "2|3", "kernels: dimension (default 2); series: units of ekin, rho, obstacle forces", PLOT, INT(dim, 2, 3)},
    {"--h", NULL, "H", "kernels: support radius in m, as a scene takes it (default: the scene default)", PLOT, DOUBLE(h, 1e-4, 1e6)},
    {"--y", NULL, "C[,C...]", "series: the columns to draw", PLOT, STRING(ycols)},
    {"--x", NULL, "t|step", "series: the x axis (default t)", PLOT, STRING(xcol)},
    {"--bins", NULL, "N", "passes: time bins of the stacked chart (default 100)", PLOT, INT(bins, 1, 120)},
    {"--svg", NULL, NULL, "also write BASE.svg", PLOT, FLAG(svg)},
    /* hardcases */
    {"--quick", NULL, NULL, "a quarter of the steps of the long cases (at least 1500), for CI", HARDCASES, FLAG(quick)},
    {"--only", NULL, "NAME", "run one case", HARDCASES, STRING(only)},
    {"--list", NULL, NULL, "list the cases", HARDCASES, FLAG(list)},
    {"--verbose", NULL, NULL, "print the watchdog's report of cases it stopped", HARDCASES, FLAG(verbose)},
    /* study */
    {"--vary", NULL, "KEY=V1,V2,...",
     "a knob and its values (repeatable, up to 8): any scene key as for --set\n"
     "(fluid.spacing, kernels.h, kernels.density, time.cfl, time.dt,\n"
     "physics.stiffness, physics.accumulate, ...), or\n"
     "  h_over_spacing  kernels.h = value x the (finest) fluid spacing\n"
     "  kernel          one kernel for density, pressure and viscosity\n"
     "or scene keys linked by '+', their values too, set together:\n"
     "  physics.pressure_solver+physics.solver_tolerance=eos+0.01,pcisph+0.001",
     STUDY, LIST(vary)},
    {"--out", NULL, "DIR", "where to write (made if missing)", STUDY, STRING(out)},
    {"--metric", NULL, "NAME", "density | density-surface | hydrostatic | taylor-green | compression\n(default: guessed from the scene)",
     STUDY, STRING(metric)},
    {"--repeats", NULL, "N", "runs per combination; the time is their median (default 3)", STUDY,
     INT(repeats, 1, 100)},
    {"--name", NULL, "BASE", "file names BASE.csv, BASE.png, BASE.pdf (default study)", STUDY, BASENAME(name)},
    /* estimate */
    {"--dim", NULL, "1|2", "dimension (default 1; 1D kernels: the same shapes, 1D normalisation)", ESTIMATE,
     INT(dim, 1, 2)},
    {"--function", NULL, "sin|gauss", "sin(2 pi x) [x sin(2 pi y)], or a Gaussian bump of width 0.1 (default sin)",
     ESTIMATE, STRING(function)},
    {"--kernel", NULL, "K", "poly6, spiky, cubic or wendland (default poly6)", ESTIMATE, STRING(kernel)},
    {"--samples", NULL, "lattice|jitter|random",
     "sample positions: lattice nodes, nodes moved up to --jitter spacings,\nor uniform random (default random)",
     ESTIMATE, STRING(samples)},
    {"--jitter", NULL, "J", "largest offset of jittered samples, in spacings (default 0.3)", ESTIMATE,
     DOUBLE(jitter, 0, 0.5)},
    {"--seed", NULL, "S", "random seed (default 1)", ESTIMATE, INT(seed, 0, 2147483647L)},
    {"--h", NULL, "H1,H2,...",
     "support radii, each up to 0.125 (default 0.005,0.01,0.02,0.04,0.08,0.125\nin 1D; 0.01,0.02,0.04,0.08,0.125 in 2D)",
     ESTIMATE, STRING(h_list)},
    {"--n", NULL, "N1,N2,...",
     "samples per unit length (n^dim in all; default 100,1000,10000 in 1D;\n50,100,200 in 2D)", ESTIMATE,
     STRING(n_list)},
    {"--out", NULL, "DIR", "also write DIR/estimate.csv and the chart DIR/estimate.png, .pdf", ESTIMATE, STRING(out)},
    {"--name", NULL, "BASE", "file names (default estimate)", ESTIMATE, BASENAME(name)},
    /* lesson */
    {"--list", NULL, NULL, "the lessons, their level and what each is about", LESSON, FLAG(list)},
    {"--export", NULL, "DIR",
     "without a display: runs the lesson's experiments with this binary's own\n"
     "commands, writes its figures (PNG; charts also as PDF, each beside its\n"
     "CSV) and DIR/report.md with the parameters and the measured numbers;\n"
     "the commands' outputs go to DIR/logs/",
     LESSON, PATH(export_dir)},
    {"--format", NULL, "md|html",
     "with --export: html also writes DIR/report.html (and report.fr.html), the figures\nshown in the page (default md: report.md and report.fr.md only)",
     LESSON, CHOICE(format, "md|html")},
    {"--quick", NULL, NULL, "with --export: fewer steps and variants (for tests: a few seconds a lesson)", LESSON,
     FLAG(quick)},
    {"--quiet", NULL, NULL, "with --export: do not print the commands as they run", LESSON, FLAG(quiet)},
    {"--dry-run", NULL, NULL, "print the window's command instead of running it", LESSON, FLAG(dry_run)},
    /* bench */
    {"--dim", NULL, "2|3", "dimension of the scene (default 3)", BENCH, INT(dim, 2, 3)},
    {"--fps", NULL, "F", "ladder: the frame rate to reach, steps/s (default 60)", BENCH, DOUBLE(fps, 0.01, 1e5)},
    {"--at", NULL, "N",
     "ladder: particle count of the per-pass table (default 20000; --quick 6000); solvers: the dam break's "
     "(default 50000; --quick 4000); pair: the block's (default 20000); scaling: the largest N of the sweep "
     "(default 262144 in 3D, 524288 in 2D; --quick 8192)",
     BENCH, INT(at, 8, 20000000L)},
    {"--time", NULL, "T", "solvers: simulated seconds each run covers, the window the error is measured over "
     "(default 0.02; --quick 0.01)", BENCH, DOUBLE(time, 1e-4, 10)},
    {"--repeats", NULL, "R", "solvers: interleaved rounds of eos and the solver rows (default 5; --quick 1); pair: "
     "rounds (default 15; --quick 3)", BENCH, INT(repeats, 1, 50)},
    {"--quick", NULL, NULL, "small sizes, few repeats (for CI and the tests: the ladder about a minute, scaling about 30 s on 2 cores)", BENCH,
     FLAG(quick)},
    {"--out", NULL, "DIR", "where the CSV, JSON and charts go (made if missing; default .)", BENCH, PATH(out)},
    {"--levels", NULL, "L0,L3,...", "only these levels (default: all)", BENCH, STRING(levels)},
    {"--solvers", NULL, "S,S,...",
     "solvers: only these rows besides eos (pcisph, dfsph, pcisph+, dfsph+, pcisph*, dfsph*; default: all; quote "
     "a list with * from the shell)",
     BENCH, STRING(solvers)},
    {"--watchdog", NULL, NULL, "keep the watchdog's checks on while timing (default off: a debugging aid)", BENCH,
     FLAG(watchdog)},
    {"--trace", NULL, NULL, "one line per measurement on stderr (size, steps/s, repeats, others)", BENCH,
     FLAG(trace)},
    /* validate */
    {"--resolution", NULL, "R[,R...]",
     "the resolutions to run, in the problem's unit (`sphlab validate list`:\n"
     "a/spacing, particles per side, ...; default: three per problem)",
     VALIDATE, STRING(resolution)},
    {"--out", NULL, "DIR", "where NAME.csv, NAME.png and NAME.pdf go (made if missing;\ndefault out/validate)",
     VALIDATE, PATH(out)},
    {"--quick", NULL, NULL,
     "one small resolution and a short run (for tests: seconds a problem); the targets are meant for the\n"
     "default resolutions, and drop-3d's quick run FAILs them, so `validate all --quick` exits 1",
     VALIDATE, FLAG(quick)},
    /* every command */
    {"--quiet", "-q", NULL, "no progress line, no tables, no list of files written (files are still written)",
     RUN | RENDER | PLOT | STUDY | ESTIMATE | BENCH | VALIDATE, FLAG(quiet)},
    {"--help", "-h", NULL, "this text",
     RUN | CHECK | PLOT | RENDER | VIEW | HARDCASES | STUDY | ESTIMATE | LESSON | BENCH | VALIDATE,
     HELP},
};
const int app_option_count = (int)(sizeof app_options / sizeof app_options[0]);

void app_opts_init(app_opts *o)
{
    memset(o, 0, sizeof *o);
    o->steps = o->every = o->frames = o->steps_per_frame = o->repeats = o->dim = o->bins = o->seed = o->at = -1;
    o->select = -1;
    o->threads = 0; /* one per core */
    o->time = -1;
    o->h = o->jitter = o->fps = -1;
    o->slice = NAN;
}

bool app_parse_int(const char *opt, const char *s, long lo, long hi, long *out)
{
    char *end;
    errno = 0;
    long v = s ? strtol(s, &end, 10) : 0;
    if (s && end != s && (*end == '.' || *end == 'e' || *end == 'E') && !errno) {
        /* 1e3 or 1000.0: whole numbers, as a scene file's integer keys take them (steps = 1e9) */
        char *dend;
        errno = 0;
        const double d = strtod(s, &dend);
        if (!*dend && !errno && isfinite(d) && d == floor(d)) {
            if (fabs(d) >= (double)LONG_MAX) {
                fprintf(stderr, "sphlab: %s %s: out of range (accepted: %ld to %ld)\n", opt, s, lo, hi);
                return false;
            }
            v = (long)d;
            end = dend;
        }
        errno = 0;
    }
    if (!s || end == s || *end || (errno && errno != ERANGE)) {
        fprintf(stderr, "sphlab: %s '%s': not a whole number\n", opt, s ? s : "");
        return false;
    }
    if (errno == ERANGE || v < lo || v > hi) { /* ERANGE: whole, but beyond a long */
        if (errno == ERANGE) {
            fprintf(stderr, "sphlab: %s %s: out of range (accepted: %ld to %ld)\n", opt, s, lo, hi);
            return false;
        }
        fprintf(stderr, "sphlab: %s %ld: out of range (accepted: %ld to %ld)\n", opt, v, lo, hi);
        return false;
    }
    *out = v;
    return true;
}

bool app_parse_double(const char *opt, const char *s, double lo, double hi, double *out)
{
    char *end;
    double v = s ? strtod(s, &end) : 0;
    if (!s || end == s || *end) {
        fprintf(stderr, "sphlab: %s '%s': not a number\n", opt, s ? s : "");
        return false;
    }
    if (!isfinite(v) || v < lo || v > hi) {
        fprintf(stderr, "sphlab: %s %s: out of range (accepted: %g to %g)\n", opt, s, lo, hi);
        return false;
    }
    *out = v;
    return true;
}

/* Whether `word` is one of the '|'-separated words of `choices`. */
static bool choice_has(const char *choices, const char *word)
{
    size_t n = strlen(word);
    for (const char *c = choices; *c;) {
        const char *bar = strchr(c, '|');
        size_t len = bar ? (size_t)(bar - c) : strlen(c);
        if (len == n && strncmp(c, word, n) == 0) return true;
        if (!bar) break;
        c = bar + 1;
    }
    return false;
}

static bool parse_size(const char *s, long lo, long hi, long out[2])
{
    char *end;
    errno = 0;
    long w = strtol(s, &end, 10), h = -1;
    if (end != s && (*end == 'x' || *end == 'X')) {
        const char *t = end + 1;
        h = strtol(t, &end, 10);
        if (end == t || *end) h = -1;
    }
    if (errno || w < lo || w > hi || h < lo || h > hi) return false;
    out[0] = w;
    out[1] = h;
    return true;
}

/* Stores the value of option `r` for command `cmd`; false with a message. */
static bool opt_store(const app_opt *r, const char *cmd, const char *v, app_opts *o)
{
    void *dst = (char *)o + r->at;
    switch (r->kind) {
    case APP_OPT_INT: return app_parse_int(r->name, v, (long)r->lo, (long)r->hi, dst);
    case APP_OPT_DOUBLE: return app_parse_double(r->name, v, r->lo, r->hi, dst);
    case APP_OPT_STRING:
        if (strlen(v) < (size_t)r->lo) {
            fprintf(stderr, "sphlab %s: %s: empty, want %s\n", cmd, r->name, r->arg);
            return false;
        }
        *(const char **)dst = v;
        return true;
    case APP_OPT_CHOICE:
        if (!choice_has(r->choices, v)) {
            fprintf(stderr, "sphlab %s: %s '%s': accepted: ", cmd, r->name, v);
            for (const char *c = r->choices; *c; c++) fputs(*c == '|' ? ", " : (char[2]){*c, 0}, stderr);
            fputc('\n', stderr);
            return false;
        }
        *(const char **)dst = v;
        return true;
    case APP_OPT_BASENAME:
        if (!*v || strchr(v, '/') || strlen(v) > 200) {
            fprintf(stderr, "sphlab %s: %s '%s': want a file name without '/' (up to 200 characters)\n", cmd, r->name,
                    v);
            return false;
        }
        *(const char **)dst = v;
        return true;
    case APP_OPT_SIZE:
        if (!parse_size(v, (long)r->lo, (long)r->hi, dst)) {
            fprintf(stderr, "sphlab %s: %s '%s': want WxH in pixels, each %ld to %ld (e.g. 1000x700)\n", cmd, r->name,
                    v, (long)r->lo, (long)r->hi);
            return false;
        }
        return true;
    case APP_OPT_LIST: {
        app_list *l = dst;
        if (l->n == APP_LIST_MAX) {
            fprintf(stderr, "sphlab %s: more than %d %s options\n", cmd, APP_LIST_MAX, r->name);
            return false;
        }
        l->v[l->n++] = v;
        return true;
    }
    case APP_OPT_HELP:
    case APP_OPT_FLAG: break;
    }
    return false;
}

/* The row of `cmd` that argument `a` names ("--name", "--name=value" or
 * the alias), or NULL; *value points after '=' if there is one. */
static const app_opt *opt_find(unsigned cmd, const char *a, const char **value)
{
    for (int k = 0; k < app_option_count; k++) {
        const app_opt *r = &app_options[k];
        if (!(r->cmds & cmd)) continue;
        const char *names[2] = {r->name, r->alias};
        for (int j = 0; j < 2 && names[j]; j++) {
            size_t n = strlen(names[j]);
            if (strncmp(a, names[j], n) != 0 || (a[n] != '\0' && a[n] != '=')) continue;
            *value = a[n] == '=' ? a + n + 1 : NULL;
            return r;
        }
    }
    return NULL;
}

const app_opt *app_opts_find(unsigned cmd, const char *arg)
{
    const char *value;
    return opt_find(cmd, arg, &value);
}

const char *app_opts_closest(unsigned cmd, const char *arg)
{
    char a[64];
    snprintf(a, sizeof a, "%s", arg);
    char *eq = strchr(a, '=');
    if (eq) *eq = '\0';
    const char *best = NULL;
    int best_d = 1 << 30;
    size_t na = strlen(a);
    for (int k = 0; k < app_option_count; k++) {
        const app_opt *r = &app_options[k];
        if (!(r->cmds & cmd)) continue;
        int d = sph_edit_distance(a, r->name);
        /* a prefix of a longer option ("--step" for "--steps-per-frame") counts as close */
        if (na > 3 && strncmp(r->name, a, na) == 0 && d > 2) d = 2;
        if (d < best_d) {
            best_d = d;
            best = r->name;
        }
    }
    size_t limit = na / 3 > 2 ? na / 3 : 2;
    return best && (size_t)best_d <= limit ? best : NULL;
}

int app_opts_parse(const app_cmd_spec *spec, int argc, char **argv, app_opts *o)
{
    const char *cmd = spec->name;
    /* each single-valued option's last value: one given twice keeps the last, and says so, as --set does (a
     * teacher's `--resolution 10 --resolution 12` ran 12 unsaid) */
    enum { SEEN_MAX = 256 };
    const char *seen[SEEN_MAX] = {NULL};
    for (int i = 1; i < argc; i++) {
        char *a = argv[i];
        const char *v = NULL;
        const app_opt *r = a[0] == '-' && a[1] ? opt_find(spec->cmd, a, &v) : NULL;
        if (r && r->kind == APP_OPT_HELP) {
            app_opts_usage(spec, stdout);
            return 0;
        }
        if (r && r->kind == APP_OPT_FLAG) {
            if (v) {
                fprintf(stderr, "sphlab %s: %s takes no value ('%s')\n", cmd, r->name, a);
                return 2;
            }
            *(bool *)((char *)o + r->at) = true;
        } else if (r) {
            if (!v) {
                if (i + 1 >= argc) {
                    fprintf(stderr, "sphlab %s: %s needs a value (%s)\n", cmd, r->name, r->arg);
                    return 2;
                }
                /* "--export --quick": the next word is this command's option,
                 * not a value (a value may start with one '-': a number) */
                const char *next_v = NULL, *next = argv[i + 1];
                if (next[0] == '-' && next[1] == '-' && opt_find(spec->cmd, next, &next_v)) {
                    fprintf(stderr, "sphlab %s: %s needs a value (%s) before the option '%s'\n", cmd, r->name, r->arg,
                            next);
                    return 2;
                }
                v = argv[++i];
            }
            if (!opt_store(r, cmd, v, o)) return 2;
            const long k = r - app_options;
            if (r->kind != APP_OPT_LIST && k >= 0 && k < SEEN_MAX) {
                if (seen[k] && strcmp(seen[k], v) != 0)
                    fprintf(stderr, "sphlab %s: warning: %s is given twice ('%s', then '%s'): the last is used\n", cmd,
                            r->name, seen[k], v);
                seen[k] = v;
            }
        } else if ((a[0] == '-' && a[1]) || o->n_pos == spec->max_pos) {
            if (spec->flags & APP_SPEC_PASS_ON) {
                if (o->n_rest == APP_REST_MAX) {
                    fprintf(stderr, "sphlab %s: more than %d arguments\n", cmd, APP_REST_MAX);
                    return 2;
                }
                o->rest[o->n_rest++] = a;
            } else if (a[0] == '-' && a[1]) {
                const char *near = app_opts_closest(spec->cmd, a);
                fprintf(stderr, "sphlab %s: unknown option '%s'", cmd, a);
                if (near) fprintf(stderr, " (did you mean %s?)", near);
                fprintf(stderr, "\n");
                app_opts_usage_error(spec, NULL);
                return 2;
            } else {
                if (spec->extra_pos)
                    fprintf(stderr, "sphlab %s: %s ('%s')\n", cmd, spec->extra_pos, a);
                else
                    fprintf(stderr, "sphlab %s: unexpected argument '%s'\n", cmd, a);
                return 2;
            }
        } else {
            o->pos[o->n_pos++] = a;
        }
    }
    return -1;
}

/* "--name ARG", or "--name, -a ARG" with the alias. */
static void opt_label(const app_opt *r, char *buf, size_t cap)
{
    snprintf(buf, cap, "%s%s%s%s%s", r->name, r->alias ? ", " : "", r->alias ? r->alias : "", r->arg ? " " : "",
             r->arg ? r->arg : "");
}

void app_opts_usage_error(const app_cmd_spec *spec, const char *what)
{
    if (what) fprintf(stderr, "sphlab %s: %s\n", spec->name, what);
    const char *nl = strchr(spec->synopsis, '\n');
    fprintf(stderr, "%.*s\nsee `sphlab %s --help`\n", nl ? (int)(nl - spec->synopsis) : (int)strlen(spec->synopsis),
            spec->synopsis, spec->name);
}

/* The pass fields' colour names, from the field registry (sph_fields.h): a new
 * field's colour is named in --color's help without an edit here. */
static size_t pass_colours(char *buf, size_t n)
{
    static const char *const own[] = {"density", "pressure", "speed"}; /* named first, in the help's own words */
    const char *names[] = {
#define APP_FIELD_COLOUR(ID, name, comps, unit, unit2, kind, made_by, check, colour, label, about) colour,
        SPH_FIELDS(APP_FIELD_COLOUR)
#undef APP_FIELD_COLOUR
        "dfsph-pressure", /* a colour made from two fields (overlay: SPH_COLOR_DFSPH_PRESSURE) */
    };
    size_t used = 0;
    for (size_t i = 0; i < sizeof names / sizeof *names; i++) {
        bool skip = !*names[i];
        for (size_t k = 0; k < sizeof own / sizeof *own && !skip; k++) skip = strcmp(names[i], own[k]) == 0;
        if (!skip && used < n) used += (size_t)snprintf(buf + used, n - used, "%s%s", used ? " " : "", names[i]);
    }
    return used;
}

const char *app_opt_help(const app_opt *r, char *buf, size_t n)
{
    const char *at = strstr(r->help, APP_HELP_PASS_COLOURS);
    if (!at || n == 0) return r->help;
    char list[1024];
    pass_colours(list, sizeof list);
    snprintf(buf, n, "%.*s%s%s", (int)(at - r->help), r->help, list, at + strlen(APP_HELP_PASS_COLOURS));
    return buf;
}

void app_opts_usage(const app_cmd_spec *spec, FILE *f)
{
    fputs(spec->synopsis, f);
    for (int k = 0; k < app_option_count; k++) {
        const app_opt *r = &app_options[k];
        if (!(r->cmds & spec->cmd)) continue;
        char label[96];
        opt_label(r, label, sizeof label);
        /* a long label gets its own line; continuation lines line up under the help */
        if (strlen(label) > 20) fprintf(f, "  %s\n  %-20s ", label, "");
        else fprintf(f, "  %-20s ", label);
        char expanded[2048];
        for (const char *h = app_opt_help(r, expanded, sizeof expanded); *h; h++) {
            fputc(*h, f);
            if (*h == '\n') fprintf(f, "  %-20s ", "");
        }
        fputc('\n', f);
    }
    if (spec->footer) fputs(spec->footer, f);
    if (spec->more) spec->more(f);
}

static const char *const command_names[] = {
#define APP_CMD_NAME(name, args, about) #name,
    SPH_COMMANDS(APP_CMD_NAME)
#undef APP_CMD_NAME
};
static const char *const command_about[] = {
#define APP_CMD_ABOUT(name, args, about) about,
    SPH_COMMANDS(APP_CMD_ABOUT)
#undef APP_CMD_ABOUT
};

void app_opts_list(FILE *f)
{
    for (int c = 0; c < APP_CMD_COUNT; c++)
        for (int k = 0; k < app_option_count; k++)
            if (app_options[k].cmds & (1u << c)) fprintf(f, "%s %s\n", command_names[c], app_options[k].name);
}

/* Text in a Markdown table cell: one line, '|' escaped (also inside code). */
static void md_cell(FILE *f, const char *s)
{
    for (; *s; s++) {
        if (*s == '\n')
            fputc(' ', f);
        else if (*s == '|')
            fputs("\\|", f);
        else
            fputc(*s, f);
    }
}

void app_opts_markdown(FILE *f)
{
    fputs("# Command-line options\n\n"
          "<!-- Generated from the option table (src/app/app_options.c) by\n"
          "     `sphlab help --markdown > docs/commands.md`; tests/test_options.c checks it is current. -->\n\n"
          "Every option takes its value as `--name value` or `--name=value`. `sphlab CMD --help`\n"
          "(or `sphlab help CMD`) prints the same list with the command's usage. A misspelt option\n"
          "is refused with exit status 2, naming the closest known one.\n",
          f);
    for (int c = 0; c < APP_CMD_COUNT; c++) {
        bool any = false;
        for (int k = 0; k < app_option_count; k++) {
            const app_opt *r = &app_options[k];
            if (!(r->cmds & (1u << c))) continue;
            if (!any) fprintf(f, "\n## sphlab %s\n\n%s.\n\n| option | meaning |\n|---|---|\n", command_names[c],
                              command_about[c]);
            any = true;
            char label[96];
            opt_label(r, label, sizeof label);
            fputs("| `", f);
            md_cell(f, label);
            fputs("` | ", f);
            char expanded[2048];
            md_cell(f, app_opt_help(r, expanded, sizeof expanded));
            fputs(" |\n", f);
        }
        if (!any) fprintf(f, "\n## sphlab %s\n\n%s. No options.\n", command_names[c], command_about[c]);
    }
}
