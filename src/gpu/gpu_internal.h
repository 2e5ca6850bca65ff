/* Shared by the GL backend's files (not an interface of the module): its
 * state, its buffer bindings and programs, the table of passes and the
 * small GL helpers every dispatch uses.
 *
 *   gpu_backend.c  creation, buffers, host copies, the drawer's calls
 *   gpu_program.c  the scene's constants and field buffers as GLSL, compiling
 *   gpu_passes.c   the table of passes: one row per pass, and their dispatches */
#ifndef SPH_GPU_INTERNAL_H
#define SPH_GPU_INTERNAL_H

#include <stddef.h>

#include "gl_context.h"
#include "gl_fields.h"
#include "gpu.h"
#include "sph_search.h"

#define WG 128 /* invocations per work group */

/* Binding points of the shader storage buffers. The first ones are the
 * registry's fields, one buffer each, in SPH_FIELDS order (B_POS = 0 ...: a
 * field's binding is its number); then the ids, the index and its scratch,
 * the reductions, the wall table, SRC, DST, SCAN and SUMS, bound to
 * whichever buffer a gather or prefix sum works on, and CSF, the csf pass's
 * scratch between its two sweeps (surface density, raw curvature). */
#define GPU_OTHER_BINDINGS(X) \
    X(ID) X(ENTRIES) X(SCRATCH) X(START) X(COUNT) X(REDUCE) X(WALL) X(SRC) X(DST) X(SCAN) X(SUMS) X(CSF)
enum {
#define GPU_FIELD_B(ID, name, comps, unit, unit2, kind, made_by, check, colour, label, about) B_##ID,
    SPH_FIELDS(GPU_FIELD_B)
#undef GPU_FIELD_B
#define GPU_B_ENUM(name) B_##name,
    GPU_OTHER_BINDINGS(GPU_B_ENUM)
#undef GPU_B_ENUM
    B_TOTAL
};
_Static_assert((int)B_ID == (int)SPH_FIELD_COUNT, "field bindings are the field numbers");
extern const char *const gpu_other_binding_names[B_TOTAL - SPH_FIELD_COUNT]; /* "ID", "ENTRIES", ... */

/* Programs: one per pass that has a shader of its own (program number = pass
 * number), then the helpers several passes share (shaders/gpu_NAME.comp). */
#define GPU_HELPERS(X) \
    X(bitonic) X(fill) X(histogram) X(scan_block) X(scan_add) X(scatter) X(rank) X(gather) X(reindex) X(range) \
    X(bitonic_local) X(stats) X(stats_sum) X(dfsph_force) X(forces) X(health) X(csf_force) \
    X(pcisph_force) X(wall_extrapolate) X(solver_blend)
enum {
#define GPU_H_ENUM(name) H_##name,
    GPU_HELPERS(GPU_H_ENUM)
#undef GPU_H_ENUM
    H_TOTAL
};
#define PROG_H(name) (SPH_PASS_COUNT + H_##name)
#define PROG_TOTAL (SPH_PASS_COUNT + H_TOTAL)
#define HELPER_BIT(name) (1u << H_##name)

/* Uniforms the programs may have; looked up once per program. */
#define GPU_UNIFORMS(X) X(dt) X(w) X(flip) X(count) X(value) X(point) X(rows) X(gscale) X(damp) X(g0) X(kick) X(bound)
enum {
#define GPU_U_ENUM(name) U_##name,
    GPU_UNIFORMS(GPU_U_ENUM)
#undef GPU_U_ENUM
    U_TOTAL
};

#define MAX_SCAN_LEVELS 8
/* floats of the density kernel's volume-wall tables, the B_WALL buffer (gpu_backend.c) */
#define GPU_WALL_FLOATS (2 * (SPH_WALL_TABLE + 1) + 2 * (SPH_WALL_CORNER + 1) * (SPH_WALL_CORNER + 1))
/* after them, the pressure solvers' wall share and slope (sph_solver_state,
 * src/passes/solver.h), in the same buffer: no binding more for them */
#define GPU_SOLVER_WALL_FLOATS (2 * (SPH_SOLVER_WALL_SAMPLES + 1))
/* after those, the pressure kernel's tables (the same four) and its second
 * moments tn, tt: the walls' pressure force (sph_wall_ghost_accel) */
