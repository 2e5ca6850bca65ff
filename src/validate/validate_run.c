/* What every problem of `sphlab validate` shares: its scene at a resolution,
 * the stepping loop with an observer, the output files and the verdict. */
#define _DEFAULT_SOURCE /* getloadavg */
#include "validate_run.h"

#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include <unistd.h>

#include "sph_walls.h"

/* scenes/validate/FILE from the working directory, else beside the binary
 * (a build run from elsewhere still finds the scenes it was built with);
 * where: the folders looked in, for the message when neither has it. */
static bool scene_path(const char *file, char *out, size_t n, char *where, size_t wn)
{
    snprintf(out, n, "scenes/validate/%s", file);
    if (access(out, R_OK) == 0) return true;
    char cwd[PATH_MAX];
    snprintf(where, wn, "%s", getcwd(cwd, sizeof cwd) ? cwd : ".");
    char exe[PATH_MAX];
    ssize_t len = readlink("/proc/self/exe", exe, sizeof exe - 1);
    if (len > 0) {
        exe[len] = '\0';
        char *slash = strrchr(exe, '/');
        if (slash) *slash = '\0';
        snprintf(out, n, "%s/scenes/validate/%s", exe, file);
        if (access(out, R_OK) == 0) return true;
        size_t used = strlen(where);
        snprintf(where + used, wn - used, " nor %s", exe);
    }
    snprintf(out, n, "scenes/validate/%s", file);
    return false;
}

bool val_scene_unchecked(const char *file, double spacing, sph_scene_def *def)
{
    char path[PATH_MAX + 64];
    char where[2 * PATH_MAX + 8];
    if (!scene_path(file, path, sizeof path, where, sizeof where)) {
        fprintf(stderr,
                "sphlab validate: %s: not found in %s (run sphlab from the project's directory, or keep the "
                "project's scenes/ beside the binary)\n",
                path, where);
        return false;
    }
    sph_error err;
    *def = sph_default_scene_def();
    if (sph_scene_load(path, def, &err) != SPH_ERR_OK) {
        fprintf(stderr, "sphlab validate: %s\n", err.msg);
        return false;
    }
    /* every block on the new spacing; h keeps its ratio to the spacing */
    double ratio = def->h / def->blocks[0].spacing;
    for (int b = 0; b < def->n_blocks; b++) def->blocks[b].spacing = (float)spacing;
    def->h = (float)(ratio * spacing);
    return true;
}

bool val_scene(const char *file, double spacing, sph_scene_def *def)
{
    if (!val_scene_unchecked(file, spacing, def)) return false;
    sph_error err;
    if (sph_scene_validate(def, &err) != SPH_ERR_OK) {
        fprintf(stderr, "sphlab validate: %s (at spacing %g m)\n", err.msg, spacing);
        return false;
    }
    return true;
}

/* What each run of the problem cost, for the verdict's cost line and
 * NAME-cost.csv: the command runs one problem at a time, and val_verdict
 * empties the list. */
enum { VAL_MAX_COSTS = 16 };
static struct val_cost {
    char label[64];
    uint32_t particles, fluid;
    unsigned long long steps;
    double t_sim, wall_s, cpu_s; /* [s] simulated, elapsed, process CPU */
    double error;                /* the problem's error measure, NaN: none given */
} costs[VAL_MAX_COSTS];
static int ncosts;
/* The pressure model the problem's runs used when it is not the equation of
 * state (a user's copy of the scene, with pressure_solver), for the verdict:
 * its line is otherwise the same as the shipped scene's. "" for eos. */
static char model[96];

static double cpu_seconds(void)
{
    struct timespec ts;
    return clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &ts) == 0 ? (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec : NAN;
}

void val_cost_error(int run, double error)
{
    if (run >= 0 && run < ncosts) costs[run].error = error;
}

val_clock val_clock_start(void)
{
    return (val_clock){.ms = sph_now_ms(), .cpu_s = cpu_seconds()};
}

