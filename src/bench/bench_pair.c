/* sphlab bench pair: two CPU levels side by side (--levels A,B), built from
 * the bench's scene at --at N and stepped in turn from the same start on one
 * thread (or --threads T, then timed by the wall clock), for --repeats R
 * rounds (the order swapped every round), so that load from other jobs slows
 * both alike: each step's thread CPU time, the medians (least, largest) and
 * their ratio, each pass's mean time, the list builds, and how far the two
 * states are apart at the end (the same to the bit where the second level
 * only changes how the same sums are read). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "bench_cmd.h"

/* [ms] CPU time of the calling thread (one thread does all the work here). */
static double thread_cpu_ms(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec * 1e3 + (double)t.tv_nsec * 1e-6;
}

/* One step, pass by pass (sph_sim_step's loop): returns its time [ms], the
 * thread's CPU time (wall: the wall clock, for several threads), and adds
 * each pass's over `rounds` to pass_ms. */
static double step_timed(sph_sim *sim, double *pass_ms, int rounds, bool wall)
{
    const uint64_t step = sim->step;
    double total = 0;
    while (sim->step == step && !sim->alarm.raised) {
        const double c0 = wall ? sph_now_ms() : thread_cpu_ms();
        const sph_pass_id p = sph_sim_step_pass(sim);
        const double t = (wall ? sph_now_ms() : thread_cpu_ms()) - c0;
        total += t;
        if (p == SPH_PASS_COUNT) { /* no pass at all: sph_sim_step advances the time */
            sph_sim_step(sim);
            break;
        }
        pass_ms[p] += t / rounds;
    }
    return total;
}

static void print_times(const char *name, double *v, int n)
{
    double least = v[0], largest = v[0], sum = 0;
    for (int r = 0; r < n; r++) {
        least = fmin(least, v[r]);
        largest = fmax(largest, v[r]);
        sum += v[r];
    }
    const double mean = sum / n, med = bench_median(v, n);
    printf("%-5s  median %9.2f ms  (least %9.2f, largest %9.2f)  mean %9.2f ms\n", name, med, least, largest, mean);
}

/* Largest |a - b| over the particles of a field (vector fields: every axis),
 * particle by particle: b_at[id] is where particle id is held in b (two
 * levels that rebuild on different steps hold the particles in different
 * orders). */
static double field_gap(uint32_t n, const uint32_t *a_id, const uint32_t *b_at, float *const fa[3],
                        float *const fb[3], int dims)
{
    double gap = 0;
    for (int d = 0; d < dims; d++)
        for (uint32_t i = 0; i < n; i++) gap = fmax(gap, fabs((double)fa[d][i] - fb[d][b_at[a_id[i]]]));
    return gap;
}

