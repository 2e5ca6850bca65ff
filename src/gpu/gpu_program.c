/* The GL backend's programs: the scene's constants as GLSL #defines before
 * the shared GLSL (shaders/gpu_common.glsl), floats as their exact bits, and
 * the storage blocks each program uses, the fields' written from the
 * registry (sph_fields.h). Each program is compiled for one scene: loops over
 * axes unroll and unused options vanish, as SPH_SPECIALISE does on the CPU. */
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "csf.h"
#include "gpu_internal.h"
#include "sph_start.h"
#include "sph_walls.h"

const char *const gpu_other_binding_names[B_TOTAL - SPH_FIELD_COUNT] = {
#define GPU_B_NAME(name) #name,
    GPU_OTHER_BINDINGS(GPU_B_NAME)
#undef GPU_B_NAME
};

static const char *const uniform_names[U_TOTAL] = {
#define GPU_U_NAME(name) "u_" #name,
    GPU_UNIFORMS(GPU_U_NAME)
#undef GPU_U_NAME
};


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
char *gpu_prelude(const gpu *g, const sph_sim *sim)
{
    const sph_scene_def *def = &sim->def;
    const sph_cells *c = &sim->S.cells;
    text t = {0};
    put(&t, "#version 430\n#define WG %d\n#define N %uu\n#define T %uu\n#define DIM %d\n#define WALL_TABLE %d\n", WG,
        g->n, g->table, g->dim, SPH_WALL_TABLE);
    /* a field's binding is its number; HAS_X: this scene allocates field X */
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        put(&t, "#define B_%s %d\n#define HAS_%s %d\n", sph_field_infos[f].id, f, sph_field_infos[f].id,
            sim->P.field[f][0] != NULL);
    for (int b = SPH_FIELD_COUNT; b < B_TOTAL; b++)
        put(&t, "#define B_%s %d\n", gpu_other_binding_names[b - SPH_FIELD_COUNT], b);
    /* integration's sum of every acceleration field the scene has, in the
     * registry's order as on the CPU (integrate.c) */
    put(&t, "#define ACC_SUM(k) (0.0");
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if (sph_field_infos[f].kind == SPH_KIND_ACCELERATION && sim->P.field[f][0])
            put(&t, " + %s_[k]", sph_field_infos[f].name);
    put(&t, ")\n");
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
    /* the domain as the particles see it: relative to sim->origin (sph_sim_create), in float */
    float lo[3], hi[3];
    for (int d = 0; d < 3; d++) lo[d] = (float)sim->def.domain_min[d], hi[d] = (float)sim->def.domain_max[d];
    put_vec3(&t, "DOM_MIN", lo);
    put_vec3(&t, "DOM_MAX", hi);
    put(&t, "#define HAS_GRAVITY %d\n", (def->effects & SPH_EFFECT(GRAVITY)) != 0);
    put(&t, "#define HAS_WALLS %d\n", (def->effects & SPH_EFFECT(WALLS)) != 0); /* the box reflects */
    put_vec3(&t, "GRAVITY", sim->def.gravity);
    put(&t, "#define WALL_VOLUME %d\n#define WALL_CORNER %d\n", sph_sim_wall_volume(sim), SPH_WALL_CORNER);
    put_float(&t, "WALL_FULL", sim->k_density.wall_lat_full);
    put_float(&t, "WALL_FULL_P", sim->k_pressure.wall_lat_full);
    put(&t, "#define WALLP_AT %d\n#define WALL_GHOST %d\n", GPU_WALLP_AT, def->wall_force == SPH_WFORCE_GHOST);
    put_float(&t, "RHO0", def->rest_density);
    put_float(&t, "STIFF", def->stiffness);
    put(&t, "#define EOS_TAIT %d\n#define CLAMP_NEG %d\n", def->eos == SPH_EOS_TAIT,
        def->negative_pressure == SPH_NEGP_CLAMP);
    put_float(&t, "GAMMA", def->tait_gamma);
    /* the equation of state's reference (sim->eos_rho0: rest_density, or the lattice's with eos_rest =
     * lattice), for the pressure, its inverse at the walls, the internal energy and Fourtakas's term */
    put_float(&t, "EOS_RHO0", sim->eos_rho0);
    put_float(&t, "TAIT_B", def->stiffness * sim->eos_rho0 / def->tait_gamma);
    /* the form as its enum value: the shader names each one it implements and
     * stops with #error on any other, so a form added on the CPU is never
     * silently computed as another on GL */
    put(&t, "#define PFORM_SYM %d\n#define VFORM %d\n#define VFORM_LAPLACIAN %d\n#define VFORM_SMOOTHING %d\n"
            "#define VFORM_MORRIS %d\n#define VFORM_ARTIFICIAL %d\n#define VFORM_MORRIS_ARTIFICIAL %d\n",
        def->pressure_form == SPH_PFORM_SYMMETRIC, (int)def->viscosity_form, (int)SPH_VFORM_LAPLACIAN,
        (int)SPH_VFORM_SMOOTHING, (int)SPH_VFORM_MORRIS, (int)SPH_VFORM_ARTIFICIAL, (int)SPH_VFORM_MORRIS_ARTIFICIAL);
    put(&t, "#define DFORM_FOURTAKAS %d\n", def->delta_form == SPH_DFORM_FOURTAKAS);
    put_float(&t, "NU", def->viscosity);
    /* the no-slip mirror's curvature term (wall_state.c) */
    put(&t, "#define WALL_CURV %d\n", sph_wall_mirror_inv_nu(def) > 0);
    put_float(&t, "WALL_INV_NU", (float)sph_wall_mirror_inv_nu(def));
    /* artificial viscosity: alpha c h_s as the CPU pass computes it in float */
    put_float(&t, "AV_ACH", def->alpha * sqrtf(def->stiffness) * (0.5f * def->h));
    put_float(&t, "AV_EPS2", 0.01f * (0.5f * def->h) * (0.5f * def->h));
    /* the cohesion pass's gamma: surface_tension = akinci's coefficient when
     * the pass is that model's cohesion term (cohesion.c) */
    const bool akinci = def->surface_tension == SPH_STENSION_AKINCI;
    put_float(&t, "COHESION", akinci ? def->surface_tension_coefficient : def->cohesion);
    put_float(&t, "ST_GAMMA", def->surface_tension_coefficient); /* the curvature term's gamma [m/s^2] */
    /* surface_tension = csf: the normals' volumes m_j / rho0 (normals.c), 1 / rho0 [m^dim/kg] in float */
    put(&t, "#define ST_CSF %d\n", def->surface_tension == SPH_STENSION_CSF);
    put_float(&t, "INV_RHO0", 1.0f / def->rest_density);
    /* csf's cuts (src/passes/csf.h): |h grad c| in float, the least tangential support in double */
    put_float(&t, "CSF_NORMAL_MIN", SPH_CSF_NORMAL_MIN);
    const double support_min = SPH_CSF_SUPPORT_MIN;
    uint32_t sm[2];
    memcpy(sm, &support_min, sizeof sm);
    put(&t, "#define CSF_SUPPORT_MIN packDouble2x32(uvec2(0x%08xu, 0x%08xu))\n", sm[0], sm[1]);
    put_float(&t, "DAMP", def->wall_damping);
    put_float(&t, "INTER_R", def->interaction_radius);
    /* the pressure solvers (src/passes/solver.h): the density they hold
     * [kg/m^dim] and its inverses as their passes compute them, alpha's floors
     * (dfsph.c), their wall table's place in B_WALL and scale [1/m], and the
     * accelerations other than theirs, summed as sph_solver_other_acc does */
    const float rho_r = sim->solver.rho_rest;
    put_float(&t, "RHO_R", rho_r);
    put_float(&t, "INV_RHO_R", rho_r > 0 ? 1.0f / rho_r : 0.0f);
    put_float(&t, "INV_RHO_R2", rho_r > 0 ? 1.0f / (rho_r * rho_r) : 0.0f);
    put_float(&t, "ALPHA_MIN", 1e-6f * rho_r * rho_r / (def->h * def->h));
    put_float(&t, "DEN_FULL", sim->solver.den_full);
    put_float(&t, "DEN_FULL_V", sim->solver.den_full_v);
    /* DFSPH's factor counts the walls' part of G^p twice where the wall particles take the fluid's kappa
     * (dfsph.c, factors) */
    put(&t, "#define WALL_PUSH %s\n",
        sph_scene_wall_particles(def) && def->solver_wall_pressure == SPH_SWALLP_EXTRAPOLATED ? "2.0" : "1.0");
    put(&t, "#define SOLVER_WALL_AT %d\n#define SOLVER_WALL_SAMPLES %d\n", GPU_WALL_FLOATS, SPH_SOLVER_WALL_SAMPLES);
    /* the particles DFSPH's divergence error is the mean over: the fluid's, not the wall particles' (dfsph.c);
     * at least 1, as the mean of none is 0 there */
    uint32_t fluid = 0;
    for (uint32_t i = 0; i < sim->n; i++) fluid += !sph_is_wall(&sim->P, i);
    put(&t, "#define N_FLUID %uu\n", fluid > 0 ? fluid : 1u);
    put_float(&t, "SOLVER_WALL_SCALE", (float)SPH_SOLVER_WALL_SAMPLES / def->h);
    put(&t, "#define ACC_OTHER(k) (0.0");
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if (sph_field_infos[f].kind == SPH_KIND_ACCELERATION && sim->P.field[f][0] && f != SPH_FIELD_ACC_PCI &&
            f != SPH_FIELD_ACC_DF)
            put(&t, " + %s_[k]", sph_field_infos[f].name);
    put(&t, ")\n");
    if (t.failed) {
        free(t.s);
        return NULL;
    }
    return t.s;
}

