/* The GL compute backend (see gpu.h): buffers, programs, and one function
 * that runs a pass by dispatching its shaders. Each program is compiled for
 * the scene: the host writes the scene's constants as #defines before the
 * shared GLSL (shaders/gpu_common.glsl), floats as their exact bits. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gl_context.h"
#include "gl_fields.h"
#include "gpu.h"
#include "gpu_shaders.h"
#include "sph_search.h"

#define WG 128 /* invocations per work group */

/* Binding points of the shader storage buffers, as in gpu_common.glsl. The
 * first ones are one buffer per particle field; SRC, DST, SCAN and SUMS are
 * bound to whichever buffer a gather or prefix sum works on. */
#define GPU_BINDINGS(X) \
    X(ID) X(MASS) X(POS) X(VEL) X(PRED) X(RHO) X(VOL) X(P) X(PRHO2) X(ACC_P) X(ACC_V) X(ACC_I) \
    X(ENTRIES) X(SCRATCH) X(START) X(COUNT) X(REDUCE) X(WALL) X(SRC) X(DST) X(SCAN) X(SUMS)
enum {
#define GPU_B_ENUM(name) B_##name,
    GPU_BINDINGS(GPU_B_ENUM)
#undef GPU_B_ENUM
    B_TOTAL
};
static const char *const binding_names[B_TOTAL] = {
#define GPU_B_NAME(name) "B_" #name,
    GPU_BINDINGS(GPU_B_NAME)
#undef GPU_B_NAME
};

/* Programs: shaders/gpu_NAME.comp; `walk` marks those that visit neighbours. */
#define GPU_PROGRAMS(X)                                                                                    \
    X(external, 0) X(hash, 0) X(bitonic, 0) X(fill, 0) X(histogram, 0) X(scan_block, 0) X(scan_add, 0)     \
    X(scatter, 0) X(rank, 0) X(gather, 0) X(reindex, 0) X(offsets, 0) X(density, 1) X(pressure, 0)          \
    X(pressure_force, 1) X(viscosity, 1) X(interaction, 0) X(integrate, 0) X(walls, 0) X(range, 0)
enum {
#define GPU_P_ENUM(name, walk) PROG_##name,
    GPU_PROGRAMS(GPU_P_ENUM)
#undef GPU_P_ENUM
    PROG_TOTAL
};
static const char *const program_names[PROG_TOTAL] = {
#define GPU_P_NAME(name, walk) #name,
    GPU_PROGRAMS(GPU_P_NAME)
#undef GPU_P_NAME
};
static const char *const program_sources[PROG_TOTAL] = {
#define GPU_P_SRC(name, walk) shader_gpu_##name##_comp,
    GPU_PROGRAMS(GPU_P_SRC)
#undef GPU_P_SRC
};

/* Uniforms the programs may have; looked up once per program. */
#define GPU_UNIFORMS(X) X(dt) X(w) X(flip) X(count) X(value) X(point) X(rows)
enum {
#define GPU_U_ENUM(name) U_##name,
    GPU_UNIFORMS(GPU_U_ENUM)
#undef GPU_U_ENUM
    U_TOTAL
};
static const char *const uniform_names[U_TOTAL] = {
#define GPU_U_NAME(name) "u_" #name,
    GPU_UNIFORMS(GPU_U_NAME)
#undef GPU_U_NAME
};

#define MAX_SCAN_LEVELS 8

typedef struct gpu {
    sph_backend base; /* first: the core's table */
    sph_glctx *ctx;           /* its own context; NULL when it runs in a shared one */
    sph_glctx *share;         /* the shared context (the window's, the renderer's), or NULL */
    sph_gl_fields fields;     /* its buffers for a drawer (sph_gpu_fields) */
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
} gpu;

/* ---- set-up --------------------------------------------------------------- */

typedef struct text {
    char *s;
    size_t len, cap;
    bool failed;
} text;

static void put(text *t, const char *fmt, ...) __attribute__((format(printf, 2, 3)));
static void put(text *t, const char *fmt, ...)
{
    for (;;) {
        va_list ap;
        va_start(ap, fmt);
        int k = vsnprintf(t->s ? t->s + t->len : NULL, t->s ? t->cap - t->len : 0, fmt, ap);
        va_end(ap);
        if (k < 0) {
            t->failed = true;
            return;
        }
        if (t->s && t->len + (size_t)k < t->cap) {
            t->len += (size_t)k;
            return;
        }
        size_t cap = t->cap ? t->cap * 2 : 4096;
        while (cap < t->len + (size_t)k + 1) cap *= 2;
        char *s = realloc(t->s, cap);
        if (!s) {
            t->failed = true;
            return;
        }
        t->s = s;
        t->cap = cap;
    }
}

/* A float as GLSL that has exactly its bits (a decimal literal would be
 * rounded by the shader compiler, perhaps not as the C compiler did). */
static void put_float(text *t, const char *name, float v)
{
    uint32_t u;
    memcpy(&u, &v, sizeof u);
    put(t, "#define %s uintBitsToFloat(0x%08xu)\n", name, u);
}

static void put_vec3(text *t, const char *name, const float v[3])
{
    uint32_t u[3];
    memcpy(u, v, sizeof u);
    put(t, "#define %s vec3(uintBitsToFloat(0x%08xu), uintBitsToFloat(0x%08xu), uintBitsToFloat(0x%08xu))\n", name,
        u[0], u[1], u[2]);
}

