/* Lessons 10 and 11: boundary handling (the three wall models on a block at
 * rest, a hydrostatic tank and a dam break) and how incompressible a flow
 * is, at what cost (the equation of state against the iterated pressure
 * solvers, through the study module, study_cmd_run). The simulations run in
 * process with the core's functions; every number comes from the sim or a
 * CSV written here. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "lesson_steps.h"
#include "sph_walls.h"
#include "study_cmd.h"

/* The wall models in the order the lesson shows them. */
static const char *const models[3] = {"reflect", "volume", "particles"};
enum { NMODEL = 3 };

/* ---- a run in process ------------------------------------------------------------------------ */

/* A run of a scene to t_end with a callback after each step; the equivalent
 * command line goes to the log. False (a failure, in the report) if the
 * scene cannot be made; *stopped says whether the watchdog stopped it (not a
 * failure: the lesson reports it). */
typedef void (*walls_step_fn)(void *ctx, const sph_sim *sim);

static bool run_to(lx *x, const char *log, const char *scene, const char *const *sets, double t_end,
                   walls_step_fn fn, void *ctx, bool *stopped, char *note, size_t nn, sph_sim **keep)
{
    const char *argv[24] = {"sphlab", "run", scene};
    int na = 3;
    for (int i = 0; sets && sets[i] && na < 18; i++) {
        argv[na++] = "--set";
        argv[na++] = sets[i];
    }
    argv[na++] = "--time";
    argv[na++] = lx_fmt("%g", t_end);
    argv[na++] = "--threads";
    argv[na++] = "1";
    argv[na] = NULL;
    const char *lpath;
    FILE *lf = lx_log_open(x, log, argv, &lpath);
    sph_scene_def def;
    sph_error err;
    sph_sim *sim = NULL;
    *stopped = false;
    note[0] = '\0';
    bool ok = lx_load_def(x, scene, &def);
    for (int i = 0; ok && sets && sets[i]; i++)
        if (sph_scene_set(&def, sets[i], &err) != SPH_ERR_OK || sph_scene_validate(&def, &err) != SPH_ERR_OK) {
            ok = false;
            lx_md(x, "\n**%s:** %s\n\n", sets[i], err.msg);
            x->failed++;
        }
    if (ok && sph_sim_create(&def, 1, &sim, &err) != SPH_ERR_OK) {
        ok = false;
        lx_md(x, "\n**The scene cannot run:** %s\n\n", err.msg);
        x->failed++;
    }
    if (ok) sph_sim_end_at(sim, t_end); /* as the `sphlab run --time` it logs: the last step ends on it */
    double t0 = sph_now_ms();
    while (ok && !sph_sim_reached(sim, t_end)) {
        sph_sim_step(sim);
        if (sim->alarm.raised) {
            *stopped = true;
            char report[2048];
            sph_sim_alarm_report(sim, report, sizeof report);
            char *nl = strchr(report, '\n');
            if (nl) *nl = '\0';
            snprintf(note, nn, "%.400s", report);
            break;
        }
        if (fn) fn(ctx, sim);
    }
    if (lf) {
        if (ok)
            fprintf(lf, "%llu steps, t = %.4f s, %.3f s of wall time%s%s\n", (unsigned long long)sim->step, sim->t,
                    (sph_now_ms() - t0) / 1e3, *stopped ? "; stopped: " : "", note);
        fclose(lf);
    }
    if (keep && ok) *keep = sim;
    else if (sim) sph_sim_destroy(sim);
    return ok;
}

/* The fluid particles within `half` of the middle of the domain in x, by
 * height: their y and p into ys, ps (at most cap); returns their count. */
static int middle_strip(const sph_sim *sim, double half, double *ys, double *ps, int cap)
{
    const sph_particles *P = &sim->P;
    double xm = 0.5 * ((double)sim->def.domain_min[0] + sim->def.domain_max[0]);
    int n = 0;
    for (uint32_t i = 0; i < sim->n && n < cap; i++) {
        if (sph_is_wall(P, i) || fabs(P->pos[0][i] - xm) >= half) continue;
        int j = n++;
        while (j > 0 && ys[j - 1] > P->pos[1][i]) { /* insertion by height */
            ys[j] = ys[j - 1];
            ps[j] = ps[j - 1];
            j--;
        }
        ys[j] = P->pos[1][i];
        ps[j] = P->p[i];
    }
    return n;
}

