/* sphlab bench solvers: the pressure solvers side by side at equal density
 * error (issue 14's target): a 3D dam break of N particles (--at, at least
 * 50,000 by default) run for a short simulated time with
 *   eos     at the stiffness that holds the largest density error within
 *           the target (doubled from a start until a run holds it),
 *   pcisph  and dfsph at solver_tolerance = the target,
 * interleaved (eos, pcisph, dfsph, eos, ...) so that a change of the
 * machine's load hits all three alike; each setting's figures are the
 * medians over the repeats. The density error is the one the step reached
 * (sph_sim_compression_lattice: summed at the positions after the step,
 * against the lattice's rest density rho_rest = rho0 (1 + e), e = +1.2 % in
 * 3D at h = 2 spacings, the walls as the solvers count them), its largest
 * over the run, the time mean of each step's largest (what the stiffness
 * search holds to the target: the largest of the run is not a function of
 * the stiffness for the equation of state, see SOLVERS_TARGET) and the
 * time mean of the mean compression. One yardstick for the three: the
 * equation of state holds rho0 with the volume model's walls, so by its own
 * measure a block at rest on the lattice reads e (and 0.2 % more at the
 * walls) before anything moves, at any stiffness. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "bench_cmd.h"

/* [1] the density error the three must hold: the solvers' tolerance (each
 * step's largest), and for the equation of state the time mean of each
 * step's largest. Its run's largest is not a target it can meet: its block
 * starts off its own rest state and rings, 0.10 % over rho_rest within the
 * first sound crossing at every stiffness from 4000 to 512,000 (measured
 * at 4000 particles), a time that shrinks as 1/c while the peak does not. */
#define SOLVERS_TARGET 0.001
#define SOLVERS_SPACING 0.01     /* [m] h = 2 spacings */
#define SOLVERS_DT_CAP 0.002     /* [s] the step's cap; CFL 0.4 below it */
#define SOLVERS_K_START 4000.0   /* [m^2/s^2] the first stiffness the search tries (c = 63 m/s) */
#define SOLVERS_K_MAX 4.1e6      /* [m^2/s^2] the search gives up above (c = 2 km/s) */

enum { SETTING_EOS, SETTING_PCISPH, SETTING_DFSPH, SETTINGS };
static const char *const setting_names[SETTINGS] = {"eos", "pcisph", "dfsph"};