/* The scene's constants, put before gpu_common.glsl in every program. */
static char *prelude(const gpu *g, const sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    const sph_cells *c = &sim->S.cells;
    const sph_particles *P = &sim->P;
    text t = {0};
    put(&t, "#version 430\n#define WG %d\n#define N %uu\n#define T %uu\n#define DIM %d\n#define WALL_TABLE %d\n", WG,
        g->n, g->table, g->dim, SPH_WALL_TABLE);
    for (int b = 0; b < B_TOTAL; b++) put(&t, "#define %s %d\n", binding_names[b], b);
    put_float(&t, "H", def->h);
    put_float(&t, "H2", def->h * def->h);
    put_float(&t, "INV_H", sim->k_density.inv_h);
    put_float(&t, "R_MIN", SPH_KERNEL_R_MIN * def->h);
    put(&t, "#define KD %d\n#define KP %d\n#define KV %d\n", (int)sim->k_density.kind, (int)sim->k_pressure.kind,
        (int)sim->k_viscosity.kind);
    put_float(&t, "SIG_D", sim->k_density.sigma);
    put_float(&t, "SIG_P", sim->k_pressure.sigma);
    put_float(&t, "SIG_V", sim->k_viscosity.sigma);
    put_float(&t, "M2_V", sim->k_viscosity.m2);
    put_vec3(&t, "CELL_ORIGIN", c->origin);
    put_vec3(&t, "CELL_INV", c->inv_size);
    put(&t, "#define CELL_COUNT ivec3(%d, %d, %d)\n", c->count[0], c->count[1], c->count[2]);
    put(&t, "#define CELL_WRAP ivec3(%d, %d, %d)\n", c->wrap[0], c->wrap[1], c->wrap[2]);
    put(&t, "#define DENSE %d\n#define SEARCH_BRUTE %d\n", c->dense, def->search == SPH_SEARCH_BRUTE);
    put(&t, "#define PERIODIC %d\n", sph_sim_periodic(sim));
    put_vec3(&t, "PER", sim->period);
    put_vec3(&t, "INV_PER", sim->inv_period);
    put_vec3(&t, "DOM_MIN", sim->def.domain_min);
    put_vec3(&t, "DOM_MAX", sim->def.domain_max);
    put(&t, "#define HAS_GRAVITY %d\n", (def->effects & SPH_EFFECT(GRAVITY)) != 0);
    put_vec3(&t, "GRAVITY", sim->def.gravity);
    put(&t, "#define HAS_PRED %d\n#define HAS_ACC_P %d\n#define HAS_ACC_V %d\n#define HAS_ACC_I %d\n", P->pred[0] != NULL,
        P->acc_p[0] != NULL, P->acc_v[0] != NULL, P->acc_i[0] != NULL);
    put(&t, "#define WALL_VOLUME %d\n", sph_sim_wall_volume(sim));
    put_float(&t, "RHO0", def->rest_density);
    put_float(&t, "STIFF", def->stiffness);
    put(&t, "#define EOS_TAIT %d\n#define CLAMP_NEG %d\n", def->eos == SPH_EOS_TAIT,
        def->negative_pressure == SPH_NEGP_CLAMP);
    put_float(&t, "GAMMA", def->tait_gamma);
    put_float(&t, "TAIT_B", def->stiffness * def->rest_density / def->tait_gamma);
    /* the form as its enum value: the shader names each one it implements and
     * stops with #error on any other, so a form added on the CPU is never
     * silently computed as another on GL */
    put(&t, "#define PFORM_SYM %d\n#define VFORM %d\n#define VFORM_LAPLACIAN %d\n#define VFORM_SMOOTHING %d\n"
            "#define VFORM_MORRIS %d\n",
        def->pressure_form == SPH_PFORM_SYMMETRIC, (int)def->viscosity_form, (int)SPH_VFORM_LAPLACIAN,
        (int)SPH_VFORM_SMOOTHING, (int)SPH_VFORM_MORRIS);
    put_float(&t, "NU", def->viscosity);
    put_float(&t, "DAMP", def->wall_damping);
    put_float(&t, "INTER_R", def->interaction_radius);
    if (t.failed) {
        free(t.s);
        return NULL;
    }
    return t.s;
}