/* ---- lesson 10: boundary handling ------------------------------------------------------------- */

typedef struct front_ctx {
    double t[4096], x[4096]; /* [s] sample times, [m] the front (the fluid's largest x) */
    int n;
    double every, next; /* [s] sampling interval, next sample */
} front_ctx;

static void front_step(void *vctx, const sph_sim *sim)
{
    front_ctx *c = vctx;
    /* the tolerance: a run now ends on t_end, which the summed `every`s may pass by a rounding */
    if (sim->t < c->next - 1e-9 * c->every || c->n >= 4096) return;
    double xmax = -INFINITY;
    for (uint32_t i = 0; i < sim->n; i++)
        if (!sph_is_wall(&sim->P, i)) xmax = fmax(xmax, sim->P.pos[0][i]);
    c->t[c->n] = sim->t;
    c->x[c->n++] = xmax;
    c->next += c->every;
}

/* 1. The wall row of a block at rest: the density of the first density pass. */
static void lesson10_rest(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return;
    const double s = def.blocks[0].spacing, rho0 = def.rest_density;
    const int cols = (int)sph_block_nodes(&def, 0, 0), rows = (int)sph_block_nodes(&def, 0, 1);
    static double prof_y[NMODEL][64], prof[NMODEL][64], flat[64]; /* [m], [kg/m^2], [kg/m^2] */
    /* [kg/m^2] the first pass's density at four places of the lattice, per model */
    double wall_row[NMODEL] = {NAN, NAN, NAN}, corner[NMODEL] = {NAN, NAN, NAN}, interior[NMODEL] = {NAN, NAN, NAN},
           free_top[NMODEL] = {NAN, NAN, NAN};
    int nrow = rows < 64 ? rows : 64;
    bool ok[NMODEL] = {false};
    for (int m = 0; m < NMODEL; m++) {
        const char *sets[] = {lx_fmt("domain.wall_model=%s", models[m]), NULL};
        bool stopped;
        char note[512];
        sph_sim *sim = NULL;
        /* one step: the density is the first pass's, computed before anything moves */
        if (!run_to(x, lx_fmt("rest-%s", models[m]), scene, sets, 0.5 * def.dt, NULL, NULL, &stopped, note,
                    sizeof note, &sim) ||
            !sim)
            continue;
        const sph_particles *P = &sim->P;
        for (uint32_t i = 0; i < sim->n; i++) {
            if (sph_is_wall(P, i)) continue;
            uint32_t id = P->id[i];
            int col = (int)(id % (uint32_t)cols), row = (int)(id / (uint32_t)cols);
            if (col == cols / 2 && row < nrow) {
                prof_y[m][row] = (row + 0.5) * s + def.blocks[0].min[1];
                prof[m][row] = P->rho[i];
            }
            if (col == 0 && row == 0) corner[m] = P->rho[i];
        }
        wall_row[m] = prof[m][0];
        interior[m] = prof[m][nrow / 2];
        free_top[m] = prof[m][nrow - 1];
        ok[m] = true;
        sph_sim_destroy(sim);
    }
    for (int r = 0; r < nrow; r++) flat[r] = rho0;
    lx_val(x, "rest_cols", "%d", cols);
    lx_val(x, "rest_rows", "%d", rows);
    lx_val(x, "rest_spacing", "%g", s);
    lx_val(x, "rest_h", "%g", def.h);
    lx_val(x, "rest_kernel", "%s", sph_kernel_names[def.kernel_density]);
    lx_block(x, "rest_table");
    lx_md(x, "| {{@wall model|modèle de paroi}} | {{@wall row (floor)|rangée de paroi (fond)}} | "
             "{{@interior|intérieur}} | "
             "{{@free top row|rangée libre du haut}} | {{@corner (floor and wall)|coin (fond et paroi)}} | "
             "{{@wall row / interior|rangée de paroi / intérieur}} |\n|---|---|---|---|---|---|\n");
    FILE *f = lx_csv_open(x, "wall-row-density.csv");
    if (f) fprintf(f, "wall_model,row,y,rho,rho_over_rho0\n");
    for (int m = 0; m < NMODEL; m++) {
        if (!ok[m]) {
            lx_md(x, "| %s | - | - | - | - | - |\n", models[m]);
            continue;
        }
        lx_md(x, "| %s | %.1f (%+.1f%%) | %.1f (%+.1f%%) | %.1f (%+.1f%%) | %.1f (%+.1f%%) | %.4f |\n", models[m],
              wall_row[m], 100 * (wall_row[m] / rho0 - 1), interior[m], 100 * (interior[m] / rho0 - 1), free_top[m],
              100 * (free_top[m] / rho0 - 1), corner[m], 100 * (corner[m] / rho0 - 1), wall_row[m] / interior[m]);
        lx_val(x, lx_fmt("rest_wall_%s", models[m]), "%.1f", wall_row[m]);
        lx_val(x, lx_fmt("rest_ratio_%s", models[m]), "%.3f", wall_row[m] / interior[m]);
        if (f)
            for (int r = 0; r < nrow; r++)
                fprintf(f, "%s,%d,%.4f,%.3f,%.5f\n", models[m], r, prof_y[m][r], prof[m][r], prof[m][r] / rho0);
    }
    lx_block_end(x);
    lx_val(x, "rest_interior", "%.1f", interior[1]);
    if (f) lx_csv_close(x, f, "wall-row-density.csv", 
                           "{{@the density up the middle column with each wall model|"
                           "la densité le long de la colonne du milieu avec chaque modèle de paroi}}");
    plot_lines L = {0};
    snprintf(L.title, sizeof L.title, "The wall row: density up the middle column, floor to free surface");
    snprintf(L.subtitle, sizeof L.subtitle, "a %d x %d lattice at rest, spacing %g m, h = %g m, %s; the first density "
                                            "pass",
             cols, rows, s, def.h, sph_kernel_names[def.kernel_density]);
    snprintf(L.xlabel, sizeof L.xlabel, "height y [m]");
    /* half a spacing beyond the first and last rows: the free top row's markers sat on the frame */
    L.xlo = INFINITY, L.xhi = -INFINITY;
    for (int m = 0; m < NMODEL; m++)
        for (int r = 0; ok[m] && r < nrow; r++) L.xlo = fmin(L.xlo, prof_y[m][r]), L.xhi = fmax(L.xhi, prof_y[m][r]);
    if (L.xlo < L.xhi) L.xlo -= 0.5 * s, L.xhi += 0.5 * s;
    else L.xlo = L.xhi = 0; /* from the data */
    L.np = 1;
    snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "density [kg/m#u2#d]");
    for (int m = 0; m < NMODEL; m++)
        if (ok[m]) {
            plot_series *ps = &L.p[0].s[L.p[0].n++];
            snprintf(ps->label, sizeof ps->label, "wall_model = %s", models[m]);
            ps->x = prof_y[m];
            ps->y = prof[m];
            ps->n = (size_t)nrow;
            ps->style = m;
        }
    if (L.p[0].n) {
        L.p[0].s[L.p[0].n++] = (plot_series){"rest density", prof_y[1], flat, (size_t)nrow, 6, false};
        lx_chart(x, PLOT_LINES, &L, "wall-row-density", 1000, 650,
                 "{{@the density up the middle column with each wall model: the wall row|la densité le long de la "
                 "colonne du milieu avec chaque modèle de paroi : la rangée contre la paroi}}");
    }
}