#define GPU_WALLP_AT (GPU_WALL_FLOATS + GPU_SOLVER_WALL_FLOATS)
#define GPU_WALLP_FLOATS (GPU_WALL_FLOATS + 2 * (SPH_WALL_TABLE + 1))

/* Timer queries (gpu_timing.c): per step, a GL_TIMESTAMP before and after
 * each pass; a ring of steps read back when the device has them. */
#define GPU_TIMER_FRAMES 4   /* steps the device may be behind before timing waits */
#define GPU_TIMER_ENTRIES 48 /* timed pass calls per step (an iterative pass calls several) */
typedef struct gpu_timer_frame {
    uint64_t step;                          /* the step it times (sim->step while it ran) */
    int count;                              /* pass calls timed */
    signed char pass[GPU_TIMER_ENTRIES];    /* each call's pass */
    GLuint q[2 * GPU_TIMER_ENTRIES];        /* before and after each call */
} gpu_timer_frame;
typedef struct gpu_timer {
    bool available;  /* the context counts GL_TIMESTAMP */
    bool on;         /* pass times from the queries (else glFinish and the host clock) */
    bool open;       /* frame[(head + pending) % FRAMES] is being recorded */
    bool recording;  /* a pass's first timestamp is queued, its second not yet */
    int head;        /* the oldest pending frame */
    int pending;     /* frames complete but not read back */
    gpu_timer_frame frame[GPU_TIMER_FRAMES];
} gpu_timer;

typedef struct gpu {
    sph_backend base;     /* first: the core's table */
    sph_glctx *ctx;       /* its own context; NULL when it runs in a shared one */
    sph_glctx *share;     /* the shared context (the window's, the renderer's), or NULL */
    sph_gl_fields fields; /* its buffers for a drawer (sph_gpu_fields) */
    sph_gl gl;
    sph_gl_compute gc;
    uint32_t n, table; /* particles, hash keys */
    int dim;
    GLuint buf[B_TOTAL];      /* 0 where the scene has no such buffer */
    GLuint spare;             /* the reorder pass gathers into this and swaps */
    GLuint levels[MAX_SCAN_LEVELS]; /* totals of each level of the prefix sum */
    GLuint prog[PROG_TOTAL];  /* 0: not needed by this scene */
    GLint loc[PROG_TOTAL][U_TOTAL];
    bool reordered;           /* this step's reorder pass ran (as S->reordered on the CPU) */
    bool pass_sync;           /* glFinish after each pass, so per-pass timings are true */
    GLuint range;             /* a field's min and max, as ordered keys (sph_gpu_field_range) */
    uint64_t downloaded;      /* bytes copied to the host: sph_sim_sync, range reads */
    gpu_timer timer;          /* pass times from timer queries (gpu_timing.c) */
    uint64_t finishes;        /* glFinish calls made by the passes (a debug counter for the tests) */
    GLuint stats_rows, stats_out; /* the statistics' per-group rows and their sum (gpu_stats.c) */
    uint64_t changes;         /* passes run and uploads so far: what the device holds changed */
    uint64_t stats_at;        /* changes + 1 when stats was reduced; 0: never */
    sph_stats stats;          /* the last reduction, read again while nothing changed */
    GLuint health_keys, health_sums; /* the hash health's per-key records and sums (gpu_health.c) */
} gpu;

/* ---- the table of passes (gpu_passes.c) ----------------------------------
 * One row per pass of SPH_PASSES that runs on the device. A pass without a
 * row is refused on GL by name (never run without its shader). */
typedef struct gpu_pass_row {
    /* Its shader (shaders/gpu_NAME.comp, embedded as shader_gpu_NAME_comp),
     * compiled when the pass is in the pipeline; NULL: none of its own. */
    const char *source;
    /* Its dispatches; NULL: its shader once over the particles (a walk over
     * neighbours is told whether the particles are in cell order). */
    void (*run)(gpu *g, sph_sim *sim);
    /* The helper programs it needs for this scene (HELPER_BIT); NULL: none. */
    unsigned (*helpers)(const sph_scene_def *def);
} gpu_pass_row;