static bool compile(gpu *g, int p, const char *pre, char *why, size_t n)
{
    sph_gl *gl = &g->gl;
    /* "#include_walk" in a pass's source stands for gpu_walk.glsl */
    const char *src = program_sources[p], *mark = strstr(src, "#include_walk\n");
    /* The buffers the pass declares: its first line, "// uses: POS VEL ...";
     * only those that exist in this scene, or are bound per dispatch. */
    char uses[512] = "";
    size_t used = 0;
    const char *line = strstr(src, "// uses:"), *eol = line ? strchr(line, '\n') : NULL;
    for (int b = 0; line && eol && b < B_TOTAL; b++) {
        const char *name = binding_names[b] + 2, *at = line;
        size_t len = strlen(name);
        bool listed = false;
        while ((at = strstr(at, name)) && at < eol) {
            if (at[-1] == ' ' && (at[len] == ' ' || at[len] == '\n')) listed = true;
            at += len;
        }
        bool dynamic = b == B_SRC || b == B_DST || b == B_SCAN || b == B_SUMS;
        if (listed && (g->buf[b] || dynamic))
            used += (size_t)snprintf(uses + used, sizeof uses - used, "#define USE_%s 1\n", name);
    }
    const char *parts[6] = {pre, uses, shader_gpu_common_glsl, src, "", ""};
    GLint lens[6] = {-1, -1, -1, -1, -1, -1};
    int count = 4;
    if (mark) {
        lens[3] = (GLint)(mark - src);
        parts[4] = shader_gpu_walk_glsl;
        parts[5] = mark + strlen("#include_walk\n");
        count = 6;
    }
    const sph_gl_stage stage = {GL_COMPUTE_SHADER, count, parts, lens};
    char what[96];
    snprintf(what, sizeof what, "shaders/gpu_%s.comp", program_names[p]);
    GLuint prog = sph_gl_program(gl, &stage, 1, what, why, n);
    if (!prog) return false;
    g->prog[p] = prog;
    for (int u = 0; u < U_TOTAL; u++) g->loc[p][u] = gl->GetUniformLocation(prog, uniform_names[u]);
    return true;
}

static GLuint new_buffer(gpu *g, size_t bytes, const void *data)
{
    GLuint b = 0;
    g->gl.GenBuffers(1, &b);
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    g->gl.BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(bytes ? bytes : 4), data, GL_DYNAMIC_COPY);
    return b;
}

static void bind(gpu *g, int binding, GLuint b)
{
    g->gc.BindBufferBase(GL_SHADER_STORAGE_BUFFER, (GLuint)binding, b);
}

static void current(gpu *g)
{
    /* a caller's context (SDL's) is the caller's to keep current: nothing done */
    sph_glctx_make_current(g->ctx ? g->ctx : g->share);
}

/* ---- dispatch ------------------------------------------------------------- */

static void use(gpu *g, int p)
{
    g->gl.UseProgram(g->prog[p]);
}

static void set_u(gpu *g, int p, int u, uint32_t v)
{
    if (g->loc[p][u] >= 0) g->gc.Uniform1ui(g->loc[p][u], v);
}

static void set_f(gpu *g, int p, int u, float v)
{
    if (g->loc[p][u] >= 0) g->gl.Uniform1f(g->loc[p][u], v);
}

/* Runs the current program over `items` invocations, then makes its writes
 * visible to the next dispatch and to buffer reads. */
static void dispatch(gpu *g, uint32_t items)
{
    uint32_t groups = (items + WG - 1) / WG;
    if (!groups) return;
    uint32_t gx = groups < 65535 ? groups : 65535, gy = (groups + gx - 1) / gx;
    g->gc.DispatchCompute(gx, gy, 1);
    g->gc.MemoryBarrier(GL_SHADER_STORAGE_BARRIER_BIT | GL_BUFFER_UPDATE_BARRIER_BIT);
}

static void fill(gpu *g, GLuint b, uint32_t count, uint32_t value)
{
    use(g, PROG_fill);
    bind(g, B_SCAN, b);
    set_u(g, PROG_fill, U_count, count);
    set_u(g, PROG_fill, U_value, value);
    dispatch(g, count);
}

/* Inclusive prefix sum of count values of b, in place. */
static void scan(gpu *g, GLuint b, uint32_t count, int level)
{
    use(g, PROG_scan_block);
    bind(g, B_SCAN, b);
    bind(g, B_SUMS, g->levels[level]);
    set_u(g, PROG_scan_block, U_count, count);
    dispatch(g, count);
    uint32_t groups = (count + WG - 1) / WG;
    if (groups <= 1) return;
    scan(g, g->levels[level], groups, level + 1);
    use(g, PROG_scan_add);
    bind(g, B_SCAN, b);
    bind(g, B_SUMS, g->levels[level]);
    set_u(g, PROG_scan_add, U_count, count);
    dispatch(g, count);
}

static void sort_bitonic(gpu *g)
{
    uint32_t P = 1;
    while (P < g->n) P <<= 1;
    use(g, PROG_bitonic);
    set_u(g, PROG_bitonic, U_count, P / 2);
    for (uint32_t w0 = 1; w0 < P; w0 <<= 1)
        for (uint32_t w = w0; w >= 1; w >>= 1) {
            set_u(g, PROG_bitonic, U_w, w);
            set_u(g, PROG_bitonic, U_flip, w == w0);
            dispatch(g, P / 2);
        }
}

/* Counting sort with a prefix sum: histogram of keys, inclusive scan (each
 * key's first slot), atomic scatter, then each run put in index order. */
static void sort_counting(gpu *g)
{
    fill(g, g->buf[B_COUNT], g->table + 1, 0);
    use(g, PROG_histogram);
    dispatch(g, g->n);
    scan(g, g->buf[B_COUNT], g->table + 1, 0);
    use(g, PROG_scatter);
    dispatch(g, g->n);
    use(g, PROG_rank);
    dispatch(g, g->n);
}

