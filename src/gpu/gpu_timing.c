/* The GL backend's pass times from timer queries: a GL_TIMESTAMP before and
 * after each pass (glQueryCounter), kept per step in a ring of frames and
 * read back when the device has them, a step or more later, so that timing
 * never waits for the device. Without timer queries (a context whose
 * GL_QUERY_COUNTER_BITS for GL_TIMESTAMP is 0) the backend falls back to a
 * glFinish after each pass and the host clock (gpu_passes.c). */
#include <string.h>

#include "gpu_internal.h"

static const char *const timing_queries = "timer queries on the device (GL_TIMESTAMP, read a step later)";
static const char *const timing_finish =
    "the host clock after a glFinish per pass (this context has no timer queries)";

static gpu_timer_frame *frame_at(gpu *g, int k)
{
    return &g->timer.frame[(g->timer.head + k) % GPU_TIMER_FRAMES];
}

/* Files the oldest pending frame's times with the core; false if the device
 * has not finished it and wait is false. */
static bool read_oldest(gpu *g, sph_sim *sim, bool wait)
{
    gpu_timer_frame *f = frame_at(g, 0);
    if (f->count > 0 && !wait) {
        GLint ready = 0;
        g->gc.GetQueryObjectiv(f->q[2 * f->count - 1], GL_QUERY_RESULT_AVAILABLE, &ready);
        if (!ready) return false;
    }
    double ms[SPH_PASS_COUNT];
    for (int p = 0; p < SPH_PASS_COUNT; p++) ms[p] = -1.0;
    for (int k = 0; k < f->count; k++) {
        GLuint64 t0 = 0, t1 = 0; /* [ns] */
        g->gc.GetQueryObjectui64v(f->q[2 * k], GL_QUERY_RESULT, &t0);
        g->gc.GetQueryObjectui64v(f->q[2 * k + 1], GL_QUERY_RESULT, &t1);
        int p = f->pass[k];
        if (ms[p] < 0) ms[p] = 0.0; /* an iterative pass's calls add up */
        ms[p] += t1 > t0 ? (double)(t1 - t0) * 1e-6 : 0.0;
    }
    if (f->count > 0) sph_sim_record_step_times(sim, ms);
    g->timer.head = (g->timer.head + 1) % GPU_TIMER_FRAMES;
    g->timer.pending--;
    return true;
}

/* The frame being recorded is complete once the core has moved to another step. */
static void close_finished(gpu *g, const sph_sim *sim)
{
    if (g->timer.open && frame_at(g, g->timer.pending)->step != sim->step) {
        g->timer.open = false;
        g->timer.pending++;
    }
}

static void collect(sph_backend *b, sph_sim *sim, bool wait)
{
    gpu *g = (gpu *)b;
    if (!g->timer.on) return;
    gpu_current(g);
    close_finished(g, sim);
    while (g->timer.pending > 0 && read_oldest(g, sim, wait)) {
    }
}

bool gpu_timer_init(gpu *g)
{
    GLint bits = 0;
    g->gc.GetQueryiv(GL_TIMESTAMP, GL_QUERY_COUNTER_BITS, &bits);
    while (g->gl.GetError() != GL_NO_ERROR) {
    }
    g->base.collect_times = collect;
    if (bits <= 0) {
        g->base.timing = timing_finish;
        return false;
    }
    for (int k = 0; k < GPU_TIMER_FRAMES; k++) g->gc.GenQueries(2 * GPU_TIMER_ENTRIES, g->timer.frame[k].q);
    g->timer.available = true;
    gpu_timer_enable(g, NULL, true);
    return true;
}

void gpu_timer_enable(gpu *g, sph_sim *sim, bool on)
{
    on = on && g->timer.available;
    if (!on && g->timer.on && sim) collect(&g->base, sim, true); /* what was measured is filed first */
    if (!on) {
        g->timer.open = false;
        g->timer.pending = 0;
    }
    g->timer.on = on;
    g->base.device_times = on;
    g->base.timing = on ? timing_queries : timing_finish;
}

void gpu_timer_free(gpu *g)
{
    if (!g->timer.available) return;
    for (int k = 0; k < GPU_TIMER_FRAMES; k++) g->gc.DeleteQueries(2 * GPU_TIMER_ENTRIES, g->timer.frame[k].q);
}

void gpu_timer_begin(gpu *g, sph_sim *sim, int pass)
{
    if (!g->timer.on) return;
    close_finished(g, sim);
    /* what the device has finished is filed now, without waiting */
    while (g->timer.pending > 0 && read_oldest(g, sim, false)) {
    }
    if (!g->timer.open) {
        /* the ring is full only when the device is GPU_TIMER_FRAMES steps
         * behind the host: then (only) the oldest is waited for */
        if (g->timer.pending == GPU_TIMER_FRAMES) read_oldest(g, sim, true);
        gpu_timer_frame *f = frame_at(g, g->timer.pending);
        f->step = sim->step;
        f->count = 0;
        g->timer.open = true;
    }
    gpu_timer_frame *f = frame_at(g, g->timer.pending);
    if (f->count >= GPU_TIMER_ENTRIES) return; /* more calls in one step than intervals: the rest untimed */
    f->pass[f->count] = (signed char)pass;
    g->gc.QueryCounter(f->q[2 * f->count], GL_TIMESTAMP);
    g->timer.recording = true;
}

void gpu_timer_end(gpu *g)
{
    if (!g->timer.on || !g->timer.recording) return;
    gpu_timer_frame *f = frame_at(g, g->timer.pending);
    g->gc.QueryCounter(f->q[2 * f->count + 1], GL_TIMESTAMP);
    f->count++;
    g->timer.recording = false;
}
