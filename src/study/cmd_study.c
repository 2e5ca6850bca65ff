/* sphlab study SCENE --vary KEY=V1,V2,... --out DIR: what each accuracy
 * choice buys and what it costs. Runs every combination of the knobs on one
 * of the reference problems, measures its error (docs/accuracy.md) and its
 * wall time (median of repeats), and writes DIR/study.csv, a log-log chart
 * of error against time with the Pareto front (DIR/study.png, .pdf) and a
 * table on stdout. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "app.h"
#include "plot.h"
#include "../io/io.h"
#include "study_cmd.h"
#include "study_plot.h"
#include "sph_names.h"

static const app_cmd_spec spec = {
    .name = "study",
    .cmd = APP_CMD(study),
    .synopsis = "usage: sphlab study SCENE.ini --vary KEY=V1,V2,... [--vary ...] --out DIR [options]\n"
                "Runs every combination of the --vary lists on a reference problem, measures its error and its\n"
                "wall time, and writes DIR/study.csv, DIR/study.png and DIR/study.pdf (error against time, log-log,\n"
                "Pareto front marked) and a table. docs/accuracy.md defines each error.\n",
    .footer = "exit status: 0 done; 1 bad scene (a combination the scene refuses too) or output directory; 2 bad\n"
              "command line (a bad --set, or a --vary key or value, too); 4 every combination was stopped by the\n"
              "watchdog\n",
    .max_pos = 1,
    .extra_pos = "more than one scene file",
};

/* mkdir -p DIR and check that a file can be made in it (sph_output_dir),
 * before any run: a bad --out fails at once, not after the study. */
static bool prepare_dir(const char *dir)
{
    char err[1200];
    if (sph_output_dir(dir, err, sizeof err)) return true;
    fprintf(stderr, "sphlab study: --out: %s\n", err);
    return false;
}

typedef struct progress_ctx {
    bool on;
    long combo, combos;
    int repeat, repeats;
    char what[120];
    double t0;
} progress_ctx;

static void show_progress(void *vctx, const sph_sim *sim, double done)
{
    progress_ctx *c = vctx;
    if (!c->on) return;
    (void)sim;
    fprintf(stderr, "\r  [%ld/%ld] %-46.46s run %d/%d %3.0f%%  %4.0f s elapsed ", c->combo + 1, c->combos, c->what,
            c->repeat + 1, c->repeats, 100 * fmin(done, 1.0), (sph_now_ms() - c->t0) / 1e3);
}

static void combo_text(const study_plan *p, const int *idx, char *out, size_t n, const char *sep)
{
    size_t len = 0;
    out[0] = '\0';
    for (int k = 0; k < p->n_knobs && len < n; k++)
        len += (size_t)snprintf(out + len, n - len, "%s%s=%s", k ? sep : "", p->knob[k].key, p->knob[k].value[idx[k]]);
    if (p->n_knobs == 0) snprintf(out, n, "(the scene as it is)");
}

/* Whether knob k sets kernels.h (alone, linked by '+', or as h_over_spacing): then h / spacing is the user's. */
static bool knob_sets_h(const study_knob *kn)
{
    if (strcmp(kn->key, "h_over_spacing") == 0) return true;
    const char *part = kn->key;
    for (;;) {
        const size_t len = strcspn(part, "+");
        if (len == strlen("kernels.h") && strncmp(part, "kernels.h", len) == 0) return true;
        if (!part[len]) return false;
        part += len + 1;
    }
}

/* A study over the spacing at a fixed kernels.h changes h / spacing too, so its errors mix a finer lattice
 * with a kernel that spans more spacings (2 to 4 for spacing 0.02 to 0.01 at h = 0.04 m): a student read the
 * falling error as convergence with resolution. Said, with the two ways to keep the ratio. */
static bool ratio_varies(const study_plan *plan, double lo, double hi)
{
    if (!(hi > lo * (1 + 1e-6))) return false;
    for (int k = 0; k < plan->n_knobs; k++)
        if (knob_sets_h(&plan->knob[k])) return false;
    return true;
}