typedef struct solver_run {
    bool ok;            /* ran to the end, the watchdog quiet */
    double err_max;     /* [1] the largest density error of any step */
    double err_step;    /* [1] the time mean of each step's largest: what the target holds */
    double err_mean;    /* [1] the time mean of each step's mean compression */
    double steps;       /* [1] */
    double iterations;  /* [1] per step, divergence solve included */
    double ms_per_s;    /* [ms] wall time in sph_sim_step per simulated second */
    double dt_mean;     /* [s] */
    char why[1024];     /* if not ok */
} solver_run;

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
             "[physics]\nrest_density = 1000\neos = linear\nstiffness = %g\nviscosity = 0.002\n"
             "negative_pressure = clamp\npressure_solver = %s\nsolver_tolerance = %g\n"
             "[kernels]\nh = %g\n[time]\ndt = %g\ncfl = 0.4\n",
             duration, 3 * side[0] * s, 1.5 * side[1] * s, side[2] * s, side[0] * s, side[1] * s, side[2] * s, s,
             k, setting_names[setting], SOLVERS_TARGET, 2 * s, SOLVERS_DT_CAP);
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
            snprintf(out->why, sizeof out->why, "the time mean of each step's largest error is above %g %% by t = %.4g s",
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
    sph_sim_destroy(sim);
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

int bench_cmd_solvers(bench_opts *o)
{
    const double n = o->at_given ? o->at : (o->quick ? 4000 : 50000);
    const double duration = o->quick ? 0.01 : 0.02; /* [s] simulated: the column's first fall */
    const int repeats = o->quick ? 1 : 3, threads = 2;
    int side[3];
    column_sides(n, side);
    const double count = (double)side[0] * side[1] * side[2];
    setvbuf(stdout, NULL, _IOLBF, 0); /* each line as it comes: a long run into a file keeps what it measured */
    char date[64];
    double load0[3], load1[3];
    bench_now_iso(date, sizeof date);
    bench_loadavg(load0);
    if (!o->quiet)
        printf("sphlab bench solvers: %s, load %.2f; 3D dam break, %.0f particles (%d x %d x %d, spacing %g m), "
               "%g s simulated, %d threads, target: density error <= %g %% (each step's largest; eos: its time mean)\n",
               date, load0[0], count, side[0], side[1], side[2], SOLVERS_SPACING, duration, threads,
               100 * SOLVERS_TARGET);

    /* the stiffness: doubled until a run holds the target; if none does
     * before the watchdog stops the runs, the stiffest that ran is compared
     * (the equation of state then at a larger error than the solvers) */
    double k = SOLVERS_K_START, k_ran = 0;
    bool held = false;
    solver_run r;
    for (; k <= SOLVERS_K_MAX; k *= 2) {
        bench_progress("eos: trying stiffness %g", k);
        run_one(SETTING_EOS, count, k, duration, threads, SOLVERS_TARGET, true, &r);
        if (!o->quiet) printf("  eos, stiffness %-9g %s\n", k, r.ok ? "holds it" : r.why);
        if (r.ok) {
            held = true;
            break;
        }
        if (strstr(r.why, "time mean")) k_ran = k; /* stopped by the target, not by the watchdog */
    }
    if (!held) {
        if (!(k_ran > 0)) {
            bench_progress_done();
            fprintf(stderr, "sphlab bench solvers: no stiffness from %g to %g ran\n", SOLVERS_K_START, SOLVERS_K_MAX);
            return 1;
        }
        k = k_ran;
        if (!o->quiet)
            printf("  no stiffness holds %g %%: eos is compared at %g, the stiffest that ran, at a larger error\n",
                   100 * SOLVERS_TARGET, k);
    }
    bench_progress_done();

    solver_run runs[SETTINGS][8];
    for (int rep = 0; rep < repeats; rep++)
        for (int s = 0; s < SETTINGS; s++) {
            bench_progress("repeat %d of %d: %s", rep + 1, repeats, setting_names[s]);
            run_one(s, count, k, duration, threads, 0, o->cfg.watchdog, &runs[s][rep]);
            if (!runs[s][rep].ok) {
                bench_progress_done();
                fprintf(stderr, "sphlab bench solvers: %s: %s\n", setting_names[s], runs[s][rep].why);
                return 1;
            }
        }
    bench_progress_done();
    bench_loadavg(load1);

    double med[SETTINGS][7];
    for (int s = 0; s < SETTINGS; s++) {
        double v[7][8];
        for (int rep = 0; rep < repeats; rep++) {
            const solver_run *x = &runs[s][rep];
            const double f[7] = {x->err_max,    x->err_mean, x->steps,   x->iterations,
                                 x->ms_per_s, x->dt_mean,  x->err_step};
            for (int c = 0; c < 7; c++) v[c][rep] = f[c];
        }
        for (int c = 0; c < 7; c++) med[s][c] = median(v[c], repeats);
    }
    if (!o->quiet) {
        printf("\n%-8s %-11s %-10s %-11s %-11s %-7s %-8s %-8s %-14s %s\n", "solver", "stiffness", "err max %",
               "step max %", "err mean %", "steps", "dt ms", "it/step", "ms per sim. s", "eos / this");
        for (int s = 0; s < SETTINGS; s++) {
            char kk[32];
            snprintf(kk, sizeof kk, s == SETTING_EOS ? "%g" : "-", k);
            printf("%-8s %-11s %-10.4f %-11.4f %-11.4f %-7.0f %-8.4f %-8.1f %-14.0f %.2f\n", setting_names[s], kk,
                   100 * med[s][0], 100 * med[s][6], 100 * med[s][1], med[s][2], 1e3 * med[s][5], med[s][3],
                   med[s][4], med[SETTING_EOS][4] / med[s][4]);
        }
        printf("\nmedians of %d interleaved repeat(s); load %.2f at the start, %.2f at the end (1-minute averages)\n",
               repeats, load0[0], load1[0]);
    }
    return 0;
}