/* Whether `name` is a word of the "// uses:" line [line, eol). */
static bool uses_word(const char *line, const char *eol, const char *name)
{
    size_t len = strlen(name);
    for (const char *at = line; (at = strstr(at, name)) && at < eol; at += len)
        if (at[-1] == ' ' && (at[len] == ' ' || at[len] == '\n')) return true;
    return false;
}

/* The storage blocks a program declares: its first line, "// uses: POS VEL
 * ...", names fields by their registry id and the other buffers by binding
 * name; ACCELERATIONS stands for every acceleration field. Only buffers this
 * scene has (or that are bound per dispatch) are declared, since Mesa counts
 * every declared block against its limit of 16 per shader. A field's block is
 * written here from the registry: `float NAME_[]`, component d of particle i
 * at d * N + i. */
static void declare_buffers(const gpu *g, const char *src, text *t)
{
    const char *line = strstr(src, "// uses:"), *eol = line ? strchr(line, '\n') : NULL;
    if (!line || !eol) return;
    bool accs = uses_word(line, eol, "ACCELERATIONS");
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        const sph_field_info *fi = &sph_field_infos[f];
        bool listed = uses_word(line, eol, fi->id) || (accs && fi->kind == SPH_KIND_ACCELERATION);
        if (listed && g->buf[f])
            put(t, "layout(std430, binding = B_%s) buffer Buf_%s { float %s_[]; };\n", fi->id, fi->id, fi->name);
    }
    for (int b = SPH_FIELD_COUNT; b < B_TOTAL; b++) {
        const char *name = gpu_other_binding_names[b - SPH_FIELD_COUNT];
        bool dynamic = b == B_SRC || b == B_DST || b == B_SCAN || b == B_SUMS;
        if (uses_word(line, eol, name) && (g->buf[b] || dynamic)) put(t, "#define USE_%s 1\n", name);
    }
}