void val_cost_add(const char *label, const sph_sim *sim, val_clock since)
{
    const sph_scene_def *def = &sim->def;
    if (!*model && def->pressure_solver != SPH_PSOLVER_EOS) {
        /* the walls' pressure under a solver only where there are wall particles */
        bool walls = val_fluid_count(sim) < (double)sim->n;
        snprintf(model, sizeof model, "pressure_solver = %s%s%s", sph_pressure_solver_names[def->pressure_solver],
                 walls ? ", solver_wall_pressure = " : "",
                 walls ? sph_solver_wall_pressure_names[def->solver_wall_pressure] : "");
    }
    if (ncosts >= VAL_MAX_COSTS) return;
    struct val_cost *k = &costs[ncosts++];
    snprintf(k->label, sizeof k->label, "%s", label);
    k->particles = sim->n;
    k->fluid = (uint32_t)val_fluid_count(sim);
    k->steps = (unsigned long long)sim->step;
    k->t_sim = sim->t;
    k->wall_s = (sph_now_ms() - since.ms) / 1e3;
    k->cpu_s = cpu_seconds() - since.cpu_s;
    k->error = NAN;
}

bool val_run(const val_ctx *c, const char *label, const sph_scene_def *def, double t_end, val_observe_fn fn, void *ctx)
{
    sph_sim *sim;
    sph_error err;
    if (sph_sim_create(def, c->threads, &sim, &err) != SPH_ERR_OK) {
        fprintf(stderr, "sphlab validate: %s: %s\n", label, err.msg);
        return false;
    }
    bool ok = true;
    const val_clock clock = val_clock_start();
    double shown = clock.ms, start = shown;
    const bool tty = isatty(STDERR_FILENO) != 0;
    /* the observers read the particles' fields: on the GL backend the host copies are refreshed on demand
     * (the hydrostatic tank read p = 0 and v = 0 there, and passed) */
    const sph_mask fields = SPH_SYNC_ALL & ~(SPH_SYNC_INDEX | SPH_SYNC_LISTS);
    sph_sim_sync(sim, fields);
    fn(ctx, sim);
    while (sim->t < t_end - 1e-12) {
        sph_sim_step(sim);
        if (sim->alarm.raised) {
            char report[4096];
            sph_sim_alarm_report(sim, report, sizeof report);
            char *nl = strchr(report, '\n');
            if (nl) *nl = '\0';
            fprintf(stderr, "%ssphlab validate: %s: stopped by the watchdog at t = %.4g s: %s\n", c->quiet ? "" : "\n",
                    label, sim->t, report);
            ok = false;
            break;
        }
        sph_sim_sync(sim, fields);
        fn(ctx, sim);
        double now = sph_now_ms();
        /* on a terminal a line rewritten in place; into a file or a pipe (a log, CI) a line every 30 s */
        if (!c->quiet && now - shown > (tty ? 250 : 30000)) {
            shown = now;
            fprintf(stderr, tty ? "\r  %-40.40s %3.0f%%  %5.0f s" : "  %-40.40s %3.0f%%  %5.0f s\n", label,
                    100 * sim->t / t_end, (now - start) / 1e3);
        }
    }
    if (!c->quiet) {
        if (tty) fprintf(stderr, "\r%-62s\r", ""); /* the progress line's place, blanked */
        fprintf(stderr, "  %-40.40s done: %u particles, %llu steps, %.1f s\n", label, sim->n,
                (unsigned long long)sim->step, (sph_now_ms() - start) / 1e3);
    }
    val_cost_add(label, sim, clock);
    sph_sim_destroy(sim);
    return ok;
}

double val_fluid_count(const sph_sim *sim)
{
    double n = 0;
    for (uint32_t i = 0; i < sim->n; i++) n += !sph_is_wall(&sim->P, i);
    return n;
}

FILE *val_csv(const val_ctx *c, const char *file)
{
    return plot_out_stage_csv(c->out, file);
}

bool val_csv_close(const val_ctx *c, FILE *f, const char *file)
{
    return plot_out_close_csv(f, c->out, file);
}

bool val_chart(const val_ctx *c, const char *base, const plot_lines *chart)
{
    return plot_chart(PLOT_LINES, chart, c->out, base, 1400, 1000);
}

/* The 1-minute load average, for the cost line (times on a busy machine are longer). */
static const char *load_text(void)
{
    static char buf[32];
    double l[1];
    if (getloadavg(l, 1) == 1)
        snprintf(buf, sizeof buf, "%.1f", l[0]);
    else
        snprintf(buf, sizeof buf, "unknown");
    return buf;
}

