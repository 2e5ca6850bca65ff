/* sphlab bench solvers: the pressure solvers side by side at equal density
 * error (issue 14's target): a 3D dam break of N particles (--at, 50,000 by
 * default) run for T simulated seconds (--time, 0.02 s by default) from the
 * same initial state with
 *   eos     at the least stiffness that holds the target (bisection on
 *           log k: doubled or halved from a start until the target is
 *           bracketed, then split until the bracket is within 10 %; a try
 *           stops as soon as its error can only end above the target, or
 *           when the watchdog fires),
 *   pcisph  and dfsph at solver_tolerance = the target, from p = 0 each step,
 *   pcisph+ and dfsph+ the same with solver_warm_start = on (pcisph+ also
 *           pcisph_local_delta = on),
 *   pcisph* and dfsph* the + rows with solver_chebyshev = 0.9 (the density
 *           solve's Chebyshev acceleration, src/passes/solver.h),
 * in R interleaved rounds (--repeats; eos, pcisph*, dfsph*, pcisph+, dfsph+, pcisph, dfsph, eos, ...) so that
 * a change of the machine's load hits all three alike; each setting's
 * figures are the medians over the rounds, each ratio the median of the
 * rounds' own ratios with the least and the largest. The error is measured
 * the same way for every row over the same window 0 to T: after every step
 * the compression sph_sim_compression_lattice gives (summed at the positions
 * after the step, against the lattice's rest density rho_rest = rho0 (1 + e),
 * e = +1.2 % in 3D at h = 2 spacings, the walls as the solvers count them);
 * its largest over the particles is a step's error, and the target holds
 * the time mean of the steps' errors (each weighted by its dt). The largest
 * over the particles and the steps is printed beside it: the equation of
 * state cannot be held to it (see SOLVERS_TARGET). The same rest density for
 * the three: the equation of state runs with eos_rest = lattice, so it too
 * holds rho_rest and a block on the lattice starts at p = 0 (with rho0 it
 * started compressed by e, and its free surfaces burst outward at a speed
 * growing with sqrt(k)); only the volume model's walls still read 0.2 % more
 * than the solvers' wall rows before anything moves. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cmd.h"

/* [1] the density error the three must hold: the solvers' tolerance (each
 * step's largest), and for the equation of state the time mean of each
 * step's largest. Its run's largest is not the target: the equation of
 * state only answers compression it has seen (0.16 % at 4000 particles and
 * the stiffness found, 2378; when it held rho0, its block started off its
 * own rest state and rang 0.10 % over rho_rest within the first sound
 * crossing at every stiffness from 4000 to 512,000). */
#define SOLVERS_TARGET 0.001
#define SOLVERS_SPACING 0.01     /* [m] h = 2 spacings */
#define SOLVERS_DT_CAP 0.002     /* [s] the step's cap; CFL 0.4 below it */
#define SOLVERS_K_START 16000.0  /* [m^2/s^2] the first stiffness the search tries (c = 126 m/s) */
#define SOLVERS_K_MIN 250.0      /* [m^2/s^2] the search goes no lower (c = 16 m/s) */
#define SOLVERS_K_MAX 4.1e6      /* [m^2/s^2] the search gives up above (c = 2 km/s) */
#define SOLVERS_K_RATIO 1.1      /* [1] the search stops when its bracket (held / not held) is this narrow */
#define SOLVERS_ROUNDS_MAX 50    /* --repeats' bound */
/* [1] the solvers' iteration cap here: high enough that they iterate until
 * they hold the target (at 50,688 particles and 2 ms steps the scenes' 100
 * stopped PCISPH at 0.33 % and DFSPH at 0.18 % on average, cheaper than the
 * target but not at equal error); every iteration is counted in the cost */
#define SOLVERS_ITER_CAP 2000

/* pcisph+ and dfsph+: the same solvers with solver_warm_start = on (and for
 * PCISPH pcisph_local_delta = on), beside the cold ones in the same rounds;
 * pcisph* and dfsph*: those with solver_chebyshev = 0.9 */
