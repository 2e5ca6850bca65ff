/* The lessons' simulations, run in this process with the core (sph_sim_*):
 * what `sphlab run` does, with its timings and summary read from the sim
 * itself (lx_run), not from its printed tables. Each run still leaves a log
 * in DIR/logs/ (the equivalent command line and the tables `sphlab run`
 * would print), and writes --stats and --dump CSV files the way `sphlab run`
 * does (the same functions, src/app/cmd_run.c). */
#include <stdlib.h>
#include <string.h>

#include "../io/io.h"
#include "app.h"
#include "lesson.h"

/* The command line `sphlab run` would take for these options (for the log). */
static int run_argv(const lx_run_opts *o, const char **argv, int cap, char steps[24], char threads[24])
{
    int n = 0;
    argv[n++] = "sphlab";
    argv[n++] = "run";
    argv[n++] = o->scene;
    if (o->steps >= 0) {
        snprintf(steps, 24, "%ld", o->steps);
        argv[n++] = "--steps";
        argv[n++] = steps;
    }
    if (o->threads > 0) {
        snprintf(threads, 24, "%d", o->threads);
        argv[n++] = "--threads";
        argv[n++] = threads;
    }
    for (int i = 0; i < LX_RUN_MAX_SETS && o->sets[i] && n + 2 < cap - 5; i++) {
        argv[n++] = "--set";
        argv[n++] = o->sets[i];
    }
    if (o->stats) {
        argv[n++] = "--stats";
        argv[n++] = o->stats;
    }
    if (o->dump) {
        argv[n++] = "--dump";
        argv[n++] = o->dump;
    }
    argv[n] = NULL;
    return n;
}

/* The summary of a finished run, from the sim. */
static void run_fill(const sph_sim *sim, double wall_ms, lx_run *r)
{
    memset(r, 0, sizeof *r);
    double total = 0, steps = sim->step ? (double)sim->step : 1;
    for (int p = 0; p < SPH_PASS_COUNT; p++) total += sim->timing[p].total_ms;
    for (int p = 0; p < SPH_PASS_COUNT && r->npass < LX_RUN_MAX_PASSES; p++) {
        if (!sim->in_pipeline[p]) continue;
        snprintf(r->pass[r->npass], sizeof r->pass[0], "%s", sph_passes[p]->name);
        r->ms_step[r->npass] = sim->timing[p].total_ms / steps;
        r->share[r->npass++] = total > 0 ? 100.0 * sim->timing[p].total_ms / total : 0.0;
    }
    r->total_ms_step = total / steps;
    r->steps = (long)sim->step;
    r->t_sim = sim->t;
    r->wall_s = wall_ms / 1e3;
    r->steps_per_s = wall_ms > 0 ? (double)sim->step / (wall_ms / 1e3) : 0;
    sph_stats s;
    sph_sim_stats(sim, &s);
    r->ekin = s.ekin;
    r->rho_min = s.rho_min;
    r->rho_mean = s.rho_mean;
    r->rho_max = s.rho_max;
    r->threads = sim->threads;
    r->particles = s.n;
}

/* Marks the run failed: counted, and named in the report with its log. */
static bool run_failed(lx *x, const char *log_path, const char *const *argv, const char *why)
{
    x->failed++;
    fprintf(stderr, "sphlab lesson %d: a run failed (%s); its log is %s:\n  ", x->L->num, why, log_path);
    lx_print_args(stderr, argv);
    fputc('\n', stderr);
    lx_md(x, "\n**A run failed** (%s), see `logs/%s`:\n\n```\n", why, strrchr(log_path, '/') + 1);
    lx_md_args(x, argv);
    return false;
}

/* The scene with its overrides, as `sphlab run` loads it, but its error or
 * warning goes into the run's log: a lesson's export prints only the
 * commands (none with --quiet), and the log is where a run's words go. */
static bool load_into_log(const app_scene_opts *so, sph_scene_def *def, FILE *lf)
{
    sph_error err;
    *def = sph_default_scene_def();
    sph_io_add_input(so->path);
    bool ok = sph_scene_load(so->path, def, &err) == SPH_ERR_OK;
    for (int i = 0; ok && i < so->n_sets; i++) ok = sph_scene_set(def, so->sets[i], &err) == SPH_ERR_OK;
    ok = ok && sph_scene_validate(def, &err) == SPH_ERR_OK;
    if (!ok) {
        fprintf(lf, "sphlab: %s\n", err.msg);
        return false;
    }
    sph_scene_warnings_print(def, lf);
    return true;
}

bool lx_run_sim(lx *x, const char *log, const lx_run_opts *o, lx_run *r)
{
    return lx_run_sim_stoppable(x, log, o, r, NULL);
}

