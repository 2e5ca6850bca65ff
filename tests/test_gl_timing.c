/* The GL backend's pass times from timer queries (src/gpu/gpu_timing.c),
 * on Mesa's llvmpipe through EGL surfaceless: their structure, never their
 * speed. With the queries on, no pass waits for the device (no glFinish);
 * the times of a step come a step later and add up to the step's. */
#define _GNU_SOURCE /* setenv */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu.h"
#include "test_gl_util.h"
#include "test_util.h"

static const char *scene_2d =
    "[scene]\nname=gl timing\ndimension=2\neffects=gravity pressure viscosity walls\njitter=0.2\n"
    "[domain]\nmin=-0.3 -0.2\nmax=0.3 0.4\nwall_damping=0.3\n"
    "[physics]\nnegative_pressure=clamp\nviscosity=0.005\n"
    "[kernels]\nh=0.04\n[time]\ndt=0.001\ncfl=0.4\n"
    "[fluid a]\nmin=-0.3 -0.2\nmax=0.0 0.1\nspacing=0.02\nvelocity=0.5 0\n";


static sph_sim *make_gl(const char *ini)
{
    sph_scene_def def = test_scene(ini);
    def.backend = SPH_BACKEND_GL;
    sph_sim *sim;
    sph_error err;
    cr_assert_eq(sph_sim_create(&def, 2, &sim, &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert(sim->backend, "the GL simulation has no backend");
    return sim;
}

static int passes_run(const sph_sim *sim)
{
    int k = 0;
    for (int p = 0; p < SPH_PASS_COUNT; p++) k += sim->in_pipeline[p] && sim->enabled[p];
    return k;
}

Test(gl_timing, queries_time_every_pass_without_waiting)
{
    need_gl();
    sph_sim *sim = make_gl(scene_2d);
    cr_assert(sim->backend->device_times, "llvmpipe has timer queries (GL_TIMESTAMP)");
    cr_assert(sim->backend->timing && strstr(sim->backend->timing, "timer queries"), "%s",
              sim->backend->timing ? sim->backend->timing : "(none)");
    /* Structure only, never speed: every pass is filed once per step, as a
     * finite, non-negative interval (an end query read before its begin
     * would be negative), and the step window holds their sum. How the
     * device times compare with the host's clock depends on the machine and
     * its load: that belongs to `sphlab bench`, not here. */
    for (int s = 0; s < 5; s++) {
        sph_sim_step(sim);
        sph_sim_collect_times(sim); /* waits for this step's queries */
        cr_assert_eq(sph_gpu_finish_count(sim), 0, "no glFinish with timer queries on");
        double sum = 0;
        for (int p = 0; p < SPH_PASS_COUNT; p++) {
            if (!sim->in_pipeline[p]) continue;
            cr_assert_eq(sim->timing[p].calls, (uint64_t)s + 1, "%s: one call per step", sph_passes[p]->name);
            cr_assert(isfinite(sim->timing[p].last_ms) && sim->timing[p].last_ms >= 0, "%s: %g ms (begin and end "
                      "queries out of order)", sph_passes[p]->name, sim->timing[p].last_ms);
            sum += sim->timing[p].last_ms;
        }
        int window;
        double step_ms = sph_sim_step_ms(sim, &window);
        cr_assert_eq(window, s + 1, "one step in the window per step: %d", window);
        /* bookkeeping: the window files the very sum of the step's passes */
        cr_assert(fabs(sim->step_ms[s] - sum) <= 1e-9 * (1 + sum), "the window holds the step's sum");
        (void)step_ms;
    }
    sph_sim_destroy(sim);
}

Test(gl_timing, times_arrive_a_step_later_without_collecting)
{
    need_gl();
    sph_sim *sim = make_gl(scene_2d);
    cr_assert(sim->backend->device_times);
    sph_sim_step(sim);
    /* the first step's queries are read when the second starts (or later):
     * nothing was filed yet, though every pass counted its call */
    cr_assert_eq(sim->step_ms_count, 0, "no step's times before they are collected");
    cr_assert_eq(sim->timing[SPH_PASS_DENSITY].calls, 1);
    for (int s = 0; s < 6; s++) sph_sim_step(sim);
    cr_assert(sim->step_ms_count >= 1 && sim->step_ms_count <= 6, "%llu steps filed while stepping",
              (unsigned long long)sim->step_ms_count);
    sph_sim_collect_times(sim);
    cr_assert_eq(sim->step_ms_count, 7, "every step filed once collected");
    double total = 0, steps = 0;
    for (int p = 0; p < SPH_PASS_COUNT; p++) total += sim->timing[p].total_ms;
    for (int s = 0; s < 7; s++) steps += sim->step_ms[s];
    cr_assert(fabs(total - steps) <= 1e-9 * (1 + total), "the table's total %.6f is the steps' %.6f", total, steps);
    cr_assert_eq(sph_gpu_finish_count(sim), 0);
    sph_sim_destroy(sim);
}

Test(gl_timing, pass_by_pass_stepping_files_whole_steps)
{
    need_gl();
    sph_sim *sim = make_gl(scene_2d);
    int n = passes_run(sim);
    for (int k = 0; k < 3 * n; k++) sph_sim_step_pass(sim);
    cr_assert_eq(sim->step, 3);
    sph_sim_step_pass(sim); /* the fourth step under way: not filed */
    sph_sim_collect_times(sim);
    cr_assert_eq(sim->step_ms_count, 3, "three complete steps, the fourth still open");
    for (int k = 1; k < n; k++) sph_sim_step_pass(sim);
    sph_sim_collect_times(sim);
    cr_assert_eq(sim->step_ms_count, 4);
    sph_sim_destroy(sim);
}

Test(gl_timing, without_queries_each_pass_waits_and_says_so)
{
    need_gl();
    sph_sim *sim = make_gl(scene_2d);
    cr_assert_not(sph_gpu_set_timer_queries(sim, false));
    cr_assert_not(sim->backend->device_times);
    cr_assert(strstr(sim->backend->timing, "glFinish"), "%s", sim->backend->timing);
    sph_sim_step(sim);
    sph_sim_step(sim);
    cr_assert_eq(sph_gpu_finish_count(sim), (uint64_t)(2 * passes_run(sim)), "one glFinish per pass");
    cr_assert_eq(sim->step_ms_count, 2, "the host clock files each step at once");
    cr_assert(sph_gpu_set_timer_queries(sim, true));
    sph_sim_step(sim);
    sph_sim_collect_times(sim);
    cr_assert_eq(sim->step_ms_count, 3);
    cr_assert_eq(sph_gpu_finish_count(sim), (uint64_t)(2 * passes_run(sim)), "no more waits with queries on");
    sph_sim_destroy(sim);
}