static void note_ratio(const study_plan *plan, const sph_scene_def *scene, double lo, double hi)
{
    if (!ratio_varies(plan, lo, hi)) return;
    const study_knob *sk = NULL; /* the knob that moves the spacing, for the example */
    for (int k = 0; k < plan->n_knobs && !sk; k++) {
        const char *dot = strrchr(plan->knob[k].key, '.');
        if (dot && strcmp(dot, ".spacing") == 0 && !strchr(plan->knob[k].key, '+')) sk = &plan->knob[k];
    }
    const double s0 = sph_scene_finest_spacing(scene), ratio = s0 > 0 ? scene->h / s0 : NAN;
    fprintf(stderr,
            "sphlab study: warning: h / spacing runs from %.3g to %.3g over the combinations: kernels.h stays %g m "
            "while the spacing changes, so each error mixes a finer lattice with a kernel spanning more spacings; to "
            "refine at one ratio, add --vary h_over_spacing=%.3g",
            lo, hi, (double)scene->h, ratio);
    if (sk && isfinite(ratio)) {
        fprintf(stderr, " or link the keys: --vary '%s+kernels.h=", sk->key);
        for (int v = 0; v < sk->n && v < 3; v++)
            fprintf(stderr, "%s%s+%.6g", v ? "," : "", sk->value[v], ratio * atof(sk->value[v]));
        fprintf(stderr, "%s'", sk->n > 3 ? ",..." : "");
    }
    fprintf(stderr, "\n");
}

/* The knobs' keys for the chart's legend, each part without its section where no other part has its name
 * ("pressure_solver+stiffness+solver_tolerance"): the full keys of lesson 11's study made a line the legend
 * shrank to 6 pixels. A name two sections of the scene format share ([physics] and [kernels] viscosity) keeps
 * its section. */
static void knob_names_short(const study_plan *plan, char *out, size_t n)
{
    const char *part[STUDY_MAX_KNOBS * 8];
    size_t plen[STUDY_MAX_KNOBS * 8];
    int np = 0, first[STUDY_MAX_KNOBS + 1];
    for (int k = 0; k < plan->n_knobs; k++) {
        first[k] = np;
        for (const char *p = plan->knob[k].key; np < STUDY_MAX_KNOBS * 8;) {
            const size_t len = strcspn(p, "+");
            part[np] = p;
            plen[np++] = len;
            if (!p[len]) break;
            p += len + 1;
        }
    }
    first[plan->n_knobs] = np;
    size_t used = 0;
    out[0] = '\0';
    for (int k = 0; k < plan->n_knobs && used < n; k++)
        for (int i = first[k]; i < first[k + 1] && used < n; i++) {
            const char *dot = memchr(part[i], '.', plen[i]);
            const char *name = dot ? dot + 1 : part[i];
            size_t nlen = plen[i] - (size_t)(name - part[i]);
            bool unique = true;
            for (int j = 0; j < np && unique; j++) {
                const char *dj = memchr(part[j], '.', plen[j]);
                const char *nj = dj ? dj + 1 : part[j];
                const size_t lj = plen[j] - (size_t)(nj - part[j]);
                unique = j == i || lj != nlen || strncmp(nj, name, nlen) != 0;
            }
            for (int q = 0, sections = 0; q < sph_scene_key_count && unique; q++) /* [physics] / [kernels] viscosity */
                if (strlen(sph_scene_keys[q].name) == nlen && strncmp(sph_scene_keys[q].name, name, nlen) == 0)
                    unique = ++sections < 2;
            if (!unique) name = part[i], nlen = plen[i];
            used += (size_t)snprintf(out + used, n - used, "%s%.*s",
                                     i == first[k] ? (k ? ", " : "") : "+", (int)nlen, name);
        }
}

static const char *error_label(study_metric m)
{
    switch (m) {
    case STUDY_METRIC_DENSITY: return "interior density error, RMS of #gr/#gr#d0#u - 1 [-]";
    case STUDY_METRIC_DENSITY_SURFACE: return "free-surface density error, RMS [-]";
    case STUDY_METRIC_HYDROSTATIC: return "pressure profile error, RMS / #gr#d0#u g H [-]";
    case STUDY_METRIC_COMPRESSION: return "each step's largest #gr/#gr#dheld#u - 1, time mean [-]";
    default: return "decay rate error |#gl/#gl#dexact#u - 1| [-]";
    }
}

/* ratio: the table has an h/s column, where h / spacing differs between the rows and no knob sets h (then
 * the knobs' own columns do not show what each error was measured at; see note_ratio). */