int bench_cmd_pair(bench_opts *o)
{
    if (o->nsel != 2 || !o->levels) {
        fprintf(stderr, "sphlab bench pair: --levels: name two levels (e.g. --levels L12,L13)\n");
        return 2;
    }
    const int rounds = o->repeats > 0 ? o->repeats : o->quick ? 3 : 15;
    const int k = bench_k_near(o->cfg.dim, o->at);
    const int threads = o->threads > 0 ? o->threads : 1;
    const bool wall = threads > 1; /* a thread's CPU time would count one thread's share only */
    const bench_level *L[2] = {&bench_levels[o->sel[0]], &bench_levels[o->sel[1]]};
    sph_sim *sim[2] = {NULL, NULL};
    double *ms = calloc(2 * (size_t)rounds, sizeof *ms);
    double pass_ms[2][SPH_PASS_COUNT];
    memset(pass_ms, 0, sizeof pass_ms);
    int rc = 0;
    if (!ms) {
        fprintf(stderr, "sphlab bench pair: out of memory\n");
        return 1;
    }
    for (int s = 0; s < 2 && rc == 0; s++) {
        char why[600];
        sph_scene_def def;
        sph_error err;
        if (bench_level_gl(L[s])) {
            fprintf(stderr, "sphlab bench pair: %s is a GL level: pair compares CPU levels on one thread\n",
                    L[s]->name);
            rc = 2;
        } else if (!bench_scene_def(&o->cfg, L[s], k, false, &def, why, sizeof why)) {
            fprintf(stderr, "sphlab bench pair: %s: %s\n", L[s]->name, why);
            rc = 1;
        } else if (sph_sim_create(&def, threads, &sim[s], &err) != SPH_ERR_OK) {
            fprintf(stderr, "sphlab bench pair: %s: %s\n", L[s]->name, err.msg);
            rc = 1;
        } else {
            sim[s]->watchdog = o->cfg.watchdog;
        }
    }
    if (rc == 0) {
        char date[64];
        double load0[3], load1[3];
        bench_now_iso(date, sizeof date);
        bench_loadavg(load0);
        for (int s = 0; s < 2; s++) sph_sim_step(sim[s]); /* untimed: the first build, the first touch of memory */
        const uint64_t builds0[2] = {sim[0]->S.builds, sim[1]->S.builds}; /* the timed steps' builds are counted */
        for (int r = 0; r < rounds; r++) {
            bench_progress("round %d of %d", r + 1, rounds);
            for (int t = 0; t < 2; t++) {
                const int s = r % 2 ? 1 - t : t; /* A B, then B A */
                ms[(size_t)s * (size_t)rounds + (size_t)r] = step_timed(sim[s], pass_ms[s], rounds, wall);
            }
        }
        bench_progress_done();
        bench_loadavg(load1);
        printf("sphlab bench pair: %s, N = %u, %dD, %d thread%s, %d round%s after one untimed step, load %.2f -> "
               "%.2f\n",
               date, sim[0]->n, o->cfg.dim, threads, threads > 1 ? "s" : "", rounds, rounds > 1 ? "s" : "", load0[0],
               load1[0]);
        printf("%s per step:\n", wall ? "wall time" : "thread CPU time");
        double med[2];
        for (int s = 0; s < 2; s++) {
            print_times(L[s]->name, ms + (size_t)s * (size_t)rounds, rounds); /* sorts: median below */
            med[s] = bench_median(ms + (size_t)s * (size_t)rounds, rounds);
        }
        printf("ratio of the medians %s / %s: x%.2f\n", L[0]->name, L[1]->name, med[0] / med[1]);
        printf("mean %s ms per pass:\n", wall ? "wall" : "thread CPU");
        for (int p = 0; p < SPH_PASS_COUNT; p++) {
            if (pass_ms[0][p] < 0.05 && pass_ms[1][p] < 0.05) continue;
            printf("  %-16s %9.2f %9.2f  x%.2f\n", sph_passes[p]->name, pass_ms[0][p], pass_ms[1][p],
                   pass_ms[1][p] > 0 ? pass_ms[0][p] / pass_ms[1][p] : NAN);
        }
        printf("list builds in the %d timed step%s: %s %llu, %s %llu (and one each in the untimed first step)\n", rounds,
               rounds > 1 ? "s" : "", L[0]->name, (unsigned long long)(sim[0]->S.builds - builds0[0]), L[1]->name,
               (unsigned long long)(sim[1]->S.builds - builds0[1]));
        const sph_particles *A = &sim[0]->P, *B = &sim[1]->P;
        const int dim = sim[0]->dim;
        float *const ra[3] = {A->rho, NULL, NULL}, *const rb[3] = {B->rho, NULL, NULL};
        const uint32_t n = sim[0]->n;
        uint32_t *b_at = malloc((size_t)n * sizeof *b_at);
        bool ids = b_at && sim[1]->n == n; /* ids are the indices at creation: 0 .. n - 1 */
        for (uint32_t i = 0; ids && i < n; i++) {
            ids = A->id[i] < n && B->id[i] < n;
            if (ids) b_at[B->id[i]] = i;
        }
        if (!ids) {
            fprintf(stderr, "sphlab bench pair: the two states could not be compared (%s)\n",
                    b_at ? "their particles' ids differ" : "out of memory");
            rc = 1;
        } else {
            printf("after %d steps: |dx| <= %.3g m, |dv| <= %.3g m/s, |drho| <= %.3g kg/m^3 (particles matched by id)\n",
                   rounds + 1, field_gap(n, A->id, b_at, A->pos, B->pos, dim),
                   field_gap(n, A->id, b_at, A->vel, B->vel, dim), field_gap(n, A->id, b_at, ra, rb, 1));
        }
        free(b_at);
    }
    for (int s = 0; s < 2; s++) sph_sim_destroy(sim[s]);
    free(ms);
    return rc;
}
