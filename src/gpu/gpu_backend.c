/* The GL compute backend (see gpu.h): its context, its buffers (one per
 * field of the registry, sph_fields.h), the host copies and the drawer's
 * calls. The passes' table and dispatches are in gpu_passes.c, the programs
 * in gpu_program.c. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "gpu_internal.h"

static GLuint new_buffer(gpu *g, size_t bytes, const void *data)
{
    GLuint b = 0;
    g->gl.GenBuffers(1, &b);
    g->gl.BindBuffer(GL_SHADER_STORAGE_BUFFER, b);
    g->gl.BufferData(GL_SHADER_STORAGE_BUFFER, (GLsizeiptr)(bytes ? bytes : 4), data, GL_DYNAMIC_COPY);
    return b;
}

/* ---- host copies ---------------------------------------------------------- */

static void download(sph_backend *b, sph_sim *sim, sph_mask what)
{
    gpu *g = (gpu *)b;
    gpu_current(g);
    const size_t row = (size_t)g->n * sizeof(float);
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        if (!(what & SPH_SYNC_FIELD(f)) || !g->buf[f]) continue;
        for (int d = 0; d < (sph_field_infos[f].vector ? g->dim : 1); d++)
            if (sim->P.field[f][d]) gpu_get(g, g->buf[f], (size_t)d * row, row, sim->P.field[f][d]);
    }
    if (what & SPH_SYNC_ID) gpu_get(g, g->buf[B_ID], 0, (size_t)g->n * sizeof(uint32_t), sim->P.id);
    sph_search_data *S = &sim->S;
    if ((what & SPH_SYNC_INDEX) && g->buf[B_ENTRIES]) {
        gpu_get(g, g->buf[B_ENTRIES], 0, (size_t)g->n * sizeof(sph_entry), S->entries);
        gpu_get(g, g->buf[B_START], 0, (size_t)g->table * sizeof(uint32_t), S->start);
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
    gpu_current(g);
    const size_t row = (size_t)g->n * sizeof(float);
    for (int f = 0; f < SPH_FIELD_COUNT; f++) {
        if (!g->buf[f]) continue;
        for (int d = 0; d < (sph_field_infos[f].vector ? g->dim : 1); d++)
            if (sim->P.field[f][d]) gpu_send(g, g->buf[f], (size_t)d * row, row, sim->P.field[f][d]);
    }
    gpu_send(g, g->buf[B_ID], 0, (size_t)g->n * sizeof(uint32_t), sim->P.id);
    g->changes++;
}

static void destroy(sph_backend *b)
{
    gpu *g = (gpu *)b;
    if (!g) return;
    if (g->ctx || g->share) {
        gpu_current(g);
        for (int p = 0; p < PROG_TOTAL; p++)
            if (g->prog[p]) g->gl.DeleteProgram(g->prog[p]);
        for (int i = 0; i < B_TOTAL; i++)
            if (g->buf[i]) g->gl.DeleteBuffers(1, &g->buf[i]);
        if (g->spare) g->gl.DeleteBuffers(1, &g->spare);
        for (int l = 0; l < MAX_SCAN_LEVELS; l++)
            if (g->levels[l]) g->gl.DeleteBuffers(1, &g->levels[l]);
        if (g->range) g->gl.DeleteBuffers(1, &g->range);
        gpu_timer_free(g);
        gpu_stats_free(g);
        gpu_health_free(g);
        sph_glctx_destroy(g->ctx);
    }
    free(g);
}

/* ---- creation ------------------------------------------------------------- */