static void print_table(FILE *f, const study_plan *p, const study_row *rows, int n, bool ratio)
{
    int w[STUDY_MAX_KNOBS];
    fprintf(f, "%4s", "#");
    for (int k = 0; k < p->n_knobs; k++) {
        w[k] = (int)strlen(p->knob[k].key);
        for (int v = 0; v < p->knob[k].n; v++)
            if ((int)strlen(p->knob[k].value[v]) > w[k]) w[k] = (int)strlen(p->knob[k].value[v]);
        fprintf(f, "  %-*s", w[k], p->knob[k].key);
    }
    if (ratio) fprintf(f, "  %5s", "h/s");
    fprintf(f, "  %9s %8s %11s %10s %9s  %s\n", "particles", "steps", "error", "ms/step", "run s", "front");
    for (int i = 0; i < n; i++) {
        const study_row *r = &rows[i];
        fprintf(f, "%4d", i + 1);
        for (int k = 0; k < p->n_knobs; k++) fprintf(f, "  %-*s", w[k], p->knob[k].value[r->idx[k]]);
        if (ratio) fprintf(f, "  %5.3g", r->h_over_s);
        char err[32];
        if (r->r.stopped)
            snprintf(err, sizeof err, "stopped");
        else
            snprintf(err, sizeof err, "%.4g", r->r.error);
        fprintf(f, "  %9u %8llu %11s %10.4g %9.4g  %s\n", r->r.particles, (unsigned long long)r->r.steps, err,
               r->ms_per_step, r->total_s, r->front ? "*" : "");
    }
}

int cmd_study(int argc, char **argv)
{
    plot_out_command("study"); /* the charts' and tables' messages name this command */
    study_plan plan;
    memset(&plan, 0, sizeof plan);
    char why[1024];
    app_opts opt;
    app_opts_init(&opt);
    opt.repeats = 3;
    int rc = app_opts_parse(&spec, argc, argv, &opt);
    if (rc >= 0) return rc;
    const char *out = opt.out, *metric_name = opt.metric, *base = opt.name ? opt.name : "study";
    long repeats = opt.repeats, steps = opt.steps, threads = opt.threads;
    double until = opt.time;
    bool quiet = opt.quiet;
    for (int i = 0; i < opt.vary.n; i++)
        if (!study_plan_add(&plan, opt.vary.v[i], why, sizeof why)) {
            fprintf(stderr, "sphlab study: %s\n", why);
            return 2;
        }
    if (until >= 0 && !(until > 0)) {
        fprintf(stderr, "sphlab study: --time %g: must be above 0 s\n", until);
        return 2;
    }
    app_scene_opts o;
    if (!app_scene_from_opts(&o, &opt)) return 2;
    study_cmd c = {o, plan, out, metric_name, base, repeats, steps, threads, until, quiet, quiet ? NULL : stdout};
    return study_cmd_run(&c);
}

