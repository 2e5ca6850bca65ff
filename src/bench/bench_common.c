/* What the bench's parts share, below the command: the progress line and
 * the trace, the options' defaults, the level table, small formatting. The
 * command (cmd_bench.c), the ladder, its report and the scaling stand on it. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cmd.h"
#include "../io/io_json.h"

static const bench_opts *g_opts;

void bench_progress_opts(const bench_opts *o)
{
    g_opts = o;
}

void bench_progress(const char *fmt, ...)
{
    if (!g_opts || !g_opts->progress) return;
    char line[160];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(line, sizeof line, fmt, ap);
    va_end(ap);
    fprintf(stderr, "\r  %-76.76s", line);
    fflush(stderr);
}

void bench_progress_done(void)
{
    if (g_opts && g_opts->progress) fprintf(stderr, "\r%80s\r", "");
}

void bench_trace(const bench_level *L, const bench_meas *m, const char *what)
{
    if (!g_opts || !g_opts->trace) return;
    bench_progress_done();
    fprintf(stderr, "trace %s %-6s N %8u  %8.2f steps/s  %8.3f ms/step  repeats %d  attempts %d  others %.2f\n", L->name,
            what, m->n, m->steps_per_s, m->ms_step, m->repeats, m->attempts, m->others);
}

const char *bench_dim_tag(int dim) { return dim == 2 ? "2d" : "3d"; }

double bench_round_fixed(double v, int decimals)
{
    if (!isfinite(v)) return v;
    char s[400];
    snprintf(s, sizeof s, "%.*f", decimals, v);
    return strtod(s, NULL);
}

bool bench_json_add_load(cJSON *obj, const char *key, const double l[3])
{
    double r[3];
    for (int i = 0; i < 3; i++) r[i] = bench_round_fixed(l[i], 2);
    cJSON *a = cJSON_CreateDoubleArray(r, 3);
    if (a && cJSON_AddItemToObject(obj, key, a)) return true;
    cJSON_Delete(a);
    return false;
}

void bench_opts_init(bench_opts *o, bool quick)
{
    memset(o, 0, sizeof *o);
    o->fps = 60;
    o->cfg.dim = 3;
    o->quick = quick;
    o->out = ".";
    o->at = quick ? 6000 : 20000;
    o->time = -1;
    o->repeats = -1;
    for (int i = 0; i < bench_level_count && i < BENCH_MAX_LEVELS; i++) o->sel[o->nsel++] = i;
}

void bench_levels_print(FILE *f, const bench_opts *o)
{
    fprintf(f, "%-5s %-42s %-8s %s\n", "level", "description", "threads", "scene keys");
    for (int s = 0; s < o->nsel; s++) {
        const bench_level *L = &bench_levels[o->sel[s]];
        char t[16];
        snprintf(t, sizeof t, "%d", L->threads);
        fprintf(f, "%-5s %-42s %-8s %s\n", L->name, L->about, bench_level_gl(L) ? "device" : L->threads > 0 ? t : "cores",
                L->sets);
    }
}
