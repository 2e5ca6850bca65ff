/* sphlab validate NAME [--resolution R[,R...]] [--out DIR] [--quick]:
 * a reference problem with published data or an exact solution, run at
 * several resolutions; writes DIR/NAME.csv, the chart DIR/NAME.png and .pdf
 * against the reference, and one line "validate NAME: PASS|FAIL: ..." with
 * the measured error and its tolerance. `sphlab validate list` lists them. */
#include <errno.h>
#include <stdlib.h>
#include <string.h>

#include "app.h"
#include "plot.h"
#include "validate_run.h"
#include "sph_names.h"

/* One row per problem; run NULL: not written yet. */
const val_problem val_problems[] = {
    {"dam-break", "collapse of a water column of width a and height 2a (n^2 = 2) on a dry floor",
     "surge front Z(T) of Martin & Moyce 1952, Table 2 (judged; their Figure 3 curves of two column sizes and "
     "Koshizuka & Oka 1996 shown and reported); column height H of Martin & Moyce 1952, Table 6",
     "over 0.8 <= T <= 3: front mean |Z/Z_ref - 1| <= 5 %, max <= 10 %; height mean |H/H_ref - 1| <= 5 %; at "
     "a/spacing >= 40",
     "a / spacing", {20, 40, 80},
     10, 4, 400, val_run_dam_break},
    {"hydrostatic", "water at rest in a tank with no-slip wall particles",
     "p(y) of the column at rest with the scene's equation of state (dp/dy = -rho(p) g; rho0 g (H - y) as c grows) "
     "on the centre line, the row at the floor included; speed 0",
     "after settling, in every sampled frame: |p - p_exact| <= 1 % of rho0 g H at H/spacing >= 20; max speed < 1 % "
     "of sqrt(g H)",
     "H / spacing", {20, 40, 80}, 8, 4, 400, val_run_hydrostatic},
    {"taylor-green", "the decaying periodic vortex at Re = 100",
     "exact decay U exp(-8 pi^2 t / Re): max speed, kinetic energy, L1 error of the speed (PySPH's definitions)",
     "at 50 particles a side: max-speed error <= 5 %, L1 <= 10 %; L1 falls as the resolution grows",
     /* from 13: the periodic box (1 m) must be longer than 3 h, h = 4 spacings */
     "particles per side", {25, 50, 100}, 16, 13, 400, val_run_taylor_green},
    {"poiseuille", "start-up plane Poiseuille flow between no-slip walls, driven by a body force",
     "series solution, Morris, Fox & Zhu 1997 eq. 21",
     "velocity profile error <= 5 % of u_max during start-up, <= 2 % at steady state", "particles across",
     {10, 20, 40}, 10, 4, 400, val_run_poiseuille},
    {"couette", "start-up Couette flow: the top wall moves at U from t = 0",
     "series solution of the same diffusion problem", "velocity profile error <= 2 % of U at every sampled time",
     "particles across", {10, 20, 40}, 10, 4, 400, val_run_couette},
    {"drop", "a 2D drop (a liquid cylinder) without gravity, held by surface_tension = stress (sigma = 1 N/m, written 1 N in the 2D units of a slice one metre deep), "
             "oscillating in its n = 2 mode",
     "Rayleigh 1879: omega^2 = (n^3 - n) sigma / (rho R^3) at the stated sigma (akinci: sigma measured from the "
     "Laplace pressure of two drops)",
     "period within 5 % of Rayleigh's at R / spacing = 20", "R / spacing", {10, 15, 20}, 10, 6, 200, val_run_drop},
    {"drop-3d", "a 3D drop (a sphere) without gravity, held by surface_tension = csf (sigma = 1 N/m), oscillating in "
                "its l = 2 mode",
     "Rayleigh 1879: omega^2 = l (l - 1) (l + 2) sigma / (rho R^3) at the stated sigma",
     "period within 5 % of Rayleigh's at R / spacing = 10", "R / spacing", {6, 8, 10}, 6, 4, 40, val_run_drop_3d},
    {"obstacle", "a dam break (column a x 2a) hitting a box obstacle across the tank at x = 2a: the force on it",
     "the hydrostatic force rho0 g d^2 / 2 of the water standing against it at rest (exact); the impact time "
     "against the published surge fronts, reported",
     "force at rest (mean over the last second of 3 s) within 5 % of rho0 g d^2 / 2 at a/spacing >= 20",
     "a / spacing", {10, 20, 40}, 10, 4, 160, val_run_obstacle},
};
const int val_problem_count = (int)(sizeof val_problems / sizeof val_problems[0]);

static const app_cmd_spec spec = {
    .name = "validate",
    .cmd = APP_CMD(validate),
    .synopsis = "usage: sphlab validate NAME [--resolution R[,R...]] [--out DIR] [--quick] [options]\n"
                "       sphlab validate list\n"
                "Runs a reference problem at several resolutions against published data or an exact solution,\n"
                "writes DIR/NAME.csv and the chart DIR/NAME.png, DIR/NAME.pdf, and prints one line\n"
                "'validate NAME: PASS|FAIL: ...' with the measured error and the tolerance. NAME all runs every\n"
                "problem. docs/accuracy.md (Validation) describes each problem.\n",
    .footer = "exit status: 0 every target met; 1 a target missed (the line says which, by how much);\n"
              "2 bad command line (unknown problem, bad resolution); 3 the run or its outputs failed\n",
    .max_pos = 1,
    .extra_pos = "one problem at a time (sphlab validate list names them)",
};

static const val_problem *find(const char *name)
{
    for (int i = 0; i < val_problem_count; i++)
        if (strcmp(val_problems[i].name, name) == 0) return &val_problems[i];
    return NULL;
}