/* 2. A hydrostatic tank: the pressure up the middle against rho0 g (H - y). */
static void lesson10_tank(lx *x)
{
    const char *scene = lx_src(x, "tank.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return;
    const double s = def.blocks[0].spacing, rho0 = def.rest_density, g = -(double)def.gravity[1];
    const double width = (double)def.domain_max[0] - def.domain_min[0];
    const int rows = (int)sph_block_nodes(&def, 0, 1);
    const int nrow = rows < 64 ? rows : 64;
    const double t_end = x->quick ? 0.3 : def.duration;
    static double py[NMODEL][128], pp[NMODEL][128], exact[64], ey[64]; /* [m], [N/m], [N/m], [m]: a 2D pressure */
    int np[NMODEL] = {0};
    /* [1] shares of rho0 g H; the largest speed over sqrt(g H) */
    double wall_err[NMODEL] = {NAN, NAN, NAN}, col_err[NMODEL] = {NAN, NAN, NAN}, vmax[NMODEL] = {NAN, NAN, NAN};
    bool ok[NMODEL] = {false}, stop[NMODEL] = {false};
    char notes[NMODEL][512];
    double H = 0; /* [m] the depth the fluid's mass gives */
    for (int m = 0; m < NMODEL; m++) {
        const char *sets[] = {lx_fmt("domain.wall_model=%s", models[m]), NULL};
        sph_sim *sim = NULL;
        if (!run_to(x, lx_fmt("tank-%s", models[m]), scene, sets, t_end, NULL, NULL, &stop[m], notes[m],
                    sizeof notes[m], &sim) ||
            !sim)
            continue;
        if (stop[m]) {
            sph_sim_destroy(sim);
            continue;
        }
        long fluid = 0;
        double vm = 0;
        for (uint32_t i = 0; i < sim->n; i++) {
            if (sph_is_wall(&sim->P, i)) continue;
            fluid++;
            double v2 = (double)sim->P.vel[0][i] * sim->P.vel[0][i] + (double)sim->P.vel[1][i] * sim->P.vel[1][i];
            vm = fmax(vm, sqrt(v2));
        }
        /* the depth the fluid's mass gives at rho0 (2D: each particle holds s^2) */
        H = fluid * s * s / width;
        const double scale = rho0 * g * H;
        /* the two middle columns of the lattice, particle by particle, by height */
        np[m] = middle_strip(sim, s, py[m], pp[m], 128);
        double sum = 0;
        for (int k = 0; k < np[m]; k++) sum += fabs(pp[m][k] - rho0 * g * (H - py[m][k])) / scale;
        /* the wall row: the lowest particle of each of the two columns */
        if (np[m] >= 2)
            wall_err[m] = fabs(0.5 * (pp[m][0] + pp[m][1]) - rho0 * g * (H - 0.5 * (py[m][0] + py[m][1]))) / scale;
        col_err[m] = np[m] ? sum / np[m] : NAN;
        vmax[m] = vm / sqrt(g * H);
        ok[m] = np[m] >= 2;
        sph_sim_destroy(sim);
    }
    for (int r = 0; r < nrow; r++) {
        ey[r] = def.blocks[0].min[1] + (r + 0.5) * s;
        exact[r] = rho0 * g * (H - ey[r]);
    }
    lx_val(x, "tank_time", "%g", t_end);
    lx_val(x, "tank_depth", "%.3f", H);
    lx_val(x, "tank_width", "%g", width);
    lx_val(x, "tank_spacing", "%g", s);
    lx_val(x, "tank_scale", "%.0f", rho0 * g * H);
    lx_block(x, "tank_table");
    lx_md(x, "| {{@wall model|modèle de paroi}} | {{@wall row: \\|p - rho0 g (H - y)\\| / rho0 g H|rangée de paroi : "
             "\\|p - rho0 g (H - y)\\| / rho0 g H}} | "
             "{{@mean over the column|moyenne sur la colonne}} | {{@max speed / sqrt(g H)|vitesse max / sqrt(g H)}} "
             "|\n|---|---|---|---|\n");
    FILE *f = lx_csv_open(x, "hydrostatic-pressure.csv");
    if (f) fprintf(f, "wall_model,rank,y,p,p_exact\n");
    for (int m = 0; m < NMODEL; m++) {
        if (!ok[m]) {
            lx_md(x, "| %s | %s | - | - |\n", models[m],
                  stop[m] ? "{{@stopped by the watchdog|arrêté par le chien de garde}}" : "-");
            lx_val(x, lx_fmt("tank_wall_%s", models[m]), "%s", stop[m] ? "stopped" : "-");
            continue;
        }
        lx_md(x, "| %s | %.1f %% | %.1f %% | %.4f |\n", models[m], 100 * wall_err[m], 100 * col_err[m], vmax[m]);
        lx_val(x, lx_fmt("tank_wall_%s", models[m]), "%.1f %%", 100 * wall_err[m]);
        if (f)
            for (int k = 0; k < np[m]; k++)
                fprintf(f, "%s,%d,%.4f,%.2f,%.2f\n", models[m], k, py[m][k], pp[m][k], rho0 * g * (H - py[m][k]));
    }
    lx_block_end(x);
    lx_block(x, "tank_notes");
    for (int m = 0; m < NMODEL; m++)
        if (stop[m]) lx_md(x, "- `%s`: %s\n", models[m], notes[m]);
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "hydrostatic-pressure.csv", 
                           "{{@the pressure up the middle of the tank with each wall model|"
                           "la pression le long du milieu de la cuve avec chaque modèle de paroi}}");
    plot_lines L = {0};
    snprintf(L.title, sizeof L.title, "A tank at rest: pressure up the middle, against #gr#d0#u g (H - y)");
    snprintf(L.subtitle, sizeof L.subtitle, "water %.2f m deep, spacing %g m, t = %g s; every particle of the two "
                                            "middle columns",
             H, s, t_end);
    snprintf(L.xlabel, sizeof L.xlabel, "height y [m]");
    L.np = 1;
    snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "pressure [N/m] (2D)");
    for (int m = 0; m < NMODEL; m++)
        if (ok[m]) {
            plot_series *ps = &L.p[0].s[L.p[0].n++];
            snprintf(ps->label, sizeof ps->label, "wall_model = %s", models[m]);
            ps->x = py[m];
            ps->y = pp[m];
            ps->n = (size_t)np[m];
            ps->style = m;
        }
    if (L.p[0].n) {
        L.p[0].s[L.p[0].n++] = (plot_series){"#gr#d0#u g (H - y)", ey, exact, (size_t)nrow, 6, false};
        lx_chart(x, PLOT_LINES, &L, "hydrostatic-pressure", 1000, 650,
                 "{{@the pressure up the middle of a tank at rest with each wall model, against the exact profile|la "
                 "pression le long du milieu d'une cuve au repos avec chaque modèle de paroi, contre le profil "
                 "exact}}");
    }
}