bool lx_run_sim_stoppable(lx *x, const char *log, const lx_run_opts *o, lx_run *r, bool *stopped)
{
    const char *argv[2 * LX_RUN_MAX_SETS + 16];
    char steps_s[24], threads_s[24];
    run_argv(o, argv, (int)(sizeof argv / sizeof argv[0]), steps_s, threads_s);
    const char *log_path;
    FILE *lf = lx_log_open(x, log, argv, &log_path);
    if (!lf) return run_failed(x, log_path, argv, "cannot write its log");

    app_scene_opts so = {.path = o->scene};
    for (int i = 0; i < LX_RUN_MAX_SETS && o->sets[i]; i++) so.sets[so.n_sets++] = o->sets[i];
    sph_scene_def def;
    sph_sim *sim = NULL;
    sph_error err;
    const char *why = NULL;
    if (!load_into_log(&so, &def, lf)) why = "the scene does not load";
    else if (sph_sim_create(&def, o->threads, &sim, &err) != SPH_ERR_OK) {
        fprintf(lf, "sphlab: %s\n", err.msg);
        why = "the simulation cannot be made";
    }
    if (why) {
        fclose(lf);
        return run_failed(x, log_path, argv, why);
    }
    long steps = o->steps;
    double until = -1;
    if (steps < 0) {
        if (def.duration > 0) until = def.duration;
        else steps = def.steps;
    }
    app_out stats = {0}, dump = {0};
    bool ok = (!o->stats || app_out_open(&stats, o->stats)) && (!o->dump || app_out_open(&dump, o->dump));
    if (stats.f) app_stats_header(stats.f, sim);
    if (until >= 0) sph_sim_end_at(sim, until); /* as the `sphlab run` it logs: the last step ends on it */
    double t0 = sph_now_ms();
    while (ok && !(until >= 0 ? sph_sim_reached(sim, until) : (long)sim->step >= steps)) {
        sph_sim_step(sim);
        if (sim->alarm.raised) break;
        if (stats.f) {
            sph_sim_collect_times(sim); /* this step's pass times (a GL backend's timer queries come later) */
            app_stats_row(stats.f, sim, sim->dt);
        }
    }
    double wall = sph_now_ms() - t0;
    sph_sim_collect_times(sim); /* the table counts every step */
    if (stopped) *stopped = sim->alarm.raised;
    if (sim->alarm.raised) {
        char report[4096];
        sph_sim_alarm_report(sim, report, sizeof report);
        fprintf(lf, "sphlab: %s", report);
        if (!stopped) why = "the watchdog stopped it";
    }
    if (dump.f) app_dump_write(dump.f, sim);
    bool stats_ok = app_out_commit(&stats), dump_ok = app_out_commit(&dump);
    if (!ok || !stats_ok || !dump_ok) why = "cannot write its output";
    app_run_report(lf, sim, wall);
    fclose(lf);
    if (r) run_fill(sim, wall, r);
    sph_sim_destroy(sim);
    if (why) return run_failed(x, log_path, argv, why);
    return true;
}

double lx_run_pass(const lx_run *r, const char *pass)
{
    for (int i = 0; i < r->npass; i++)
        if (strcmp(r->pass[i], pass) == 0) return r->ms_step[i];
    return -1;
}

int lx_check(lx *x, const char *scene, char names[][24], int cap)
{
    const char *argv[] = {"sphlab", "check", scene, NULL};
    const char *log_path;
    FILE *lf = lx_log_open(x, "check", argv, &log_path);
    if (!lf) return run_failed(x, log_path, argv, "cannot write its log"), 0;
    app_scene_opts so = {.path = scene};
    sph_scene_def def;
    sph_sim *sim = NULL;
    sph_error err;
    if (!app_load_scene(&so, &def) || sph_sim_create(&def, 1, &sim, &err) != SPH_ERR_OK) {
        fclose(lf);
        return run_failed(x, log_path, argv, "the scene does not load"), 0;
    }
    /* the report shows what `sphlab check` prints, from the same function */
    char *text = NULL;
    size_t len = 0;
    FILE *m = open_memstream(&text, &len);
    if (m) {
        app_check_report(m, scene, sim);
        fclose(m);
        fputs(text, lf);
        lx_md_text(x, text, 40);
        free(text);
    }
    fclose(lf);
    int n = 0;
    for (int p = 0; p < SPH_PASS_COUNT && n < cap; p++)
        if (sim->in_pipeline[p]) snprintf(names[n++], 24, "%s", sph_passes[p]->name);
    sph_sim_destroy(sim);
    return n;
}

bool lx_plot(lx *x, const char *log, const plot_opts *o)
{
    /* the log names the equivalent command line */
    const char *argv[24];
    char dim[8], h[32];
    int n = 0;
    argv[n++] = "sphlab";
    argv[n++] = "plot";
    argv[n++] = o->what;
    if (o->input) argv[n++] = o->input;
    if (o->ycols) argv[n++] = "--y", argv[n++] = o->ycols;
    if (o->dim) snprintf(dim, sizeof dim, "%d", o->dim), argv[n++] = "--dim", argv[n++] = dim;
    if (o->h > 0) snprintf(h, sizeof h, "%g", o->h), argv[n++] = "--h", argv[n++] = h;
    if (o->name) argv[n++] = "--name", argv[n++] = o->name;
    if (o->out) argv[n++] = "--out", argv[n++] = o->out;
    argv[n] = NULL;
    const char *log_path;
    FILE *lf = lx_log_open(x, log, argv, &log_path);
    if (lf) fclose(lf);
    if (plot_run(o) == 0) return true;
    return run_failed(x, log_path, argv, "the chart could not be drawn");
}