static void reorder(gpu *g)
{
    static const int fields[] = {B_ID, B_MASS, B_POS, B_VEL, B_PRED};
    use(g, PROG_gather);
    for (size_t f = 0; f < sizeof fields / sizeof fields[0]; f++) {
        int b = fields[f];
        if (!g->buf[b]) continue;
        bind(g, B_SRC, g->buf[b]);
        bind(g, B_DST, g->spare);
        set_u(g, PROG_gather, U_count, b == B_ID || b == B_MASS ? 1u : (uint32_t)g->dim);
        dispatch(g, g->n);
        GLuint t = g->buf[b]; /* the gathered copy becomes the field; the old one the spare */
        g->buf[b] = g->spare;
        g->spare = t;
        bind(g, b, g->buf[b]);
    }
    use(g, PROG_reindex);
    dispatch(g, g->n);
    g->reordered = true;
}

static void integrate(gpu *g, sph_sim *sim)
{
    static const uint32_t zero[4] = {0, 0, 0, 0};
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, g->buf[B_REDUCE]);
    g->gc.BufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof zero, zero);
    use(g, PROG_integrate);
    set_f(g, PROG_integrate, U_dt, sim->dt);
    dispatch(g, g->n);
    /* the only read-back of a step: two floats for the CFL step and the watchdog */
    uint32_t bits[2] = {0x7fc00000u, 0x7fc00000u}; /* NaN if the read fails: the watchdog stops the run */
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, g->buf[B_REDUCE]);
    g->gc.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, sizeof bits, bits);
    float v2, a2, g2 = 0;
    memcpy(&v2, &bits[0], sizeof v2);
    memcpy(&a2, &bits[1], sizeof a2);
    if (sim->def.effects & SPH_EFFECT(GRAVITY))
        for (int d = 0; d < sim->dim; d++) g2 += sim->def.gravity[d] * sim->def.gravity[d];
    sim->max_speed = sqrtf(v2);
    sim->max_acc = sqrtf(a2) + sqrtf(g2);
}

/* Storage buffer bindings are the context's state, not the program's: in an
 * shared context another simulation (a reset or a variant switch in the
 * window) may have rebound them, or unbound them by deleting its buffers. */
static void rebind(gpu *g)
{
    for (int k = 0; k < B_TOTAL; k++)
        if (g->buf[k]) bind(g, k, g->buf[k]);
}

static void run(sph_backend *b, sph_sim *sim, sph_pass_id pass)
{
    gpu *g = (gpu *)b;
    current(g);
    if (g->share) rebind(g);
    int simple = -1; /* a pass that is one dispatch over the particles */
    switch (pass) {
    case SPH_PASS_EXTERNAL:
        use(g, PROG_external);
        set_f(g, PROG_external, U_dt, sim->dt);
        dispatch(g, g->n);
        break;
    case SPH_PASS_HASH:
        g->reordered = false;
        simple = PROG_hash;
        break;
    case SPH_PASS_SORT:
        if (sim->def.sort == SPH_SORT_BITONIC)
            sort_bitonic(g);
        else
            sort_counting(g);
        break;
    case SPH_PASS_REORDER: reorder(g); break;
    case SPH_PASS_OFFSETS:
        fill(g, g->buf[B_START], g->table, SPH_EMPTY);
        simple = PROG_offsets;
        break;
    case SPH_PASS_NEIGHBOURS: break; /* the force passes walk the cells themselves (gpu_walk.glsl) */
    case SPH_PASS_DENSITY: simple = PROG_density; break;
    case SPH_PASS_PRESSURE: simple = PROG_pressure; break;
    case SPH_PASS_PRESSURE_FORCE: simple = PROG_pressure_force; break;
    case SPH_PASS_VISCOSITY: simple = PROG_viscosity; break;
    case SPH_PASS_INTERACTION:
        use(g, PROG_interaction);
        set_u(g, PROG_interaction, U_count, sim->interaction_active);
        set_f(g, PROG_interaction, U_value, sim->def.interaction_strength * sim->interaction_sign);
        if (g->loc[PROG_interaction][U_point] >= 0)
            g->gl.Uniform3f(g->loc[PROG_interaction][U_point], sim->interaction_point[0], sim->interaction_point[1],
                            sim->interaction_point[2]);
        dispatch(g, g->n);
        break;
    case SPH_PASS_INTEGRATE: integrate(g, sim); break;
    case SPH_PASS_WALLS: simple = PROG_walls; break;
    default: /* check_scene refuses a pipeline with a pass not listed here */
        fprintf(stderr, "sphlab: the GL backend has no pass %d (%s)\n", (int)pass,
                (unsigned)pass < SPH_PASS_COUNT ? sph_passes[pass]->name : "unknown");
        abort();
    }
    if (simple >= 0) {
        use(g, simple);
        /* the walk's row runs need this step's particles in cell order (the
         * reorder pass may be switched off in the window) */
        set_u(g, simple, U_rows, g->reordered && sim->S.cells.dense);
        dispatch(g, g->n);
    }
    if (g->pass_sync) g->gl.Finish();
}

/* ---- host copies ---------------------------------------------------------- */

static void get(gpu *g, GLuint b, size_t offset, size_t bytes, void *dst)
{
    g->downloaded += bytes;
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    g->gc.GetBufferSubData(GL_SHADER_STORAGE_BUFFER, (GLintptr)offset, (GLsizeiptr)bytes, dst);
}