enum {
    SETTING_EOS,
    SETTING_PCISPH,
    SETTING_DFSPH,
    SETTING_PCISPH_WARM,
    SETTING_DFSPH_WARM,
    SETTING_PCISPH_CHEB,
    SETTING_DFSPH_CHEB,
    SETTINGS
};
static const char *const setting_names[SETTINGS] = {"eos", "pcisph", "dfsph", "pcisph+", "dfsph+", "pcisph*", "dfsph*"};
static const char *const setting_solver[SETTINGS] = {"eos", "pcisph", "dfsph", "pcisph", "dfsph", "pcisph", "dfsph"};
#define SOLVERS_CHEB "solver_chebyshev = 0.9\n"
static const char *const setting_keys[SETTINGS] = {"",
                                                   "",
                                                   "",
                                                   "solver_warm_start = on\npcisph_local_delta = on\n",
                                                   "solver_warm_start = on\n",
                                                   "solver_warm_start = on\npcisph_local_delta = on\n" SOLVERS_CHEB,
                                                   "solver_warm_start = on\n" SOLVERS_CHEB};

typedef struct solver_run {
    bool ok;            /* ran to the end, the watchdog quiet */
    double err_max;     /* [1] the largest density error of any step */
    double err_step;    /* [1] the time mean of each step's largest: what the target holds */
    double err_mean;    /* [1] the time mean of each step's mean compression */
    double steps;       /* [1] */
    double iterations;  /* [1] per step, divergence solve included */
    double ms_per_s;    /* [ms] wall time in sph_sim_step per simulated second */
    double dt_mean;     /* [s] */
    bool over;          /* not ok: stopped because the target could only end above (not the watchdog) */
    double t_end;       /* [s] simulated time reached */
    double wall_ms;     /* [ms] the whole run, the error's summation included */
    char why[1024];     /* if not ok */
} solver_run;

static bool g_trace; /* --trace: a line per run on stderr */

/* The column: nx x ny x nz particles, the box 3 columns long and 1.5 high. */
static void column_sides(double n, int side[3])
{
    /* a column twice as high as deep, as long as high: x = y = 2 z */
    int z = (int)ceil(cbrt(n / 4.0));
    while (4.0 * z * z * z < n) z++;
    side[0] = side[1] = 2 * z;
    side[2] = z;
    while (side[0] * side[1] * (side[2] - 1) >= n && side[2] > 1) side[2]--;
}

static bool scene(int setting, double n, double k, double duration, sph_scene_def *def, char *why, size_t cap)
{
    int side[3];
    column_sides(n, side);
    const double s = SOLVERS_SPACING;
    char ini[2048];
    snprintf(ini, sizeof ini,
             "[scene]\nname = bench solvers: 3D dam break\ndimension = 3\n"
             "effects = gravity pressure viscosity walls\nduration = %g\n"
             "[domain]\nmin = 0 0 0\nmax = %g %g %g\nwall_damping = 0.3\n"
             "[fluid column]\nmin = 0 0 0\nmax = %g %g %g\nspacing = %g\n"
             "[physics]\nrest_density = 1000\neos = linear\neos_rest = lattice\nstiffness = %g\nviscosity = 0.002\n"
             "negative_pressure = clamp\npressure_solver = %s\nsolver_tolerance = %g\nsolver_max_iterations = %d\n%s"
             "[kernels]\nh = %g\n[time]\ndt = %g\ncfl = 0.4\n",
             duration, 3 * side[0] * s, 1.5 * side[1] * s, side[2] * s, side[0] * s, side[1] * s, side[2] * s, s,
             k, setting_solver[setting], SOLVERS_TARGET, SOLVERS_ITER_CAP, setting_keys[setting], 2 * s,
             SOLVERS_DT_CAP);
    *def = sph_default_scene_def();
    sph_error err;
    if (sph_scene_load_string(ini, "bench-solvers.ini", def, &err) != SPH_ERR_OK ||
        sph_scene_validate(def, &err) != SPH_ERR_OK) {
        snprintf(why, cap, "%s", err.msg);
        return false;
    }
    return true;
}