/* 3. A dam break: where the front is with each wall model. */
static void lesson10_dam(lx *x)
{
    const char *scene = lx_src(x, "dam.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return;
    const double a = (double)def.blocks[0].max[0] - def.blocks[0].min[0], g = -(double)def.gravity[1];
    const double t_end = x->quick ? 0.1 : def.duration;
    static front_ctx fc[NMODEL];
    bool ok[NMODEL] = {false}, stop[NMODEL] = {false};
    char notes[NMODEL][512];
    for (int m = 0; m < NMODEL; m++) {
        const char *sets[] = {lx_fmt("domain.wall_model=%s", models[m]), NULL};
        memset(&fc[m], 0, sizeof fc[m]);
        fc[m].every = 0.005;
        if (!run_to(x, lx_fmt("dam-%s", models[m]), scene, sets, t_end, front_step, &fc[m], &stop[m], notes[m],
                    sizeof notes[m], NULL))
            continue;
        ok[m] = fc[m].n > 1;
    }
    /* the front at a few times, in units of the column's width */
    static const double when[] = {0.1, 0.2, 0.3};
    const int nw = x->quick ? 1 : 3;
    lx_val(x, "dam_width", "%g", a);
    lx_val(x, "dam_height", "%g", (double)def.blocks[0].max[1] - def.blocks[0].min[1]);
    lx_val(x, "dam_time", "%g", t_end);
    lx_block(x, "dam_table");
    lx_md(x, "| {{@wall model|modèle de paroi}} |");
    for (int k = 0; k < nw; k++) lx_md(x, " {{@front at|front à}} t = %g s |", when[k]);
    lx_md(x, "\n|---|");
    for (int k = 0; k < nw; k++) lx_md(x, "---|");
    lx_md(x, "\n");
    FILE *f = lx_csv_open(x, "dam-front.csv");
    if (f) fprintf(f, "wall_model,t,front_x,front_over_a,T\n");
    for (int m = 0; m < NMODEL; m++) {
        lx_md(x, "| %s |", models[m]);
        for (int k = 0; k < nw; k++) {
            double v = NAN; /* the front at when[k], interpolated between the samples around it */
            for (int i = 0; i + 1 < fc[m].n && !isfinite(v); i++)
                if (fc[m].t[i] <= when[k] && when[k] <= fc[m].t[i + 1]) {
                    const double u = (when[k] - fc[m].t[i]) / fmax(fc[m].t[i + 1] - fc[m].t[i], 1e-300);
                    v = fc[m].x[i] + u * (fc[m].x[i + 1] - fc[m].x[i]);
                }
            lx_md(x, " %s |", ok[m] && isfinite(v) ? lx_fmt("%.3f m (%.2f a)", v, v / a) : "-");
        }
        lx_md(x, "%s\n", stop[m] ? " (stopped by the watchdog)" : "");
        if (f)
            for (int i = 0; i < fc[m].n; i++)
                fprintf(f, "%s,%.4f,%.5f,%.5f,%.5f\n", models[m], fc[m].t[i], fc[m].x[i], fc[m].x[i] / a,
                        fc[m].t[i] * sqrt(2 * g / a));
    }
    lx_block_end(x);
    if (f) lx_csv_close(x, f, "dam-front.csv", 
                           "{{@the front of the dam break over time with each wall model|"
                           "le front de la rupture de barrage au cours du temps avec chaque modèle de paroi}}");
    plot_lines L = {0};
    snprintf(L.title, sizeof L.title, "Dam break: the front with each wall model");
    snprintf(L.subtitle, sizeof L.subtitle, "a column %g m wide; the front is the fluid's largest x", a);
    snprintf(L.xlabel, sizeof L.xlabel, "time [s]");
    L.np = 1;
    snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "front position [m]");
    for (int m = 0; m < NMODEL; m++)
        if (ok[m]) {
            plot_series *ps = &L.p[0].s[L.p[0].n++];
            snprintf(ps->label, sizeof ps->label, "wall_model = %s", models[m]);
            ps->x = fc[m].t;
            ps->y = fc[m].x;
            ps->n = (size_t)fc[m].n;
            ps->style = m;
        }
    if (L.p[0].n)
        lx_chart(x, PLOT_LINES, &L, "dam-front", 1000, 650,
                 "{{@the dam break's front over time, each wall model|"
                 "le front de la rupture de barrage au cours du temps, avec chaque modèle de paroi}}");
}