static void send(gpu *g, GLuint b, size_t offset, size_t bytes, const void *src)
{
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    g->gc.BufferSubData(GL_SHADER_STORAGE_BUFFER, (GLintptr)offset, (GLsizeiptr)bytes, src);
}

/* The host arrays of a particle field and its buffer binding. */
static int field_arrays(sph_sim *sim, int f, float ***vec, float **scalar)
{
    sph_particles *P = &sim->P;
    *vec = NULL;
    *scalar = NULL;
    switch (f) {
    case SPH_FIELD_POS: *vec = P->pos; return B_POS;
    case SPH_FIELD_VEL: *vec = P->vel; return B_VEL;
    case SPH_FIELD_PRED: *vec = P->pred; return B_PRED;
    case SPH_FIELD_RHO: *scalar = P->rho; return B_RHO;
    case SPH_FIELD_VOL: *scalar = P->vol; return B_VOL;
    case SPH_FIELD_P: *scalar = P->p; return B_P;
    case SPH_FIELD_PRHO2: *scalar = P->p_rho2; return B_PRHO2;
    case SPH_FIELD_ACC_P: *vec = P->acc_p; return B_ACC_P;
    case SPH_FIELD_ACC_V: *vec = P->acc_v; return B_ACC_V;
    case SPH_FIELD_ACC_I: *vec = P->acc_i; return B_ACC_I;
    case SPH_FIELD_MASS: *scalar = P->mass; return B_MASS;
    default: return -1;
    }
}

static void download(sph_backend *b, sph_sim *sim, sph_mask what)
{
    gpu *g = (gpu *)b;
    current(g);
    const size_t row = (size_t)g->n * sizeof(float);
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        if (!(what & SPH_SYNC_FIELD(f))) continue;
        float **vec, *scalar;
        int bi = field_arrays(sim, f, &vec, &scalar);
        if (bi < 0 || !g->buf[bi]) continue;
        if (scalar) get(g, g->buf[bi], 0, row, scalar);
        for (int d = 0; vec && d < g->dim; d++)
            if (vec[d]) get(g, g->buf[bi], (size_t)d * row, row, vec[d]);
    }
    if (what & SPH_SYNC_ID) get(g, g->buf[B_ID], 0, (size_t)g->n * sizeof(uint32_t), sim->P.id);
    sph_search_data *S = &sim->S;
    if ((what & SPH_SYNC_INDEX) && g->buf[B_ENTRIES]) {
        get(g, g->buf[B_ENTRIES], 0, (size_t)g->n * sizeof(sph_entry), S->entries);
        get(g, g->buf[B_START], 0, (size_t)g->table * sizeof(uint32_t), S->start);
        S->reordered = g->reordered;
        if (g->reordered && S->cell_hash)
            for (uint32_t k = 0; k < g->n; k++) S->cell_hash[k] = S->entries[k].hash;
    }
    /* The lists exist only on the host: built from the index the device made,
     * by the CPU's own neighbour pass, for the overlays and the inspector. */
    if ((what & SPH_SYNC_LISTS) && sim->in_pipeline[SPH_PASS_NEIGHBOURS] && sim->timing[SPH_PASS_NEIGHBOURS].calls)
        sph_passes[SPH_PASS_NEIGHBOURS]->run(sim);
}

static void upload(sph_backend *b, sph_sim *sim)
{
    gpu *g = (gpu *)b;
    current(g);
    const size_t row = (size_t)g->n * sizeof(float);
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        float **vec, *scalar;
        int bi = field_arrays(sim, f, &vec, &scalar);
        if (bi < 0 || !g->buf[bi]) continue;
        if (scalar) send(g, g->buf[bi], 0, row, scalar);
        for (int d = 0; vec && d < g->dim; d++)
            if (vec[d]) send(g, g->buf[bi], (size_t)d * row, row, vec[d]);
    }
    send(g, g->buf[B_ID], 0, (size_t)g->n * sizeof(uint32_t), sim->P.id);
}

static void destroy(sph_backend *b)
{
    gpu *g = (gpu *)b;
    if (!g) return;
    if (g->ctx || g->share) {
        current(g);
        for (int p = 0; p < PROG_TOTAL; p++)
            if (g->prog[p]) g->gl.DeleteProgram(g->prog[p]);
        for (int i = 0; i < B_TOTAL; i++)
            if (g->buf[i]) g->gl.DeleteBuffers(1, &g->buf[i]);
        if (g->spare) g->gl.DeleteBuffers(1, &g->spare);
        for (int l = 0; l < MAX_SCAN_LEVELS; l++)
            if (g->levels[l]) g->gl.DeleteBuffers(1, &g->levels[l]);
        if (g->range) g->gl.DeleteBuffers(1, &g->range);
        sph_glctx_destroy(g->ctx);
    }
    free(g);
}

/* ---- creation ------------------------------------------------------------- */