extern const gpu_pass_row gpu_pass_rows[SPH_PASS_COUNT];
extern const char *const gpu_helper_names[H_TOTAL];
extern const char *const gpu_helper_sources[H_TOTAL];
extern const char *const gpu_common_source, *const gpu_walk_source, *const gpu_force_terms_source;

/* Runs one pass on the device (the core's sph_backend.run). */
void gpu_run_pass(sph_backend *b, sph_sim *sim, sph_pass_id pass);
/* Which programs the scene's pipeline uses. */
void gpu_needed_programs(const sph_sim *sim, bool need[PROG_TOTAL]);

/* ---- pass times (gpu_timing.c) --------------------------------------------- */

/* Whether the context has timer queries; if so makes them and turns them on.
 * Sets base.collect_times and base.timing either way. */
bool gpu_timer_init(gpu *g);
/* Turns the queries on or off (off: glFinish per pass); sim non-NULL: what
 * is pending is read first. */
void gpu_timer_enable(gpu *g, sph_sim *sim, bool on);
void gpu_timer_free(gpu *g);
/* Around each pass's dispatches. */
void gpu_timer_begin(gpu *g, sph_sim *sim, int pass);
void gpu_timer_end(gpu *g);

/* ---- statistics (gpu_stats.c) ---------------------------------------------- */

/* sph_sim_stats on the device (sph_backend.stats); false if it cannot. */
bool gpu_stats(sph_backend *b, const sph_sim *sim, sph_stats *out);
void gpu_stats_free(gpu *g);

/* ---- hash health (gpu_health.c) -------------------------------------------- */

struct sph_hash_health;
/* sph_sim_hash_health without the neighbour count, on the device
 * (sph_backend.hash_health); false if it cannot. */
bool gpu_hash_health(sph_backend *b, const sph_sim *sim, struct sph_hash_health *out);
void gpu_health_free(gpu *g);

/* ---- programs (gpu_program.c) -------------------------------------------- */

/* The scene's constants as GLSL #defines, put before every program; NULL if out of memory. */
char *gpu_prelude(const gpu *g, const sph_sim *sim);
/* Compiles program p (PROG_*) after the prelude; false with the reason. */
bool gpu_compile(gpu *g, int p, const char *prelude, char *why, size_t n);

/* ---- GL helpers ----------------------------------------------------------- */

static inline void gpu_bind(gpu *g, int binding, GLuint b)
{
    g->gc.BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)binding, b);
}

static inline void gpu_current(gpu *g)
{
    /* a caller's context (SDL's) is the caller's to keep current: nothing done */
    sph_glctx_make_current(g->ctx ? g->ctx : g->share);
}

static inline void gpu_use(gpu *g, int p)
{
    g->gl.UseProgram(g->prog[p]);
}

static inline void gpu_set_u(gpu *g, int p, int u, uint32_t v)
{
    if (g->loc[p][u] >= 0) g->gc.Uniform1ui(g->loc[p][u], v);
}

static inline void gpu_set_f(gpu *g, int p, int u, float v)
{
    if (g->loc[p][u] >= 0) g->gl.Uniform1f(g->loc[p][u], v);
}

/* Runs the current program over `items` invocations, then makes its writes
 * visible to the next dispatch and to buffer reads. */
static inline void gpu_dispatch(gpu *g, uint32_t items)
{
    uint32_t groups = (items + WG - 1) / WG;
    if (!groups) return;
    uint32_t gx = groups < 65535 ? groups : 65535, gy = (groups + gx - 1) / gx;
    g->gc.DispatchCompute(gx, gy, 1);
    g->gc.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

static inline void gpu_get(gpu *g, GLuint b, size_t offset, size_t bytes, void *dst)
{
    g->downloaded += bytes;
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    g->gc.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, (GLintptr)offset, (GLsizeiptr)bytes, dst);
}

static inline void gpu_send(gpu *g, GLuint b, size_t offset, size_t bytes, const void *src)
{
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    g->gc.BufferSubData(GL_SHADER_STORAGE_BUFFER, (GLintptr)offset, (GLsizeiptr)bytes, src);
}

#endif