/* One run; stop_above > 0: give up as soon as a step's error exceeds it
 * (the stiffness search's failed tries cost little). */
static void run_one(int setting, double n, double k, double duration, int threads, double stop_above, bool watch,
                    solver_run *out)
{
    memset(out, 0, sizeof *out);
    sph_scene_def def;
    if (!scene(setting, n, k, duration, &def, out->why, sizeof out->why)) return;
    sph_sim *sim;
    sph_error err;
    if (sph_sim_create(&def, threads, &sim, &err) != SPH_ERR_OK) {
        snprintf(out->why, sizeof out->why, "%s", err.msg);
        return;
    }
    sim->watchdog = watch; /* off while timing, as the ladder (--watchdog keeps it) */
    const double w0 = sph_now_ms();
    double wall = 0, its = 0, mean_dt = 0, max_dt = 0;
    long steps = 0;
    out->ok = true;
    while (sim->t < duration) {
        const double t0 = sph_now_ms();
        sph_sim_step(sim);
        wall += sph_now_ms() - t0;
        if (sim->alarm.raised || !isfinite(sim->max_speed)) {
            out->ok = false;
            snprintf(out->why, sizeof out->why, "stopped at step %llu (the watchdog, or a speed not finite)",
                     (unsigned long long)sim->step);
            break;
        }
        double mx, mean;
        sph_sim_compression_lattice(sim, &mx, &mean);
        out->err_max = fmax(out->err_max, mx);
        mean_dt += sim->dt * mean;
        max_dt += sim->dt * fmax(mx, 0.0);
        its += sim->solver.iterations + sim->solver.div_iterations;
        steps++;
        if (stop_above > 0 && max_dt > stop_above * duration) { /* the time mean can only end above it */
            out->ok = false;
            out->over = true;
            snprintf(out->why, sizeof out->why, "the time mean of the steps' errors is above %g %% by t = %.4g s",
                     100 * stop_above, sim->t);
            break;
        }
    }
    out->steps = (double)steps;
    out->iterations = steps ? its / (double)steps : 0;
    out->err_mean = sim->t > 0 ? mean_dt / sim->t : 0;
    out->err_step = sim->t > 0 ? max_dt / sim->t : 0;
    out->ms_per_s = sim->t > 0 ? wall / sim->t : 0;
    out->dt_mean = steps ? sim->t / (double)steps : 0;
    out->t_end = sim->t;
    sph_sim_destroy(sim);
    out->wall_ms = sph_now_ms() - w0;
    if (g_trace)
        fprintf(stderr,
                "trace solvers %-6s k %-9g %6ld steps  t %.4g s  error: largest %.4f %%, steps' time mean %.4f %%  "
                "%.0f ms per simulated s  %.1f s wall%s%s\n",
                setting_names[setting], k, steps, out->t_end, 100 * out->err_max, 100 * out->err_step, out->ms_per_s,
                1e-3 * out->wall_ms, out->ok ? "" : "  stopped: ", out->ok ? "" : out->why);
}