/* Scene options the shaders do not implement: refused by key and value. */
static sph_error_code check_scene(const sph_sim *sim, sph_error *err)
{
    const sph_scene_def *def = &sim->def;
    /* the passes run() dispatches; a pass added to the pipeline without a
     * shader is refused here rather than skipped on the device */
    static const sph_pass_id has[] = {SPH_PASS_EXTERNAL,  SPH_PASS_HASH,       SPH_PASS_SORT,
                                      SPH_PASS_REORDER,   SPH_PASS_OFFSETS,    SPH_PASS_NEIGHBOURS,
                                      SPH_PASS_DENSITY,   SPH_PASS_PRESSURE,   SPH_PASS_PRESSURE_FORCE,
                                      SPH_PASS_VISCOSITY, SPH_PASS_INTERACTION, SPH_PASS_INTEGRATE,
                                      SPH_PASS_WALLS};
    for (int p = 0; p < SPH_PASS_COUNT; p++) {
        bool found = false;
        for (size_t k = 0; k < sizeof has / sizeof has[0]; k++) found |= has[k] == (sph_pass_id)p;
        if (sim->in_pipeline[p] && !found)
            return sph_fail(err, SPH_ERR_SCENE, "%s: the GL backend has no %s pass (the scene needs it)", def->file,
                            sph_passes[p]->name);
    }
    if (sim->in_pipeline[SPH_PASS_SORT] && def->sort != SPH_SORT_BITONIC && def->sort != SPH_SORT_COUNTING)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] sort = %s is not implemented by the GL backend (accepted there: bitonic, "
                        "counting)",
                        def->file, sph_sort_names[def->sort]);
    if (def->search != SPH_SEARCH_BRUTE && def->sort == SPH_SORT_NONE && sph_scene_needs_neighbours(def))
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] sort = none is not implemented by the GL backend (accepted there: bitonic, "
                        "counting)",
                        def->file);
    if (def->accumulate == SPH_ACC_DOUBLE && sph_scene_needs_density(def))
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [physics] accumulate = double is not implemented by the GL backend (accepted there: "
                        "float)",
                        def->file);
    return SPH_ERR_OK;
}

/* Which programs the scene's pipeline uses. */
static void needed_programs(const sph_sim *sim, bool need[PROG_TOTAL])
{
    const bool *in = sim->in_pipeline;
    memset(need, 0, PROG_TOTAL * sizeof *need);
    need[PROG_fill] = true;
    need[PROG_integrate] = true;
    need[PROG_range] = true;
    need[PROG_external] = in[SPH_PASS_EXTERNAL];
    need[PROG_hash] = in[SPH_PASS_HASH];
    if (in[SPH_PASS_SORT]) {
        bool bitonic = sim->def.sort == SPH_SORT_BITONIC;
        need[PROG_bitonic] = bitonic;
        need[PROG_histogram] = need[PROG_scan_block] = need[PROG_scan_add] = !bitonic;
        need[PROG_scatter] = need[PROG_rank] = !bitonic;
    }
    need[PROG_gather] = need[PROG_reindex] = in[SPH_PASS_REORDER];
    need[PROG_offsets] = in[SPH_PASS_OFFSETS];
    need[PROG_density] = in[SPH_PASS_DENSITY];
    need[PROG_pressure] = in[SPH_PASS_PRESSURE];
    need[PROG_pressure_force] = in[SPH_PASS_PRESSURE_FORCE];
    need[PROG_viscosity] = in[SPH_PASS_VISCOSITY];
    need[PROG_interaction] = in[SPH_PASS_INTERACTION];
    need[PROG_walls] = in[SPH_PASS_WALLS];
}

static bool make_buffers(gpu *g, const sph_sim *sim)
{
    const sph_particles *P = &sim->P;
    const size_t n = g->n, row = n * sizeof(float), vec = (size_t)g->dim * row;
    /* id and mass take a vector's size: the reorder pass swaps any gathered
     * field with the spare, which must then hold any of them */
    g->buf[B_ID] = new_buffer(g, vec, NULL);
    g->buf[B_MASS] = new_buffer(g, vec, NULL);
    g->buf[B_POS] = new_buffer(g, vec, NULL);
    g->buf[B_VEL] = new_buffer(g, vec, NULL);
    if (P->pred[0]) g->buf[B_PRED] = new_buffer(g, vec, NULL);
    if (P->rho) g->buf[B_RHO] = new_buffer(g, row, NULL);
    if (P->vol) g->buf[B_VOL] = new_buffer(g, row, NULL);
    if (P->p) g->buf[B_P] = new_buffer(g, row, NULL);
    if (P->p_rho2) g->buf[B_PRHO2] = new_buffer(g, row, NULL);
    if (P->acc_p[0]) g->buf[B_ACC_P] = new_buffer(g, vec, NULL);
    if (P->acc_v[0]) g->buf[B_ACC_V] = new_buffer(g, vec, NULL);
    if (P->acc_i[0]) g->buf[B_ACC_I] = new_buffer(g, vec, NULL);
    if (sim->in_pipeline[SPH_PASS_HASH]) {
        g->buf[B_ENTRIES] = new_buffer(g, n * sizeof(sph_entry), NULL);
        g->buf[B_START] = new_buffer(g, (size_t)g->table * sizeof(uint32_t), NULL);
        if (sim->def.sort == SPH_SORT_COUNTING) {
            g->buf[B_SCRATCH] = new_buffer(g, n * sizeof(sph_entry), NULL);
            g->buf[B_COUNT] = new_buffer(g, ((size_t)g->table + 1) * sizeof(uint32_t), NULL);
        }
    }
    if (sim->in_pipeline[SPH_PASS_REORDER]) g->spare = new_buffer(g, vec, NULL);
    /* totals of each level of the prefix sum over table + 1 counts */
    uint32_t level = g->table + 1;
    for (int l = 0; l < MAX_SCAN_LEVELS; l++) {
        level = (level + WG - 1) / WG;
        g->levels[l] = new_buffer(g, (size_t)level * sizeof(uint32_t), NULL);
        if (level <= 1) break;
    }
    g->buf[B_REDUCE] = new_buffer(g, 4 * sizeof(uint32_t), NULL);
    g->range = new_buffer(g, 4 * sizeof(uint32_t), NULL); /* 16 bytes: a uniform block's vec4 */
    float wall[2 * (SPH_WALL_TABLE + 1)];
    memcpy(wall, sim->k_density.wall_psi, sizeof sim->k_density.wall_psi);
    memcpy(wall + SPH_WALL_TABLE + 1, sim->k_density.wall_area, sizeof sim->k_density.wall_area);
    g->buf[B_WALL] = new_buffer(g, sizeof wall, wall);
    for (int b = 0; b < B_TOTAL; b++)
        if (g->buf[b]) bind(g, b, g->buf[b]);
    return g->gl.GetError() == GL_NO_ERROR;
}