int lx_lesson10(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    lx_pipeline(x, "lesson.ini", NULL, 0);
    lesson10_rest(x);
    lesson10_tank(x);
    lesson10_dam(x);
    return 0;
}

/* ---- lesson 11: how incompressible, at what cost --------------------------------------------- */

/* The study's CSV as a Markdown table: setting, errors, cost. */
static void solvers_table(lx *x, const char *csv)
{
    char *text = lx_read_file(csv);
    if (!text) {
        x->failed++;
        return;
    }
    char *lines[64];
    int nl = 0;
    for (char *l = strtok(text, "\n"); l && nl < 64; l = strtok(NULL, "\n")) lines[nl++] = l;
    char *hdr[32];
    int nh = nl ? lx_split_csv(lines[0], hdr, 32) : 0;
    static const char *const want[] = {"error", "run_max", "mean_error", "steps_per_sim_s",
                                       "iterations_per_step", "ms_per_sim_s", "pareto"};
    int col[7];
    for (int k = 0; k < 7; k++) {
        col[k] = -1;
        for (int i = 0; i < nh; i++)
            if (strcmp(hdr[i], want[k]) == 0) col[k] = i;
        if (col[k] < 0) {
            lx_md(x, "`%s`: no column %s.\n\n", csv, want[k]);
            x->failed++;
            free(text);
            return;
        }
    }
    lx_md(x, "| {{@setting (solver+stiffness+tolerance)|réglage (solveur+raideur+tolérance)}} | "
             "{{@each step's largest compression, time mean|plus grande compression de chaque pas, moyenne en "
             "temps}} | "
             "{{@the run's largest|la plus grande du calcul}} | {{@mean compression|compression moyenne}} | "
             "{{@steps per simulated s|pas par s simulée}} | {{@iterations per step|itérations par pas}} | "
             "{{@ms per simulated s|ms par s simulée}} | {{@Pareto front|front de Pareto}} "
             "|\n|---|---|---|---|---|---|---|---|\n");
    for (int l = 1; l < nl; l++) {
        char *f[32];
        if (lx_split_csv(lines[l], f, 32) != nh) continue;
        double v[7];
        for (int k = 0; k < 7; k++) v[k] = strtod(f[col[k]], NULL);
        char its[32] = "-"; /* the equation of state iterates nothing: "-", as docs/accuracy.md's table, not 0.0 */
        if (v[4] > 0 || isnan(v[4])) snprintf(its, sizeof its, "%.1f", v[4]); /* a stopped run: nan, as its others */
        lx_md(x, "| %s | %.2f %% | %.2f %% | %.3f %% | %.0f | %s | %.0f | %s |\n", f[1], 100 * v[0], 100 * v[1],
              100 * v[2], v[3], its, v[5], v[6] > 0 ? "{{@yes|oui}}" : "");
    }
    lx_md(x, "\n");
    free(text);
}