static void entry(FILE *f, const val_problem *p)
{
    fprintf(f, "%-13s %s\n", p->name, p->about);
    if (!p->run) return;
    fprintf(f, "%-13s   against: %s\n", "", p->reference);
    fprintf(f, "%-13s   target:  %s\n", "", p->target);
    fprintf(f, "%-13s   R = %s; default %d,%d,%d; --quick %d\n", "", p->res_meaning, p->res_default[0],
            p->res_default[1], p->res_default[2], p->res_quick);
}

static void list(FILE *f)
{
    for (int i = 0; i < val_problem_count; i++) entry(f, &val_problems[i]);
}

/* "40" or "20,40,80" into c->res, each within the problem's range. */
static bool parse_resolutions(const char *s, const val_problem *p, val_ctx *c)
{
    c->nres = 0;
    const char *q = s;
    for (;;) {
        char *end;
        errno = 0;
        long v = strtol(q, &end, 10);
        if (end == q || errno || (*end && *end != ',')) {
            fprintf(stderr, "sphlab validate: --resolution '%s': want whole numbers separated by commas (e.g. 20,40,80)\n",
                    s);
            return false;
        }
        if (v < p->res_min || v > p->res_max) {
            fprintf(stderr, "sphlab validate %s: --resolution %ld: out of range (R = %s, accepted: %d to %d)\n",
                    p->name, v, p->res_meaning, p->res_min, p->res_max);
            return false;
        }
        if (c->nres > 0 && v <= c->res[c->nres - 1]) { /* the trends are read in the given order */
            fprintf(stderr,
                    "sphlab validate %s: --resolution '%s': %ld after %d: give each resolution once, from the "
                    "coarsest to the finest (the error's trend is read in that order)\n",
                    p->name, s, v, c->res[c->nres - 1]);
            return false;
        }
        if (c->nres == VAL_MAX_RES) {
            fprintf(stderr, "sphlab validate: --resolution: at most %d values\n", VAL_MAX_RES);
            return false;
        }
        c->res[c->nres++] = (int)v;
        if (!*end) break;
        q = end + 1;
    }
    return true;
}

static int run_one(const val_problem *p, const app_opts *o)
{
    val_ctx c = {.out = o->out ? o->out : "out/validate", .quick = o->quick, .quiet = o->quiet,
                 .threads = (int)o->threads};
    if (o->resolution) {
        if (!parse_resolutions(o->resolution, p, &c)) return VAL_USAGE;
    } else if (o->quick) {
        c.res[0] = p->res_quick;
        c.nres = 1;
    } else {
        for (int i = 0; i < 3; i++) c.res[i] = p->res_default[i];
        c.nres = 3;
    }
    if (!plot_out_dir(c.out)) return VAL_ERROR;
    if (!c.quiet) fprintf(stderr, "validate %s: %s\n", p->name, p->about);
    return p->run(&c, p);
}

int cmd_validate(int argc, char **argv)
{
    app_opts o;
    app_opts_init(&o);
    int rc = app_opts_parse(&spec, argc, argv, &o);
    plot_out_command("validate");
    if (rc == 0) { /* the help printed: with a problem named, its reference, target and unit of --resolution too */
        for (int i = 1; i < argc; i++) {
            const val_problem *p = find(argv[i]);
            if (!p) continue;
            printf("\n");
            entry(stdout, p);
            break;
        }
    }
    if (rc >= 0) return rc;
    if (o.n_pos == 0) {
        app_opts_usage_error(&spec, "name a problem (sphlab validate list names them)");
        return VAL_USAGE;
    }
    const char *name = o.pos[0];
    if (strcmp(name, "list") == 0) {
        list(stdout);
        return 0;
    }
    if (strcmp(name, "all") == 0) {
        if (o.resolution) {
            fprintf(stderr, "sphlab validate all: --resolution differs between problems; give it to one problem\n");
            return VAL_USAGE;
        }
        int worst = VAL_PASS, n_run = 0, n_pass = 0;
        char failed[512] = "";
        size_t len = 0;
        for (int i = 0; i < val_problem_count; i++) {
            if (!val_problems[i].run) continue;
            int r = run_one(&val_problems[i], &o);
            if (r > worst) worst = r;
            n_run++;
            n_pass += r == VAL_PASS;
            if (r != VAL_PASS && len < sizeof failed)
                len += (size_t)snprintf(failed + len, sizeof failed - len, "%s%s (%s)", len ? ", " : "",
                                        val_problems[i].name, r == VAL_FAIL ? "FAIL" : "the run failed");
        }
        /* one line a class's smoke test can read: which problems did not pass, and that the exit says so */
        printf("\nvalidate all: %d of %d problems PASS%s%s%s\n", n_pass, n_run, n_pass < n_run ? "; not passed: " : "",
               failed, o.quick ? " (--quick: smaller resolutions, see each problem's line)" : "");
        return worst;
    }
    const val_problem *p = find(name);
    if (!p) {
        fprintf(stderr, "sphlab validate: unknown problem '%s'; known:", name);
        for (int i = 0; i < val_problem_count; i++) fprintf(stderr, " %s", val_problems[i].name);
        fprintf(stderr, ", list, all\n");
        int best = -1, best_d = 1 << 30;
        for (int i = 0; i < val_problem_count; i++) {
            int d = sph_edit_distance(name, val_problems[i].name);
            if (sph_name_near(name, val_problems[i].name) && d < best_d) best = i, best_d = d;
        }
        if (best >= 0) fprintf(stderr, "sphlab validate: did you mean %s?\n", val_problems[best].name);
        return VAL_USAGE;
    }
    if (!p->run) {
        fprintf(stderr, "sphlab validate %s: not written yet: %s\n", p->name, p->about);
        return VAL_USAGE;
    }
    return run_one(p, &o);
}