int val_verdict(const val_ctx *c, const val_problem *p, bool outputs_ok, bool pass, const char *fmt, ...)
{
    char run_with[128] = "";
    if (*model) snprintf(run_with, sizeof run_with, " (run with %s)", model);
    model[0] = '\0'; /* the next problem (validate all) starts without */
    if (!outputs_ok) {
        plot_out_abort();
        fprintf(stderr, "sphlab validate %s: the run or its outputs failed (above); no verdict\n", p->name);
        return VAL_ERROR;
    }
    /* what each run cost: a CSV beside the others, and one line below the verdict */
    char cost[1024] = "";
    if (ncosts) {
        char file[96];
        snprintf(file, sizeof file, "%s-cost.csv", p->name);
        FILE *f = val_csv(c, file);
        if (f) {
            fprintf(f, "run,particles,fluid_particles,steps,t_sim,wall_s,cpu_s,ms_per_sim_s,error\n");
            for (int i = 0; i < ncosts; i++) {
                const struct val_cost *k = &costs[i];
                fprintf(f, "\"%s\",%u,%u,%llu,%.6g,%.4g,%.4g,%.4g,", k->label, k->particles, k->fluid, k->steps,
                        k->t_sim, k->wall_s, k->cpu_s, k->t_sim > 0 ? 1e3 * k->wall_s / k->t_sim : NAN);
                if (isfinite(k->error)) fprintf(f, "%.6g", k->error); /* empty: the problem gave none */
                fputc('\n', f);
            }
            if (!val_csv_close(c, f, file)) outputs_ok = false;
        }
        for (int i = 0; i < ncosts; i++) {
            const struct val_cost *k = &costs[i];
            val_append(cost, sizeof cost,
                       "%s%s: %u particles, %llu steps, %.3g s (%.3g s CPU), %.3g ms per simulated s", i ? "; " : "", k->label, k->particles, k->steps, k->wall_s, k->cpu_s,
                       k->t_sim > 0 ? 1e3 * k->wall_s / k->t_sim : NAN);
        }
        ncosts = 0;
    }
    if (!outputs_ok) {
        plot_out_abort();
        fprintf(stderr, "sphlab validate %s: the outputs failed (above); no verdict\n", p->name);
        return VAL_ERROR;
    }
    if (!plot_out_commit(c->quiet)) return VAL_ERROR;
    char text[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(text, sizeof text, fmt, ap);
    va_end(ap);
    printf("validate %s: %s: %s%s%s\n", p->name, pass ? "PASS" : "FAIL", text, run_with,
           c->quick ? " [--quick: one small resolution and a short run, to try the command; the targets are meant "
                      "for the default resolutions, so a FAIL here says little]"
                    : "");
    if (*cost) printf("validate %s: cost (this machine, load %s): %s\n", p->name, load_text(), cost);
    fflush(stdout);
    return pass ? VAL_PASS : VAL_FAIL;
}

void val_append(char *buf, size_t n, const char *fmt, ...)
{
    size_t len = strlen(buf);
    if (len >= n) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(buf + len, n - len, fmt, ap);
    va_end(ap);
}

/* ---- a growing series ---------------------------------------------------- */

bool val_series_add(val_series *s, double x, double y)
{
    if (s->n == s->cap) {
        size_t cap = s->cap ? 2 * s->cap : 256;
        double *nx = realloc(s->x, cap * sizeof *nx);
        if (!nx) return false;
        s->x = nx;
        double *ny = realloc(s->y, cap * sizeof *ny);
        if (!ny) return false;
        s->y = ny;
        s->cap = cap;
    }
    s->x[s->n] = x;
    s->y[s->n] = y;
    s->n++;
    return true;
}

void val_series_free(val_series *s)
{
    free(s->x);
    free(s->y);
    memset(s, 0, sizeof *s);
}

double val_series_at(const val_series *s, double x)
{
    if (s->n == 0 || x < s->x[0] || x > s->x[s->n - 1]) return NAN;
    for (size_t i = 1; i < s->n; i++)
        if (x <= s->x[i]) {
            double d = s->x[i] - s->x[i - 1], f = d > 0 ? (x - s->x[i - 1]) / d : 1.0;
            return s->y[i - 1] + f * (s->y[i] - s->y[i - 1]);
        }
    return s->y[s->n - 1];
}