int lx_lesson11(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    lx_pipeline(x, "lesson.ini", NULL, 0);
    lx_val(x, "particles", "%ld", (long)(sph_block_nodes(&def, 0, 0) * sph_block_nodes(&def, 0, 1)));
    lx_val(x, "duration", "%g", x->quick ? 0.05 : def.duration);
    lx_val(x, "dt_cap", "%g", def.dt);
    lx_val(x, "study", "%s", lx_has_command(x, "study") ? "yes" : "");
    if (!lx_has_command(x, "study")) {
        lx_missing(x, "`sphlab study` is not in this build: no table of the solvers and no Pareto chart");
        return 0;
    }
    /* the equation of state at three stiffnesses, each solver at two tolerances: one linked knob, one row each */
    const char *knob = x->quick ? "physics.pressure_solver+physics.stiffness+physics.solver_tolerance="
                                  "eos+400+0.01,pcisph+400+0.01,dfsph+400+0.01"
                                : "physics.pressure_solver+physics.stiffness+physics.solver_tolerance="
                                  "eos+100+0.01,eos+400+0.01,eos+1600+0.01,pcisph+400+0.01,pcisph+400+0.001,"
                                  "dfsph+400+0.01,dfsph+400+0.001";
    const char *repeats = x->quick ? "1" : "3", *time = x->quick ? "0.05" : lx_fmt("%g", def.duration);
    const char *argv[] = {"sphlab", "study", scene, "--metric", "compression", "--vary", knob, "--time", time,
                          "--repeats", repeats, "--threads", "1", "--out", x->dir, "--name", "solvers", NULL};
    const char *log;
    FILE *lf = lx_log_open(x, "study-solvers", argv, &log);
    study_cmd sc = {.scene = {.path = scene}, .out = x->dir, .metric = "compression", .base = "solvers",
                    .repeats = atol(repeats), .steps = -1, .threads = 1, .until = atof(time), .quiet = true};
    char why[512] = "";
    bool planned = study_plan_add(&sc.plan, knob, why, sizeof why);
    char *text = NULL;
    size_t tlen = 0;
    sc.table = open_memstream(&text, &tlen);
    int rc = planned && sc.table ? study_cmd_run(&sc) : 2;
    if (sc.table) fclose(sc.table);
    if (lf) {
        fputs(text ? text : "", lf);
        fclose(lf);
    }
    if (rc != 0) {
        x->failed++;
        lx_md(x, "\n**`sphlab study` failed** (exit %d%s%s), see `logs/%s`.\n\n", rc, why[0] ? ": " : "", why,
              strrchr(log, '/') + 1);
        free(text);
        lx_val(x, "args_solvers", "%s", "");
        lx_val(x, "table_solvers", "%s", "");
        return 1;
    }
    lx_block(x, "args_solvers");
    for (int i = 3; argv[i]; i++) lx_md(x, "%s%s", i > 3 ? " " : "", argv[i] == x->dir ? "DIR" : argv[i]);
    lx_block(x, "table_solvers");
    lx_md_text(x, text ? text : "", 40);
    free(text);
    solvers_table(x, lx_out(x, "solvers.csv"));
    lx_block_end(x);
    lx_fig(x, "solvers.png",
           "{{@each step's largest compression (time mean) against the run's wall time of every setting (log-log), "
                             "the Pareto front marked (PDF and CSV beside it)|la plus grande compression de chaque pas "
                             "(moyenne en temps) contre le temps de calcul de chaque réglage (log-log), le front de "
                             "Pareto marqué (PDF et CSV à côté)}}");
    lx_fig(x, "solvers.csv",
           "{{@one row per setting: compression (each step's largest, the run's largest, the mean), steps and ms per "
                             "simulated second, iterations per step|une ligne par réglage : compression (la plus "
                             "grande "
                             "de chaque pas, la plus grande du calcul, la moyenne), pas et ms par seconde simulée, "
                             "itérations par pas}}");
    return 0;
}