/* The shared GLSL a program's source may pull in, each by a line of its own:
 * "#include_walk" (the neighbour walk) and "#include_forces" (the pressure
 * and viscosity terms); GLSL itself has no #include. */
#define GPU_INCLUDES 2
#define GPU_PARTS (3 + 2 * GPU_INCLUDES + 1) /* prelude, buffers, common, then source and includes in turn */

static int split_includes(const char *src, const char *parts[GPU_PARTS], GLint lens[GPU_PARTS], int count)
{
    const char *const marks[GPU_INCLUDES] = {"#include_walk\n", "#include_forces\n"};
    const char *const texts[GPU_INCLUDES] = {gpu_walk_source, gpu_force_terms_source};
    for (;;) {
        const char *at = NULL;
        int which = -1;
        for (int k = 0; k < GPU_INCLUDES; k++) {
            const char *m = strstr(src, marks[k]);
            if (m && (!at || m < at)) at = m, which = k;
        }
        if (!at || count + 2 >= GPU_PARTS) break;
        parts[count] = src, lens[count++] = (GLint)(at - src);
        parts[count] = texts[which], lens[count++] = -1;
        src = at + strlen(marks[which]);
    }
    parts[count] = src, lens[count++] = -1;
    return count;
}

bool gpu_compile(gpu *g, int p, const char *pre, char *why, size_t n)
{
    sph_gl *gl = &g->gl;
    const bool helper = p >= SPH_PASS_COUNT;
    const char *src = helper ? gpu_helper_sources[p - SPH_PASS_COUNT] : gpu_pass_rows[p].source;
    text uses = {0};
    declare_buffers(g, src, &uses);
    if (uses.failed) {
        free(uses.s);
        snprintf(why, n, "out of memory");
        return false;
    }
    const char *parts[GPU_PARTS] = {pre, uses.s ? uses.s : "", gpu_common_source};
    GLint lens[GPU_PARTS] = {-1, -1, -1};
    const int count = split_includes(src, parts, lens, 3);
    const sph_gl_stage stage = {GL_COMPUTE_SHADER, count, parts, lens};
    char what[96];
    snprintf(what, sizeof what, "shaders/gpu_%s.comp", helper ? gpu_helper_names[p - SPH_PASS_COUNT] : sph_passes[p]->name);
    GLuint prog = sph_gl_program(gl, &stage, 1, what, why, n);
    free(uses.s);
    if (!prog) return false;
    g->prog[p] = prog;
    for (int u = 0; u < U_TOTAL; u++) g->loc[p][u] = gl->GetUniformLocation(prog, uniform_names[u]);
    return true;
}