static int cmp_double(const void *a, const void *b)
{
    const double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

static double median(double *v, int n)
{
    qsort(v, (size_t)n, sizeof *v, cmp_double);
    return n == 0 ? NAN : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

/* The least stiffness whose run holds the time mean of the steps' errors
 * within the target (the eos's cheapest run at that error): bracketed by
 * doubling or halving from SOLVERS_K_START, then bisected on log k. 0 if
 * none from SOLVERS_K_MIN to SOLVERS_K_MAX holds; *k_over: the stiffest stopped by
 * the target rather than the watchdog, 0 if none. */
static double stiffness_search(const bench_opts *o, double count, double duration, int threads, int *tries,
                               double *k_over)
{
    double k_hold = 0, k_low = 0; /* k_low: the stiffest below k_hold known not to hold */
    *k_over = 0;
    *tries = 0;
    solver_run r;
#define TRY(kk)                                                                                                       \
    do {                                                                                                              \
        bench_progress("eos: trying stiffness %g (try %d)", (kk), *tries + 1);                                       \
        run_one(SETTING_EOS, count, (kk), duration, threads, SOLVERS_TARGET, true, &r);                              \
        ++*tries;                                                                                                     \
        if (r.over && (kk) > *k_over) *k_over = (kk);                                                                 \
        if (!o->quiet)                                                                                                \
            printf("  eos, stiffness %-9g %s (%.1f s)\n", (kk), r.ok ? "holds it" : r.why, 1e-3 * r.wall_ms);     \
    } while (0)
    double k = SOLVERS_K_START;
    TRY(k);
    if (r.ok) {
        k_hold = k;
        for (k = k_hold / 2; k >= SOLVERS_K_MIN; k /= 2) {
            TRY(k);
            if (!r.ok) {
                k_low = k;
                break;
            }
            k_hold = k;
        }
    } else {
        k_low = k;
        for (k = 2 * k_low; k <= SOLVERS_K_MAX; k *= 2) {
            TRY(k);
            if (r.ok) {
                k_hold = k;
                break;
            }
            k_low = k;
        }
    }
    while (k_hold > 0 && k_low > 0 && k_hold / k_low > SOLVERS_K_RATIO) {
        k = sqrt(k_hold * k_low);
        TRY(k);
        if (r.ok)
            k_hold = k;
        else
            k_low = k; /* the watchdog too: not a stiffness that holds it */
    }
#undef TRY
    return k_hold;
}

/* --solvers: the rows to run besides eos, which always runs (every ratio is against it); NULL: all. */
static bool parse_solvers(const char *list, bool want[SETTINGS])
{
    for (int s = 0; s < SETTINGS; s++) want[s] = list == NULL;
    want[SETTING_EOS] = true;
    if (!list) return true;
    const size_t len = strlen(list); /* empty items ("", "pcisph,"): a typo, said (strtok dropped them unsaid) */
    if (!len || list[0] == ',' || list[len - 1] == ',' || strstr(list, ",,")) {
        fprintf(stderr, "sphlab bench solvers: --solvers '%s': an empty item (accepted: eos, pcisph, dfsph, pcisph+, "
                        "dfsph+, pcisph*, dfsph*, comma-separated)\n", list);
        return false;
    }
    char buf[256];
    if (snprintf(buf, sizeof buf, "%s", list) >= (int)sizeof buf) {
        fprintf(stderr, "sphlab bench solvers: --solvers '%s': too long\n", list);
        return false;
    }
    for (char *save = NULL, *t = strtok_r(buf, ",", &save); t; t = strtok_r(NULL, ",", &save)) {
        int found = -1;
        for (int s = 0; s < SETTINGS; s++)
            if (strcmp(t, setting_names[s]) == 0) found = s;
        if (found < 0) {
            fprintf(stderr, "sphlab bench solvers: --solvers: no solver row '%s' (accepted: eos, pcisph, dfsph, "
                    "pcisph+, dfsph+, pcisph*, dfsph*)\n", t);
            return false;
        }
        want[found] = true;
    }
    return true;
}

int bench_cmd_solvers(bench_opts *o)
{
    const double n = o->at_given ? o->at : (o->quick ? 4000 : 50000);
    const double duration = o->time > 0 ? o->time : o->quick ? 0.01 : 0.02; /* [s] simulated: the column's first fall */
    const int repeats = o->repeats > 0 ? o->repeats : o->quick ? 1 : 5, threads = 2;
    if (o->cfg.dim != 3) {
        fprintf(stderr, "sphlab bench solvers: --dim %d: the solver bench is a 3D dam break only\n", o->cfg.dim);
        return 2;
    }
    const double cap_steps = duration / SOLVERS_DT_CAP;
    if (fabs(cap_steps - round(cap_steps)) > 1e-6) { /* else the solvers' last step runs past T */
        fprintf(stderr, "sphlab bench solvers: --time %g: want a whole number of the solvers' %g s steps\n", duration,
                SOLVERS_DT_CAP);
        return 2;
    }
    if (repeats > SOLVERS_ROUNDS_MAX) {
        fprintf(stderr, "sphlab bench solvers: --repeats %d: at most %d\n", repeats, SOLVERS_ROUNDS_MAX);
        return 2;
    }
    bool want[SETTINGS];
    if (!parse_solvers(o->solvers, want)) return 2;
    g_trace = o->trace;
    int side[3];
    column_sides(n, side);
    const double count = (double)side[0] * side[1] * side[2];
    setvbuf(stdout, NULL, _IOLBF, 0); /* each line as it comes: a long run into a file keeps what it measured */
    char date[64];
    double load0[3], load1[3];
    const double t_start = sph_now_ms();
    bench_now_iso(date, sizeof date);
    bench_loadavg(load0);
    if (!o->quiet)
        printf("sphlab bench solvers: %s, load %.2f; 3D dam break, %.0f particles (%d x %d x %d, spacing %g m), "
               "%d threads\nwindow: 0 to %g s simulated, the same initial state for all; a step's error: the largest "
               "compression over the particles\ntarget: the time mean of the steps' errors <= %g %% (pcisph, dfsph: "
               "solver_tolerance = %g %%, each step); the same rest density rho_rest for every row (eos: eos_rest = "
               "lattice)\n",
               date, load0[0], count, side[0], side[1], side[2], SOLVERS_SPACING, threads, duration,
               100 * SOLVERS_TARGET, 100 * SOLVERS_TARGET);

    int tries;
    double k_over;
    double k = stiffness_search(o, count, duration, threads, &tries, &k_over);
    bench_progress_done();
    if (!(k > 0)) { /* no ratio at equal error: timing eos at a larger error would answer another question */
        fprintf(stderr,
                "sphlab bench solvers: no stiffness from %g to %g holds the time mean of the steps' errors within "
                "%g %% over 0 to %g s (%d tries; the stiffest stopped by the target, not by the watchdog: %g); "
                "no ratio at equal error\n",
                SOLVERS_K_MIN, SOLVERS_K_MAX, 100 * SOLVERS_TARGET, duration, tries, k_over);
        return 1;
    }
    if (!o->quiet)
        printf("  eos at stiffness %g: the least that holds it, to a factor %g (%d tries, %.0f s)\n", k,
               SOLVERS_K_RATIO, tries, 1e-3 * (sph_now_ms() - t_start));

    static solver_run runs[SETTINGS][SOLVERS_ROUNDS_MAX];
    /* each round: eos, the warm solvers, then the cold ones (at 50,000 particles a cold solve could run to
     * its cap for minutes: --trace has the warm rows' figures before) */
    static const int order[SETTINGS] = {SETTING_EOS,         SETTING_PCISPH_CHEB, SETTING_DFSPH_CHEB,
                                        SETTING_PCISPH_WARM, SETTING_DFSPH_WARM, SETTING_PCISPH,
                                        SETTING_DFSPH};
    for (int rep = 0; rep < repeats; rep++)
        for (int o_ = 0; o_ < SETTINGS; o_++) {
            const int s = order[o_];
            if (!want[s]) continue;
            bench_progress("round %d of %d: %s", rep + 1, repeats, setting_names[s]);
            run_one(s, count, k, duration, threads, 0, o->cfg.watchdog, &runs[s][rep]);
            if (!runs[s][rep].ok) {
                bench_progress_done();
                fprintf(stderr, "sphlab bench solvers: %s: %s\n", setting_names[s], runs[s][rep].why);
                return 1;
            }
        }
    bench_progress_done();
    bench_loadavg(load1);

    enum { C_MAX, C_MEAN, C_STEPS, C_ITS, C_MS, C_DT, C_STEP, C_RATIO, COLS };
    double med[SETTINGS][COLS] = {{0}}, lo[SETTINGS] = {0}, hi[SETTINGS] = {0};
    for (int s = 0; s < SETTINGS; s++) {
        if (!want[s]) continue;
        double v[COLS][SOLVERS_ROUNDS_MAX];
        for (int rep = 0; rep < repeats; rep++) {
            const solver_run *x = &runs[s][rep];
            const double ratio = runs[SETTING_EOS][rep].ms_per_s / x->ms_per_s; /* this round's own */
            const double f[COLS] = {x->err_max, x->err_mean, x->steps,    x->iterations,
                                    x->ms_per_s, x->dt_mean, x->err_step, ratio};
            for (int c = 0; c < COLS; c++) v[c][rep] = f[c];
        }
        for (int c = 0; c < COLS; c++) med[s][c] = median(v[c], repeats); /* sorts: v[C_RATIO] ascending */
        lo[s] = v[C_RATIO][0];
        hi[s] = v[C_RATIO][repeats - 1];
    }
    bool equal = true;
    for (int s = 0; s < SETTINGS; s++) equal = equal && (!want[s] || med[s][C_STEP] <= SOLVERS_TARGET * (1 + 1e-6));
    if (!o->quiet) {
        printf("\n%-8s %-11s %-10s %-11s %-11s %-7s %-8s %-8s %-14s %-11s %s\n", "solver", "stiffness", "err max %",
               "step max %", "err mean %", "steps", "dt ms", "it/step", "ms per sim. s", "eos / this", "least-largest");
        for (int s = 0; s < SETTINGS; s++) {
            if (!want[s]) continue;
            char kk[32];
            snprintf(kk, sizeof kk, s == SETTING_EOS ? "%g" : "-", k);
            printf("%-8s %-11s %-10.4f %-11.4f %-11.4f %-7.0f %-8.4f %-8.1f %-14.0f %-11.2f %.2f-%.2f\n",
                   setting_names[s], kk, 100 * med[s][C_MAX], 100 * med[s][C_STEP], 100 * med[s][C_MEAN],
                   med[s][C_STEPS], 1e3 * med[s][C_DT], med[s][C_ITS], med[s][C_MS], med[s][C_RATIO], lo[s], hi[s]);
        }
        printf("\nerr max: the largest over the particles and the steps; step max: the time mean of the steps' "
               "largest (the target);\nerr mean: the time mean of the mean compression; medians of %d interleaved "
               "round(s); eos / this: the median of\nthe rounds' ratios of ms per simulated second, with the least "
               "and the largest\n",
               repeats);
        printf("at equal error (step max <= %g %% for every row): %s\n", 100 * SOLVERS_TARGET,
               equal ? "yes" : "NO");
        char r[SETTINGS][48];
        for (int s = 0; s < SETTINGS; s++)
            snprintf(r[s], sizeof r[s], want[s] ? "%.2f (%.2f-%.2f)" : "not run", med[s][C_RATIO], lo[s], hi[s]);
        printf("ratio: eos / pcisph %s, eos / dfsph %s; %.0f particles, %g s simulated\n", r[SETTING_PCISPH],
               r[SETTING_DFSPH], count, duration);
        printf("warm start (+): eos / pcisph+ %s, eos / dfsph+ %s; pcisph+: solver_warm_start and pcisph_local_delta "
               "on, dfsph+: solver_warm_start on\n",
               r[SETTING_PCISPH_WARM], r[SETTING_DFSPH_WARM]);
        printf("Chebyshev (*): eos / pcisph* %s, eos / dfsph* %s; the + rows with solver_chebyshev = 0.9\n",
               r[SETTING_PCISPH_CHEB], r[SETTING_DFSPH_CHEB]);
        printf("load %.2f at the start, %.2f at the end (1-minute averages); %.0f s in all\n", load0[0], load1[0],
               1e-3 * (sph_now_ms() - t_start));
    }
    return 0;
}