/* Scene options the shaders do not implement: refused by key and value. */
static sph_error_code check_scene(const sph_sim *sim, sph_error *err)
{
    const sph_scene_def *def = &sim->def;
    char at[300]; /* "file:line" or "--set": where the refused key was given */
    if (def->lists_in_place == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] lists_in_place = on is not implemented by the GL backend (its passes walk the "
                        "cells and build no lists; accepted there: off)",
                        sph_scene_key_where(def, "search", "lists_in_place", at, sizeof at));
    if (def->compact_lists == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] compact_lists = on is not implemented by the GL backend (its passes walk the "
                        "cells and build no lists; accepted there: off)",
                        sph_scene_key_where(def, "search", "compact_lists", at, sizeof at));
    if (def->vector_avx2 == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] vector_avx2 = on is not implemented by the GL backend (it selects the CPU's "
                        "AVX2 loops; the shaders' lanes are the device's; accepted there: off)",
                        sph_scene_key_where(def, "search", "vector_avx2", at, sizeof at));
    if (def->cell_batch == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] cell_batch = on is not implemented by the GL backend (it selects the CPU's "
                        "AVX2 search of a cell's particles together; the shaders walk the cells; accepted there: off)",
                        sph_scene_key_where(def, "search", "cell_batch", at, sizeof at));
    if (def->packed_records == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [compute] packed_records = on is not implemented by the GL backend (it changes how the "
                        "CPU's AVX2 loops read neighbours; the shaders read buffers; accepted there: off)",
                        sph_scene_key_where(def, "compute", "packed_records", at, sizeof at));
    if (def->uniform_mass == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [compute] uniform_mass = on is not implemented by the GL backend (it changes how the "
                        "CPU's AVX2 force walk reads the mass; the shaders read buffers; accepted there: off)",
                        sph_scene_key_where(def, "compute", "uniform_mass", at, sizeof at));
    if (def->lists_resident == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] lists_resident = on is not implemented by the GL backend (its passes walk the "
                        "cells and build no lists; accepted there: off)",
                        sph_scene_key_where(def, "search", "lists_resident", at, sizeof at));
    if (def->wide_batch == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] wide_batch = on is not implemented by the GL backend (it selects the CPU's "
                        "AVX-512 search of a cell's particles together; the shaders walk the cells; accepted there: "
                        "off)",
                        sph_scene_key_where(def, "search", "wide_batch", at, sizeof at));
    if (def->wide_density == SPH_ON)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [compute] wide_density = on is not implemented by the GL backend (it changes how the "
                        "CPU's AVX-512 density walk reads its records; the shaders read buffers; accepted there: off)",
                        sph_scene_key_where(def, "compute", "wide_density", at, sizeof at));
    if (def->skin > 0)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] skin = %g (Verlet lists) is not implemented by the GL backend (its passes "
                        "walk the cells every step and keep no lists; accepted there: 0)",
                        sph_scene_key_where(def, "search", "skin", at, sizeof at), (double)def->skin);
    if (def->surface_tension == SPH_STENSION_STRESS)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [physics] surface_tension = stress is not implemented by the GL backend (no shader "
                        "for its surface stress yet; accepted there: none, akinci, csf)",
                        sph_scene_key_where(def, "physics", "surface_tension", at, sizeof at));
    /* a pass without a row in gpu_passes.c is refused here rather than
     * skipped on the device */
    for (int p = 0; p < SPH_PASS_COUNT; p++)
        if (sim->in_pipeline[p] && !gpu_pass_rows[p].run && !gpu_pass_rows[p].source)
            return sph_fail(err, SPH_ERR_SCENE, "%s: the GL backend has no %s pass (the scene needs it)", def->file,
                            sph_passes[p]->name);
    if (sim->in_pipeline[SPH_PASS_SORT] && def->sort != SPH_SORT_BITONIC && def->sort != SPH_SORT_COUNTING)
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] sort = %s is not implemented by the GL backend (accepted there: bitonic, "
                        "counting)",
                        sph_scene_key_where(def, "search", "sort", at, sizeof at), sph_sort_names[def->sort]);
    if (def->search != SPH_SEARCH_BRUTE && def->sort == SPH_SORT_NONE && sph_scene_needs_neighbours(def))
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [search] sort = none is not implemented by the GL backend (accepted there: bitonic, "
                        "counting)",
                        sph_scene_key_where(def, "search", "sort", at, sizeof at));
    if (def->accumulate == SPH_ACC_DOUBLE && sph_scene_needs_density(def))
        return sph_fail(err, SPH_ERR_SCENE,
                        "%s: [physics] accumulate = double is not implemented by the GL backend (accepted there: "
                        "float)",
                        sph_scene_key_where(def, "physics", "accumulate", at, sizeof at));
    return SPH_ERR_OK;
}