/* Whether the current context can run the passes; false with the reason. */
static bool context_usable(sph_gl *gl, char *why, size_t n)
{
    GLint major = 0, minor = 0, bindings = 0, blocks = 0;
    gl->GetIntegerv(GL_MAJOR_VERSION, &major);
    gl->GetIntegerv(GL_MINOR_VERSION, &minor);
    gl->GetIntegerv(GL_MAX_SHADER_STORAGE_BUFFER_BINDINGS, &bindings);
    gl->GetIntegerv(GL_MAX_COMPUTE_SHADER_STORAGE_BLOCKS, &blocks);
    if (major * 10 + minor < 43) {
        snprintf(why, n, "the context is OpenGL %d.%d, compute shaders need 4.3", major, minor);
    } else if (bindings < B_TOTAL || blocks < 12) {
        snprintf(why, n, "the device has %d storage buffer bindings and %d per compute shader (needs %d and 12)",
                 bindings, blocks, B_TOTAL);
    } else {
        return true;
    }
    return false;
}

/* An EGL surfaceless context of OpenGL 4.3 or later; NULL with the reason. */
static sph_glctx *make_context(sph_gl *gl, sph_gl_compute *gc, char *why, size_t n)
{
    sph_glctx *ctx = sph_glctx_create_egl_version(gl, 4, 3, why, n);
    if (!ctx) return NULL;
    sph_gl_load_compute_epoxy(gc);
    if (context_usable(gl, why, n)) return ctx;
    sph_glctx_destroy(ctx);
    return NULL;
}

/* A shared context (a window's, the renderer's), if it can run the passes;
 * false with the reason. Its functions come from libepoxy, which cannot
 * serve an OSMesa context (src/gl/gl_table.h). */
static bool share_context(sph_glctx *share, sph_gl *gl, sph_gl_compute *gc, char *why, size_t n)
{
    if (sph_glctx_kind_of(share) == SPH_GLCTX_OSMESA) {
        snprintf(why, n, "an OSMesa context cannot be shared (OpenGL 3.3, no libepoxy)");
        return false;
    }
    if (!sph_glctx_make_current(share)) {
        snprintf(why, n, "the shared context cannot be made current");
        return false;
    }
    sph_gl_load_epoxy(gl);
    sph_gl_load_compute_epoxy(gc);
    if (!gl->GetString(GL_VERSION)) {
        snprintf(why, n, "the shared context is not current");
        return false;
    }
    return context_usable(gl, why, n);
}

static void device_name(const sph_gl *gl, char *out, size_t n)
{
    const char *ren = (const char *)gl->GetString(GL_RENDERER), *ver = (const char *)gl->GetString(GL_VERSION);
    snprintf(out, n, "%s, OpenGL %s", ren ? ren : "?", ver ? ver : "?");
}

bool sph_gpu_probe(char *device, size_t n)
{
    sph_gl gl;
    sph_gl_compute gc;
    char why[512];
    sph_glctx *ctx = make_context(&gl, &gc, why, sizeof why);
    if (!ctx) {
        snprintf(device, n, "%s", why);
        return false;
    }
    device_name(&gl, device, n);
    sph_glctx_destroy(ctx);
    return true;
}

/* The drawer's calls (sph_gl_fields), defined with sph_gpu_field_buffer and _range. */
static bool fields_buffer(const sph_sim *sim, int field, unsigned *gl_name);
static bool fields_range(const sph_sim *sim, int field, bool norm, unsigned *gl_name, float lo_hi[2]);