int study_cmd_run(const study_cmd *cmd)
{
    const app_scene_opts o = cmd->scene;
    const study_plan plan = cmd->plan;
    const char *out = cmd->out, *metric_name = cmd->metric, *base = cmd->base;
    const long repeats = cmd->repeats, threads = cmd->threads;
    long steps = cmd->steps;
    double until = cmd->until;
    const bool quiet = cmd->quiet;
    FILE *table = cmd->table;
    char why[1024];
    if (!o.path) {
        app_opts_usage_error(&spec, "no scene file");
        return 2;
    }
    if (!out) {
        fprintf(stderr, "sphlab study: no --out DIR: say where to write study.csv and the chart\n");
        return 2;
    }
    if (steps >= 0 && until >= 0) {
        fprintf(stderr, "sphlab study: give --steps or --time, not both\n");
        return 2;
    }
    int metric = -1;
    if (metric_name && (metric = study_metric_find(metric_name)) < 0) {
        fprintf(stderr, "sphlab study: --metric '%s': unknown (accepted:", metric_name);
        for (int m = 0; m < STUDY_METRIC_COUNT; m++) fprintf(stderr, "%s %s", m ? "," : "", study_metric_names[m]);
        fprintf(stderr, ")");
        for (int m = 0; m < STUDY_METRIC_COUNT; m++)
            if (sph_name_near(metric_name, study_metric_names[m])) {
                fprintf(stderr, " (did you mean %s?)", study_metric_names[m]);
                break;
            }
        fprintf(stderr, "\n");
        return 2;
    }
    long combos = study_plan_count(&plan);
    if (combos > STUDY_MAX_COMBOS) {
        fprintf(stderr, "sphlab study: more than %d combinations: shorten the --vary lists\n", STUDY_MAX_COMBOS);
        return 2;
    }

    sph_scene_def scene;
    const int loaded = app_load_scene_status(&o, &scene); /* 2: a bad --set */
    if (loaded) return loaded;
    if (metric < 0 && (metric = study_metric_guess(&scene)) < 0) {
        /* the list from the metric table, so that a metric added there (compression) is named here too */
        fprintf(stderr,
                "sphlab study: %s is none of the reference problems this command guesses (a Taylor-Green block, "
                "a tank, a block whose density is computed): give --metric ",
                o.path);
        for (int m = 0; m < STUDY_METRIC_COUNT; m++) fprintf(stderr, "%s%s", m ? "|" : "", study_metric_names[m]);
        fprintf(stderr, " (compression: any flow with pressure, as a dam break)\n");
        return 1;
    }
    /* every combination must be a valid scene the metric applies to, before anything runs */
    double ratio_lo = INFINITY, ratio_hi = 0; /* h / spacing over the combinations */
    for (long c = 0; c < combos; c++) {
        sph_scene_def def = scene;
        bool usage = false;
        if (!study_plan_apply_why(&plan, c, &def, why, sizeof why, &usage) ||
            !study_metric_check((study_metric)metric, &def, why, sizeof why)) {
            fprintf(stderr, "sphlab study: %s\n", why);
            return usage ? 2 : 1; /* a misspelt --vary key is a bad command line, as a misspelt --set */
        }
        const double s = sph_scene_finest_spacing(&def);
        if (s > 0) {
            ratio_lo = fmin(ratio_lo, def.h / s);
            ratio_hi = fmax(ratio_hi, def.h / s);
        }
    }
    note_ratio(&plan, &scene, ratio_lo, ratio_hi);
    if (!prepare_dir(out)) return 1;

    study_row *rows = calloc((size_t)combos, sizeof *rows);
    double *walls = calloc((size_t)repeats, sizeof *walls);
    if (!rows || !walls) {
        fprintf(stderr, "sphlab study: out of memory\n");
        free(rows);
        free(walls);
        return 1;
    }
    progress_ctx pc = {!quiet && isatty(STDERR_FILENO), 0, combos, 0, (int)repeats, "", sph_now_ms()};
    int code = 0, stopped = 0;
    for (long c = 0; c < combos && code == 0; c++) {
        sph_scene_def def = scene;
        study_plan_apply(&plan, c, &def, why, sizeof why); /* checked above */
        study_row *row = &rows[c];
        study_plan_combo(&plan, c, row->idx);
        row->h_over_s = sph_scene_finest_spacing(&def) > 0 ? def.h / sph_scene_finest_spacing(&def) : NAN;
        combo_text(&plan, row->idx, pc.what, sizeof pc.what, " ");
        long n_steps = steps;
        double t_end = until;
        if (n_steps < 0 && t_end < 0) {
            if (def.duration > 0)
                t_end = def.duration;
            else
                n_steps = def.steps;
        }
        pc.combo = c;
        for (int r = 0; r < repeats; r++) {
            pc.repeat = r;
            study_result res;
            show_progress(&pc, NULL, 0);
            if (!study_run(&def, (study_metric)metric, n_steps, t_end, (int)threads, show_progress, &pc, &res, why,
                           sizeof why)) {
                fprintf(stderr, "%ssphlab study: combination %ld (%s): %s\n", pc.on ? "\r" : "", c + 1, pc.what, why);
                code = 1;
                break;
            }
            walls[r] = res.wall_ms;
            if (r == 0) row->r = res;
            if (res.stopped) break; /* the same run would stop again */
        }
        if (code) break;
        double med = study_median(walls, row->r.stopped ? 1 : (int)repeats);
        row->r.wall_ms = med;
        study_result_timed((study_metric)metric, &row->r);
        row->total_s = med / 1e3;
        row->ms_per_step = row->r.steps ? med / (double)row->r.steps : NAN;
        if (row->r.stopped) {
            stopped++;
            fprintf(stderr, "%ssphlab study: warning: combination %ld (%s): %s\n", pc.on ? "\r" : "", c + 1, pc.what,
                    row->r.note);
        } else if (row->r.note[0]) {
            fprintf(stderr, "%ssphlab study: warning: combination %ld (%s): %s\n", pc.on ? "\r" : "", c + 1, pc.what,
                    row->r.note);
        }
    }
    if (pc.on) fprintf(stderr, "\r%100s\r", "");
    for (int k = 0; k < plan.n_knobs && !code; k++)
        if (study_knob_inert(&plan, rows, combos, k))
            fprintf(stderr,
                    "sphlab study: warning: --vary %s: every value gave the same particles, steps and error: the key "
                    "changes nothing on this scene (its effects or pressure_solver leave out the passes that read "
                    "it; or another key bounds what it sets, as [time] dt caps the step that time.cfl would give; "
                    "or, for a tolerance, every value is already met at the solve's first iteration: try smaller "
                    "ones; --stats shows the error each solve ends with)\n",
                    plan.knob[k].key);
    if (code) {
        free(rows);
        free(walls);
        return code;
    }

    /* the Pareto front of (time, error) */
    double *tx = malloc((size_t)combos * sizeof *tx), *ey = malloc((size_t)combos * sizeof *ey);
    bool *front = malloc((size_t)combos * sizeof *front);
    int *num = malloc((size_t)combos * sizeof *num);
    double *fx = malloc((size_t)combos * sizeof *fx), *fy = malloc((size_t)combos * sizeof *fy);
    int *fnum = malloc((size_t)combos * sizeof *fnum);
    if (!tx || !ey || !front || !num || !fx || !fy || !fnum) {
        fprintf(stderr, "sphlab study: out of memory\n");
        code = 1;
        goto out;
    }
    for (long c = 0; c < combos; c++) {
        tx[c] = rows[c].total_s;
        ey[c] = rows[c].r.error;
        num[c] = (int)c + 1;
    }
    int nf = study_pareto(tx, ey, (int)combos, front);
    for (long c = 0; c < combos; c++) rows[c].front = front[c];
    /* front points by time, for the line */
    int m = 0;
    for (long c = 0; c < combos; c++)
        if (front[c]) {
            int j = m++;
            while (j > 0 && fx[j - 1] > tx[c]) {
                fx[j] = fx[j - 1], fy[j] = fy[j - 1], fnum[j] = fnum[j - 1];
                j--;
            }
            fx[j] = tx[c], fy[j] = ey[c], fnum[j] = (int)c + 1;
        }

    char csv_name[256];
    snprintf(csv_name, sizeof csv_name, "%s.csv", base);
    FILE *f = plot_out_stage_csv(out, csv_name);
    if (!f) {
        code = 1;
        goto out;
    }
    bool ok = study_write_csv(f, &plan, (study_metric)metric, rows, (int)combos);
    if (!plot_out_close_csv(f, out, csv_name) || !ok) {
        plot_out_abort();
        code = 1;
        goto out;
    }

    study_chart ch;
    memset(&ch, 0, sizeof ch);
    char scene_name[200];
    plot_escape(scene_name, sizeof scene_name, scene.name[0] ? scene.name : o.path);
    snprintf(ch.title, sizeof ch.title, "Error against time: %.100s (%s)", scene_name, study_metric_names[metric]);
    /* the run length, if all combinations share it */
    char len_text[64] = "runs of different lengths";
    bool same_steps = true, same_time = true;
    for (long c = 1; c < combos; c++) {
        same_steps &= rows[c].r.steps == rows[0].r.steps;
        same_time &= fabs(rows[c].r.t_end - rows[0].r.t_end) <= 0.01 * rows[0].r.t_end;
    }
    if (until < 0 && !same_time) { /* --steps at time steps that differ: unequal work on one time axis */
        double lo = INFINITY, hi = -INFINITY;
        for (long c = 0; c < combos; c++) {
            if (rows[c].r.stopped) continue; /* a watchdog stop ends early, and is said as such */
            lo = fmin(lo, rows[c].r.t_end);
            hi = fmax(hi, rows[c].r.t_end);
        }
        if (isfinite(lo) && hi > lo * 1.01)
            fprintf(stderr,
                    "sphlab study: warning: the runs simulated from %.3g to %.3g s (%s at their own time steps), so "
                    "their wall times are for unequal work and the front compares them as equal; give --time T "
                    "to compare the same simulated time\n",
                    lo, hi, steps >= 0 ? "--steps" : "the scene's steps");
    }
    if (until >= 0 || (steps < 0 && !same_steps && same_time))
        snprintf(len_text, sizeof len_text, "%.3g s simulated", rows[0].r.t_end);
    else if (same_steps)
        snprintf(len_text, sizeof len_text, "%llu step%s", (unsigned long long)rows[0].r.steps,
                 rows[0].r.steps == 1 ? "" : "s");
    snprintf(ch.subtitle, sizeof ch.subtitle, "%ld combination%s, %.40s, time: median of %ld run%s; numbers: rows of %.40s",
             combos, combos == 1 ? "" : "s", len_text, repeats, repeats == 1 ? "" : "s", csv_name);
    snprintf(ch.xlabel, sizeof ch.xlabel, "wall time of a run [s]");
    snprintf(ch.ylabel, sizeof ch.ylabel, "%s", error_label((study_metric)metric));
    study_curve *all = &ch.c[ch.nc++];
    snprintf(all->label, sizeof all->label, "combination");
    all->x = tx, all->y = ey, all->n = (int)combos, all->style = 1, all->markers = true, all->numbers = num;
    if (nf > 0) {
        study_curve *pf = &ch.c[ch.nc++];
        snprintf(pf->label, sizeof pf->label, "Pareto front");
        pf->x = fx, pf->y = fy, pf->n = m, pf->style = 2, pf->line = true, pf->solid = true, pf->markers = true, pf->filled = true;
    }
    snprintf(ch.note[ch.nn++], sizeof ch.note[0], "On the front (no other run is both");
    snprintf(ch.note[ch.nn++], sizeof ch.note[0], "faster and more accurate):");
    if (plan.n_knobs > 0) {
        char keys[400], esc[400];
        knob_names_short(&plan, keys, sizeof keys);
        /* lines of at most about 30 characters, broken after a '+' or ", ", as the notes below fit the legend at
         * its own size (a longer line is drawn smaller) */
        const char *k = keys;
        for (bool lead = true; *k && ch.nn < STUDY_MAX_NOTES - 2; lead = false) {
            size_t take = strlen(k);
            if (take > 30) {
                size_t cut = 0;
                for (size_t i = 1; i <= 30 && k[i]; i++)
                    if (k[i - 1] == '+' || (k[i - 1] == ' ' && i >= 2 && k[i - 2] == ',')) cut = i;
                take = cut ? cut : 30;
            }
            char line[64];
            snprintf(line, sizeof line, "%.*s", (int)take, k);
            plot_escape(esc, sizeof esc, line);
            snprintf(ch.note[ch.nn++], sizeof ch.note[0], "%s%.110s", lead ? "#: " : "    ", esc);
            k += take;
        }
    }
    for (int j = 0; j < m && ch.nn < STUDY_MAX_NOTES; j++) {
        int idx[STUDY_MAX_KNOBS];
        study_plan_combo(&plan, fnum[j] - 1, idx);
        char text[400] = "", esc[400];
        size_t len = 0;
        for (int k = 0; k < plan.n_knobs && len < sizeof text; k++)
            len += (size_t)snprintf(text + len, sizeof text - len, "%s%s", k ? ", " : "", plan.knob[k].value[idx[k]]);
        plot_escape(esc, sizeof esc, text);
        if (ch.nn == STUDY_MAX_NOTES - 1 && j < m - 1)
            snprintf(ch.note[ch.nn++], sizeof ch.note[0], "... and %d more (see %.60s)", m - j, csv_name);
        else
            snprintf(ch.note[ch.nn++], sizeof ch.note[0], "%d: %.100s", fnum[j], esc);
    }
    if (nf == 0) snprintf(ch.note[ch.nn++], sizeof ch.note[0], "(none: no run has a finite error)");
    if (!study_chart_loglog(&ch, out, base, 1000, 700) || !plot_out_commit(quiet)) {
        plot_out_abort();
        code = 1;
        goto out;
    }
    if (table) {
        fprintf(table, "study of %s: %ld combination%s x %ld run%s, metric %s:\n  %s\n", o.path, combos,
                combos == 1 ? "" : "s", repeats, repeats == 1 ? "" : "s", study_metric_names[metric],
                study_metric_about[metric]);
        print_table(table, &plan, rows, (int)combos, ratio_varies(&plan, ratio_lo, ratio_hi));
        if (nf > 0)
            fprintf(table, "front: the %d run%s no other run beats in both error and time (*)\n", nf,
                    nf == 1 ? "" : "s");
        else
            fprintf(table, "front: none (no run has a finite error)\n");
        if (stopped)
            fprintf(table, "%d combination%s stopped by the watchdog (error nan)\n", stopped, stopped == 1 ? "" : "s");
    }
    /* nothing measured: said by the exit status too, as `run` says a watchdog stop */
    if (code == 0 && stopped == combos) {
        fprintf(stderr, "sphlab study: every combination was stopped by the watchdog: no error to compare (%s "
                "and the chart say where)\n", csv_name);
        code = 4;
    }
out:
    free(tx);
    free(ey);
    free(front);
    free(num);
    free(fx);
    free(fy);
    free(fnum);
    free(rows);
    free(walls);
    return code;
}