static bool make_buffers(gpu *g, const sph_sim *sim)
{
    const size_t n = g->n, row = n * sizeof(float), vec = (size_t)g->dim * row;
    /* the ids and the fields the reorder pass moves take a vector's size: it
     * swaps any gathered field with the spare, which must then hold any of them */
    const sph_mask moved = sph_passes[SPH_PASS_REORDER]->writes;
    g->buf[B_ID] = new_buffer(g, vec, NULL);
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if (sim->P.field[f][0])
            g->buf[f] = new_buffer(g, sph_field_infos[f].vector || (moved & SPH_FIELD_BIT(f)) ? vec : row, NULL);
    if (sim->in_pipeline[SPH_PASS_HASH]) {
        g->buf[B_ENTRIES] = new_buffer(g, n * sizeof(sph_entry), NULL);
        g->buf[B_START] = new_buffer(g, (size_t)g->table * sizeof(uint32_t), NULL);
        if (sim->def.sort == SPH_SORT_COUNTING) {
            g->buf[B_SCRATCH] = new_buffer(g, n * sizeof(sph_entry), NULL);
            g->buf[B_COUNT] = new_buffer(g, ((size_t)g->table + 1) * sizeof(uint32_t), NULL);
        }
    }
    if (sim->in_pipeline[SPH_PASS_REORDER]) g->spare = new_buffer(g, vec, NULL);
    /* surface_tension = csf: its first sweep's two values per particle for the second (gpu_csf.comp) */
    if (sim->in_pipeline[SPH_PASS_CSF]) g->buf[B_CSF] = new_buffer(g, 2 * row, NULL);
    /* totals of each level of the prefix sum over table + 1 counts */
    uint32_t level = g->table + 1;
    for (int l = 0; l < MAX_SCAN_LEVELS; l++) {
        level = (level + WG - 1) / WG;
        g->levels[l] = new_buffer(g, (size_t)level * sizeof(uint32_t), NULL);
        if (level <= 1) break;
    }
    g->buf[B_REDUCE] = new_buffer(g, 4 * sizeof(uint32_t), NULL);
    g->range = new_buffer(g, 4 * sizeof(uint32_t), NULL); /* 16 bytes: a uniform block's vec4 */
    /* the volume walls' tables (sph_wall_hidden), the density kernel's: its
     * lattice share, slope, corner share and corner slope (shaders/gpu_common.glsl) */
    const sph_kernel *kd = &sim->k_density;
    const size_t wall_floats = GPU_WALLP_AT + GPU_WALLP_FLOATS;
    float *wall = malloc(wall_floats * sizeof *wall);
    if (!wall) return false;
    float *o = wall;
    memcpy(o, kd->wall_lat_psi, sizeof kd->wall_lat_psi);
    o += SPH_WALL_TABLE + 1;
    memcpy(o, kd->wall_lat_area, sizeof kd->wall_lat_area);
    o += SPH_WALL_TABLE + 1;
    memcpy(o, kd->wall_corner, sizeof kd->wall_corner);
    o += (SPH_WALL_CORNER + 1) * (SPH_WALL_CORNER + 1);
    memcpy(o, kd->wall_corner_slope, sizeof kd->wall_corner_slope);
    o += (SPH_WALL_CORNER + 1) * (SPH_WALL_CORNER + 1);
    /* the solvers' table, made by their pass in the start-up evaluation (zero without a solver) */
    memcpy(o, sim->solver.wall_share, sizeof sim->solver.wall_share);
    o += SPH_SOLVER_WALL_SAMPLES + 1;
    memcpy(o, sim->solver.wall_slope, sizeof sim->solver.wall_slope);
    o += SPH_SOLVER_WALL_SAMPLES + 1;
    /* the pressure kernel's: the walls' pressure force (sph_wall_ghost_accel) */
    const sph_kernel *kp = &sim->k_pressure;
    memcpy(o, kp->wall_lat_psi, sizeof kp->wall_lat_psi);
    o += SPH_WALL_TABLE + 1;
    memcpy(o, kp->wall_lat_area, sizeof kp->wall_lat_area);
    o += SPH_WALL_TABLE + 1;
    memcpy(o, kp->wall_corner, sizeof kp->wall_corner);
    o += (SPH_WALL_CORNER + 1) * (SPH_WALL_CORNER + 1);
    memcpy(o, kp->wall_corner_slope, sizeof kp->wall_corner_slope);
    o += (SPH_WALL_CORNER + 1) * (SPH_WALL_CORNER + 1);
    memcpy(o, kp->wall_lat_tn, sizeof kp->wall_lat_tn);
    o += SPH_WALL_TABLE + 1;
    memcpy(o, kp->wall_lat_tt, sizeof kp->wall_lat_tt);
    g->buf[B_WALL] = new_buffer(g, wall_floats * sizeof *wall, wall);
    free(wall);
    for (int b = 0; b < B_TOTAL; b++)
        if (g->buf[b]) gpu_bind(g, b, g->buf[b]);
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
    g->base.run = gpu_run_pass;
    g->base.download = download;
    g->base.upload = upload;
    g->base.destroy = destroy;
    g->base.stats = gpu_stats;
    g->base.hash_health = gpu_hash_health;
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
    gpu_timer_init(g);
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
    char *pre = gpu_prelude(g, sim);
    if (!pre) {
        destroy(&g->base);
        return sph_fail(err, SPH_ERR_MEMORY, "out of memory");
    }
    bool need[PROG_TOTAL];
    gpu_needed_programs(sim, need);
    for (int p = 0; p < PROG_TOTAL; p++)
        if (need[p] && !gpu_compile(g, p, pre, why, sizeof why)) {
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
    if (sim->backend && sim->backend->run == gpu_run_pass) ((gpu *)sim->backend)->pass_sync = on;
}

bool sph_gpu_set_timer_queries(sph_sim *sim, bool on)
{
    if (!sim->backend || sim->backend->run != gpu_run_pass) return false;
    gpu *g = (gpu *)sim->backend;
    gpu_current(g);
    gpu_timer_enable(g, sim, on);
    return g->timer.on;
}

uint64_t sph_gpu_finish_count(const sph_sim *sim)
{
    return sim->backend && sim->backend->run == gpu_run_pass ? ((const gpu *)sim->backend)->finishes : 0;
}

static gpu *gpu_of(const sph_sim *sim)
{
    return sim->backend && sim->backend->run == gpu_run_pass ? (gpu *)sim->backend : NULL;
}

const sph_gl_fields *sph_gpu_fields(const sph_sim *sim)
{
    gpu *g = gpu_of(sim);
    return g ? &g->fields : NULL;
}

bool sph_gpu_field_buffer(const sph_sim *sim, sph_field_id f, unsigned *gl_name)
{
    gpu *g = gpu_of(sim);
    if (!g || (int)f < 0 || f >= SPH_FIELD_COUNT || !g->buf[f]) return false;
    *gl_name = g->buf[f];
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
    gpu_current(g);
    /* min starts above every key, max below: an empty or all-NaN field stays so */
    const uint32_t init[4] = {0xFFFFFFFFu, 0, 0, 0};
    gpu_send(g, g->range, 0, sizeof init, init);
    gpu_use(g, PROG_H(range));
    gpu_bind(g, B_SRC, src);
    gpu_bind(g, B_DST, g->range);
    gpu_set_u(g, PROG_H(range), U_count, norm ? (uint32_t)g->dim : 1u);
    gpu_dispatch(g, g->n);
    *gl_name = g->range;
    if (lo_hi) {
        uint32_t k[2];
        gpu_get(g, g->range, 0, sizeof k, k);
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