sph_error_code sph_gpu_backend_create(sph_sim *sim, void *share, sph_backend **out, sph_error *err)
{
    *out = NULL;
    sph_error_code c = check_scene(sim, err);
    if (c) return c;
    gpu *g = calloc(1, sizeof *g);
    if (!g) return sph_fail(err, SPH_ERR_MEMORY, "out of memory");
    g->base.name = "gl";
    g->base.run = run;
    g->base.download = download;
    g->base.upload = upload;
    g->base.destroy = destroy;
    g->n = sim->n;
    g->dim = sim->dim;
    g->table = sim->S.table_size ? sim->S.table_size : 1;
    g->pass_sync = true;
    char why[1024];
    if (share) {
        if (share_context(share, &g->gl, &g->gc, why, sizeof why)) g->share = share;
    } else {
        g->ctx = make_context(&g->gl, &g->gc, why, sizeof why);
    }
    if (!g->ctx && !g->share) {
        free(g);
        return sph_fail(err, SPH_ERR_SCENE, "%s: [compute] backend = gl: no OpenGL 4.3 context%s: %s", sim->def.file,
                        share ? " (in the shared one)" : "", why);
    }
    g->fields = (sph_gl_fields){.ctx = g->ctx ? g->ctx : g->share, .buffer = fields_buffer, .range = fields_range};
    device_name(&g->gl, g->base.device, sizeof g->base.device);
    GLint max_block = 0;
    g->gl.GetIntegerv(GL_MAX_SHADER_STORAGE_BLOCK_SIZE, &max_block);
    if ((double)g->n * sizeof(sph_entry) > (double)(unsigned)max_block) {
        double most = (double)(unsigned)max_block / sizeof(sph_entry);
        destroy(&g->base);
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [compute] backend = gl: %u particles need storage buffers larger than this device's "
                        "%d bytes (at most %.0f particles)",
                        sim->def.file, sim->n, max_block, most);
    }
    if (!make_buffers(g, sim)) {
        destroy(&g->base);
        return sph_fail(err, SPH_ERR_MEMORY, "%s: [compute] backend = gl: out of device memory for %u particles",
                        sim->def.file, sim->n);
    }
    char *pre = prelude(g, sim);
    if (!pre) {
        destroy(&g->base);
        return sph_fail(err, SPH_ERR_MEMORY, "out of memory");
    }
    bool need[PROG_TOTAL];
    needed_programs(sim, need);
    for (int p = 0; p < PROG_TOTAL; p++)
        if (need[p] && !compile(g, p, pre, why, sizeof why)) {
            free(pre);
            destroy(&g->base);
            return sph_fail(err, SPH_ERR_SCENE, "[compute] backend = gl: %s", why);
        }
    free(pre);
    *out = &g->base;
    return SPH_ERR_OK;
}

void sph_gpu_set_pass_sync(sph_sim *sim, bool on)
{
    if (sim->backend && sim->backend->run == run) ((gpu *)sim->backend)->pass_sync = on;
}

static gpu *gpu_of(const sph_sim *sim)
{
    return sim->backend && sim->backend->run == run ? (gpu *)sim->backend : NULL;
}

const sph_gl_fields *sph_gpu_fields(const sph_sim *sim)
{
    gpu *g = gpu_of(sim);
    return g ? &g->fields : NULL;
}

bool sph_gpu_field_buffer(const sph_sim *sim, sph_field_id f, unsigned *gl_name)
{
    gpu *g = gpu_of(sim);
    float **vec, *scalar;
    int bi = g ? field_arrays((sph_sim *)sim, (int)f, &vec, &scalar) : -1;
    if (bi < 0 || !g->buf[bi]) return false;
    *gl_name = g->buf[bi];
    return true;
}

/* An ordered key's float (see gpu_range.comp). */
static float key_float(uint32_t k)
{
    uint32_t u = (k & 0x80000000u) ? (k & 0x7FFFFFFFu) : ~k;
    float v;
    memcpy(&v, &u, sizeof v);
    return v;
}

bool sph_gpu_field_range(const sph_sim *sim, sph_field_id f, bool norm, unsigned *gl_name, float lo_hi[2])
{
    gpu *g = gpu_of(sim);
    unsigned src;
    if (!g || !sph_gpu_field_buffer(sim, f, &src)) return false;
    current(g);
    /* min starts above every key, max below: an empty or all-NaN field stays so */
    const uint32_t init[4] = {0xFFFFFFFFu, 0, 0, 0};
    send(g, g->range, 0, sizeof init, init);
    use(g, PROG_range);
    bind(g, B_SRC, src);
    bind(g, B_DST, g->range);
    set_u(g, PROG_range, U_count, norm ? (uint32_t)g->dim : 1u);
    dispatch(g, g->n);
    *gl_name = g->range;
    if (lo_hi) {
        uint32_t k[2];
        get(g, g->range, 0, sizeof k, k);
        lo_hi[0] = k[0] > k[1] ? 0.0f : key_float(k[0]);
        lo_hi[1] = k[0] > k[1] ? 0.0f : key_float(k[1]);
    }
    return true;
}

static bool fields_buffer(const sph_sim *sim, int field, unsigned *gl_name)
{
    return sph_gpu_field_buffer(sim, (sph_field_id)field, gl_name);
}

static bool fields_range(const sph_sim *sim, int field, bool norm, unsigned *gl_name, float lo_hi[2])
{
    return sph_gpu_field_range(sim, (sph_field_id)field, norm, gl_name, lo_hi);
}

uint64_t sph_gpu_downloaded_bytes(const sph_sim *sim)
{
    gpu *g = gpu_of(sim);
    return g ? g->downloaded : 0;
}

void sph_gpu_register(void)
{
    sph_backend_register(SPH_BACKEND_GL, sph_gpu_backend_create);
}
