/* The renderer (see render.h). Every GL call goes through the table r->gl
 * (gl_table.h explains why). A frame is:
 *   1. the "canvas under": the domain's box;
 *   2. the particles: one instanced draw call (a quad per particle; discs in
 *      2D, sphere impostors in 3D), colours mapped on the CPU;
 *   3. the "canvas over": overlay primitives from sph_overlay_build(), the
 *      HUD, the legend and the index strip, as triangles in pixels with one
 *      texture (the font atlas).
 * Nothing depends on time or on the machine's threads, so a state renders to
 * the same bytes every time (llvmpipe rasterises deterministically). */
#include "render.h"

#include <errno.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "io.h" /* sph_io_write_png */

#include "gl_fields.h"
#include "layout.h"
#include "renderer_impl.h"
#include "sph_walls.h" /* sph_wall_particles_bounds: the box the view frames */
#include "shaders.h" /* generated from shaders/ by src/render/module.mk */

const char *const sph_gl_backend_names[SPH_GL_BACKEND_COUNT] = {
#define SPH_GL_BACKEND_NAME(id, name, about) name,
    SPH_GL_BACKENDS(SPH_GL_BACKEND_NAME)
#undef SPH_GL_BACKEND_NAME
};

static const uint32_t BG = SPH_RGBA(30, 32, 38, 255);

/* ---- set-up -------------------------------------------------------------- */

static GLuint program(sph_renderer *r, const char *vs, const char *fs, const char *name, char *err, size_t n)
{
    const sph_gl_stage stages[2] = {{GL_VERTEX_SHADER, 1, &vs, NULL}, {GL_FRAGMENT_SHADER, 1, &fs, NULL}};
    char what[128];
    snprintf(what, sizeof what, "shaders %s", name);
    return sph_gl_program(&r->gl, stages, 2, what, err, n);
}

/* Text sizes follow the image's height, so a small test image and a large
 * figure both stay readable. */
static bool make_font(sph_renderer *r, char *err, size_t n)
{
    float s, nm;
    sph_layout_font_sizes(r->h, &s, &nm);
    if (r->have_font && r->font.px[0] == s && r->font.px[1] == nm) return true;
    if (r->have_font) sph_font_free(&r->font);
    r->have_font = false;
    if (!sph_font_load(&r->font, s, nm, err, n)) return false;
    r->have_font = true;
    sph_gl *gl = &r->gl;
    if (!r->tex) gl->GenTextures(1, &r->tex);
    gl->BindTexture(GL_TEXTURE_2D, r->tex);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_R8, SPH_FONT_ATLAS, SPH_FONT_ATLAS, 0, GL_RED, GL_UNSIGNED_BYTE, r->font.atlas);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    return true;
}

static bool make_fbo(sph_renderer *r, char *err, size_t n)
{
    sph_gl *gl = &r->gl;
    if (r->fbo) {
        gl->DeleteFramebuffers(1, &r->fbo);
        gl->DeleteRenderbuffers(1, &r->rb_color);
        gl->DeleteRenderbuffers(1, &r->rb_depth);
    }
    gl->GenFramebuffers(1, &r->fbo);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    gl->GenRenderbuffers(1, &r->rb_color);
    gl->BindRenderbuffer(GL_RENDERBUFFER, r->rb_color);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, r->w, r->h);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->rb_color);
    gl->GenRenderbuffers(1, &r->rb_depth);
    gl->BindRenderbuffer(GL_RENDERBUFFER, r->rb_depth);
    gl->RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, r->w, r->h);
    gl->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->rb_depth);
    GLenum st = gl->CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (st != GL_FRAMEBUFFER_COMPLETE) {
        snprintf(err, n, "framebuffer %dx%d incomplete (status 0x%x)", r->w, r->h, (unsigned)st);
        return false;
    }
    return true;
}

static bool check_size(int w, int h, char *err, size_t n)
{
    if (w < 64 || h < 64 || w > 8192 || h > 8192) {
        snprintf(err, n, "image size %dx%d out of range (accepted: 64 to 8192 pixels a side)", w, h);
        return false;
    }
    return true;
}

static void locate(sph_renderer *r, GLuint prog, ploc *l)
{
    sph_gl *gl = &r->gl;
    l->view = gl->GetUniformLocation(prog, "u_view");
    l->proj = gl->GetUniformLocation(prog, "u_proj");
    l->radius = gl->GetUniformLocation(prog, "u_radius");
    l->sphere = gl->GetUniformLocation(prog, "u_sphere");
    l->keep_lo = gl->GetUniformLocation(prog, "u_keep_lo");
    l->keep_hi = gl->GetUniformLocation(prog, "u_keep_hi");
    l->rim = gl->GetUniformLocation(prog, "u_rim");
    l->dim = gl->GetUniformLocation(prog, "u_dim");
    l->comps = gl->GetUniformLocation(prog, "u_comps");
    l->fixed = gl->GetUniformLocation(prog, "u_fixed");
    l->range = gl->GetUniformLocation(prog, "u_range");
    l->walls = gl->GetUniformLocation(prog, "u_walls");
}

static sph_renderer *create(sph_gl_backend backend, int w, int h, bool gl43, char *err, size_t n)
{
    if (!check_size(w, h, err, n)) return NULL;
    sph_renderer *r = calloc(1, sizeof *r);
    if (!r) {
        snprintf(err, n, "out of memory");
        return NULL;
    }
    r->backend = backend;
    r->w = w;
    r->h = h;
    if (backend == SPH_GL_EGL)
        r->ctx = gl43 ? sph_glctx_create_egl_version(&r->gl, 4, 3, err, n) : sph_glctx_create_egl(&r->gl, err, n);
    else if (backend == SPH_GL_OSMESA)
        r->ctx = sph_glctx_create_osmesa(&r->gl, err, n);
    else
        r->ctx = sph_glctx_create_caller(&r->gl, err, n);
    if (!r->ctx) {
        free(r);
        return NULL;
    }
    sph_gl *gl = &r->gl;
    const char *ren = (const char *)gl->GetString(GL_RENDERER), *ver = (const char *)gl->GetString(GL_VERSION);
    snprintf(r->info, sizeof r->info, "%s, OpenGL %s", ren ? ren : "?", ver ? ver : "?");
    GLint major = 0, minor = 0;
    gl->GetIntegerv(GL_MAJOR_VERSION, &major);
    gl->GetIntegerv(GL_MINOR_VERSION, &minor);
    if (major * 10 + minor < 33) {
        snprintf(err, n, "%s: OpenGL %d.%d, 3.3 needed", sph_gl_backend_names[backend], major, minor);
        sph_renderer_destroy(r);
        return NULL;
    }
    /* the compute table comes from epoxy, which OSMesa cannot use (gl_table.h) */
    r->gl43 = major * 10 + minor >= 43 && backend != SPH_GL_OSMESA;
    if (r->gl43) sph_gl_load_compute_epoxy(&r->gc);
    if (gl43 && !r->gl43) {
        snprintf(err, n, "%s: OpenGL %d.%d, 4.3 needed to draw from the GL backend's buffers",
                 sph_gl_backend_names[backend], major, minor);
        sph_renderer_destroy(r);
        return NULL;
    }
    r->prog_p = program(r, shader_particles_vert, shader_particles_frag, "particles", err, n);
    r->prog_c = r->prog_p ? program(r, shader_canvas_vert, shader_canvas_frag, "canvas", err, n) : 0;
    if (!r->prog_c || !make_fbo(r, err, n) || !make_font(r, err, n)) {
        sph_renderer_destroy(r);
        return NULL;
    }
    locate(r, r->prog_p, &r->lp);
    r->uc_size = gl->GetUniformLocation(r->prog_c, "u_size");
    r->uc_atlas = gl->GetUniformLocation(r->prog_c, "u_atlas");

    static const float corners[8] = {-1, -1, 1, -1, -1, 1, 1, 1};
    gl->GenVertexArrays(1, &r->vao_p);
    gl->BindVertexArray(r->vao_p);
    gl->GenBuffers(1, &r->vbo_corner);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->vbo_corner);
    gl->BufferData(GL_ARRAY_BUFFER, sizeof corners, corners, GL_STATIC_DRAW);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    gl->GenBuffers(1, &r->vbo_inst);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->vbo_inst);
    gl->EnableVertexAttribArray(1);
    gl->VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, sizeof(inst), (const void *)0);
    gl->VertexAttribDivisor(1, 1);
    gl->EnableVertexAttribArray(2);
    gl->VertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(inst), (const void *)offsetof(inst, rgba));
    gl->VertexAttribDivisor(2, 1);

    gl->GenVertexArrays(1, &r->vao_c);
    gl->BindVertexArray(r->vao_c);
    gl->GenBuffers(1, &r->vbo_c);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->vbo_c);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, sizeof(vtx), (const void *)0);
    gl->EnableVertexAttribArray(1);
    gl->VertexAttribPointer(1, 2, GL_FLOAT, GL_FALSE, sizeof(vtx), (const void *)offsetof(vtx, u));
    gl->EnableVertexAttribArray(2);
    gl->VertexAttribPointer(2, 4, GL_UNSIGNED_BYTE, GL_TRUE, sizeof(vtx), (const void *)offsetof(vtx, rgba));
    gl->BindVertexArray(0);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR) {
        snprintf(err, n, "%s: GL error 0x%x while setting up", sph_gl_backend_names[backend], (unsigned)e);
        sph_renderer_destroy(r);
        return NULL;
    }
    return r;
}

sph_renderer *sph_renderer_create(sph_gl_backend backend, int w, int h, char *err, size_t n)
{
    return create(backend, w, h, false, err, n);
}

sph_renderer *sph_renderer_create_gl43(sph_gl_backend backend, int w, int h, char *err, size_t n)
{
    return create(backend, w, h, true, err, n);
}

/* The program and vertex layout that read the GL backend's buffers, made on
 * the first frame that needs them; false (reason in err) if they fail. */
static bool make_direct(sph_renderer *r, char *err, size_t n)
{
    if (r->prog_d) return true;
    sph_gl *gl = &r->gl;
    r->prog_d = program(r, shader_particles_direct_vert, shader_particles_frag, "particles_direct", err, n);
    if (!r->prog_d) return false;
    locate(r, r->prog_d, &r->ld);
    uint32_t cmap[256];
    for (int k = 0; k < 256; k++) cmap[k] = sph_colormap_viridis((float)k / 255.0f);
    gl->GenTextures(1, &r->tex_cmap);
    gl->BindTexture(GL_TEXTURE_2D, r->tex_cmap);
    gl->PixelStorei(GL_UNPACK_ALIGNMENT, 4);
    gl->TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, 256, 1, 0, GL_RGBA, GL_UNSIGNED_BYTE, cmap); /* bytes R, G, B, A */
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    gl->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    gl->GenVertexArrays(1, &r->vao_d);
    gl->BindVertexArray(r->vao_d);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->vbo_corner);
    gl->EnableVertexAttribArray(0);
    gl->VertexAttribPointer(0, 2, GL_FLOAT, GL_FALSE, 0, (const void *)0);
    for (GLuint a = 1; a <= 7; a++) {
        gl->EnableVertexAttribArray(a);
        gl->VertexAttribDivisor(a, 1);
    }
    gl->BindVertexArray(0);
    return true;
}

/* The GL compute backend has a context of its own and makes it current for
 * its passes; the headless contexts are made current again before drawing
 * (the window's is, by the window: cmd_view.c). */
static void make_current(sph_renderer *r)
{
    sph_glctx_make_current(r->ctx);
}

bool sph_renderer_resize(sph_renderer *r, int w, int h, char *err, size_t n)
{
    make_current(r);
    if (w == r->w && h == r->h) return true;
    if (!check_size(w, h, err, n)) return false;
    r->w = w;
    r->h = h;
    return make_fbo(r, err, n) && make_font(r, err, n);
}

void sph_renderer_destroy(sph_renderer *r)
{
    if (!r) return;
    if (r->ctx) make_current(r);
    sph_gl *gl = &r->gl;
    if (gl->DeleteProgram) {
        if (r->prog_p) gl->DeleteProgram(r->prog_p);
        if (r->prog_c) gl->DeleteProgram(r->prog_c);
        if (r->prog_d) gl->DeleteProgram(r->prog_d);
        if (r->tex_cmap) gl->DeleteTextures(1, &r->tex_cmap);
        if (r->vao_d) gl->DeleteVertexArrays(1, &r->vao_d);
        if (r->fbo) gl->DeleteFramebuffers(1, &r->fbo);
        if (r->rb_color) gl->DeleteRenderbuffers(1, &r->rb_color);
        if (r->rb_depth) gl->DeleteRenderbuffers(1, &r->rb_depth);
        if (r->tex) gl->DeleteTextures(1, &r->tex);
        GLuint bufs[3] = {r->vbo_corner, r->vbo_inst, r->vbo_c}, vaos[2] = {r->vao_p, r->vao_c};
        if (r->vbo_corner) gl->DeleteBuffers(3, bufs);
        if (r->vao_p) gl->DeleteVertexArrays(2, vaos);
    }
    sph_glctx_destroy(r->ctx);
    if (r->have_font) sph_font_free(&r->font);
    sph_overlay_free(&r->ov);
    free(r->inst);
    free(r->vals);
    free(r->v);
    free(r);
}

sph_glctx *sph_renderer_context(const sph_renderer *r)
{
    return r->ctx;
}

const char *sph_renderer_info(const sph_renderer *r)
{
    return r->info;
}

void sph_renderer_size(const sph_renderer *r, int *w, int *h)
{
    *w = r->w;
    *h = r->h;
}

const sph_camera *sph_renderer_camera(const sph_renderer *r)
{
    return &r->cam;
}

const sph_overlay *sph_renderer_overlay(const sph_renderer *r)
{
    return &r->ov;
}

sph_view sph_view_default(const sph_sim *sim)
{
    sph_view v;
    memset(&v, 0, sizeof v);
    v.field = sph_color_field_default(sim);
    v.overlays = SPH_OV_BIT(LEGEND) | SPH_OV_BIT(HUD);
    v.selected = -1;
    v.slice_z = 0.5f * (sim->def.domain_min[2] + sim->def.domain_max[2]);
    v.orbit = sph_orbit_default();
    v.hud.steps_per_s = -1;
    v.hud.last_pass = -1;
    return v;
}

float sph_particle_radius(const sph_sim *sim)
{
    float s = INFINITY;
    for (int b = 0; b < sim->def.n_blocks; b++)
        if (sim->def.blocks[b].spacing > 0 && sim->def.blocks[b].spacing < s) s = sim->def.blocks[b].spacing;
    if (!isfinite(s)) s = 0.5f * sim->def.h;
    return 0.5f * s;
}

/* ---- the frame ----------------------------------------------------------- */

static bool grow_particles(sph_renderer *r, uint32_t n)
{
    if (n <= r->cap_inst) return true;
    inst *a = realloc(r->inst, (size_t)n * sizeof *a);
    if (a) r->inst = a;
    float *b = realloc(r->vals, (size_t)n * sizeof *b);
    if (b) r->vals = b;
    if (!a || !b) return false;
    r->cap_inst = n;
    return true;
}

static int digits_of(uint32_t v)
{
    int d = 1;
    while (v >= 10) {
        v /= 10;
        d++;
    }
    return d;
}

/* Clips drawing to the view's rectangle (the world's things: the domain,
 * particles, world overlays), so a zoomed view stays out of the legend and
 * the strip. */
static void clip_to_view(sph_renderer *r, bool on)
{
    sph_gl *gl = &r->gl;
    if (!on) {
        gl->Disable(GL_SCISSOR_TEST);
        return;
    }
    const int *rc = r->cam.rect;
    gl->Enable(GL_SCISSOR_TEST);
    gl->Scissor(rc[0], r->h - rc[1] - rc[3], rc[2], rc[3]); /* GL counts rows from the bottom */
}

/* The view's ring (the push/pull reach at the cursor), as 64 segments. */
static void draw_ring(sph_renderer *r, const sph_view *v)
{
    const uint32_t c = v->ring_active ? SPH_RGBA(255, 210, 90, 230) : SPH_RGBA(230, 230, 240, 150);
    float prev[2] = {0, 0};
    bool have = false;
    for (int k = 0; k <= 64; k++) {
        float a = 6.2831853f * (float)k / 64.0f, p[3] = {v->ring_at[0] + v->ring_radius * cosf(a),
                                                          v->ring_at[1] + v->ring_radius * sinf(a), v->ring_at[2]};
        float px[2], depth;
        bool ok = sph_camera_project(&r->cam, p, px, &depth);
        if (ok && have) canvas_line(r, prev[0], prev[1], px[0], px[1], 1.5f, c);
        prev[0] = px[0];
        prev[1] = px[1];
        have = ok;
    }
}

void sph_renderer_side_free(const sph_renderer *r, int rc[4])
{
    const int used = (int)ceilf(r->side_used);
    rc[0] = r->side[0];
    rc[1] = r->side[1] + used;
    rc[2] = r->side[2];
    rc[3] = r->side[3] > used ? r->side[3] - used : 0;
}

/* The backend's field a colour field is made of (norm: a vector's length);
 * -1 for those the device does not hold (keys, neighbour counts). */
static int device_field(sph_color_field f, bool *norm)
{
    *norm = (int)f < SPH_FIELD_COUNT && sph_field_infos[f].vector;
    return (int)f < SPH_FIELD_COUNT ? (int)f : -1;
}

/* Overlays built from the particles' data on the host (the grid needs only
 * the cells, the HUD syncs what it shows, the legend reads its range). */
#define HOST_LAYERS                                                                                                \
    (SPH_OV_BIT(KEYS) | SPH_OV_BIT(COLLISIONS) | SPH_OV_BIT(NEIGHBOURS) | SPH_OV_BIT(FORCES) | SPH_OV_BIT(INDEX))

/* The particles as attributes read from the backend's buffers: a coordinate
 * or component each, at offset d * N floats (unused ones alias the first),
 * and the wall flag (FIXED) where the scene has wall particles (else 0: the
 * positions aliased, not read: u_walls). */
static void bind_direct(sph_renderer *r, const sph_sim *sim, unsigned pos, unsigned val, int comps, unsigned fixed)
{
    sph_gl *gl = &r->gl;
    const size_t row = (size_t)sim->n * sizeof(float);
    gl->BindVertexArray(r->vao_d);
    gl->BindBuffer(GL_ARRAY_BUFFER, pos);
    for (int d = 0; d < 3; d++)
        gl->VertexAttribPointer((GLuint)(1 + d), 1, GL_FLOAT, GL_FALSE, 0,
                                (const void *)(uintptr_t)(d < sim->dim ? (size_t)d * row : 0));
    gl->BindBuffer(GL_ARRAY_BUFFER, fixed ? fixed : pos);
    gl->VertexAttribPointer(7, 1, GL_FLOAT, GL_FALSE, 0, NULL);
    gl->BindBuffer(GL_ARRAY_BUFFER, val);
    for (int c = 0; c < 3; c++)
        gl->VertexAttribPointer((GLuint)(4 + c), 1, GL_FLOAT, GL_FALSE, 0,
                                (const void *)(uintptr_t)(c < comps ? (size_t)c * row : 0));
}

/* The box of the particles drawn (sph_renderer_shows says the rule), into
 * r->keep_lo and keep_hi; the camera is fitted. Unbounded: 3e38 m, as the
 * shaders' floats hold. */
static void keep_box(sph_renderer *r, const sph_sim *sim, const sph_view *v)
{
    for (int d = 0; d < 3; d++) r->keep_lo[d] = -3.0e38f, r->keep_hi[d] = 3.0e38f;
    if (sim->dim != 3) return;
    const float margin = 0.5f * sph_particle_radius(sim);
    /* the slice's overlays: the fluid cut open at the slice, the camera's
     * side removed, so the slice's cells are seen, not hidden */
    if (v->overlays & (SPH_OV_BIT(GRID) | SPH_OV_BIT(KEYS) | SPH_OV_BIT(COLLISIONS)))
        r->keep_hi[2] = v->slice_z + margin;
    /* the box's wall particles cover its six faces and would hide what is
     * inside from any side: those of the faces turned towards the eye are
     * left out, as a cut-away drawing does; the fluid and the obstacles lie
     * inside the domain, the near walls' layers outside it (the first half a
     * spacing out: sph_wall_particles_place) */
    if (sim->def.wall_model != SPH_WALL_PARTICLES) return;
    for (int d = 0; d < 3; d++) {
        const float lo = (float)sim->def.domain_min[d], hi = (float)sim->def.domain_max[d];
        if (r->cam.eye[d] < lo) r->keep_lo[d] = fmaxf(r->keep_lo[d], lo - margin);
        if (r->cam.eye[d] > hi) r->keep_hi[d] = fminf(r->keep_hi[d], hi + margin);
    }
}

bool sph_renderer_shows(const sph_renderer *r, const float x[3])
{
    for (int d = 0; d < 3; d++)
        if (!(x[d] >= r->keep_lo[d] && x[d] <= r->keep_hi[d])) return false;
    return true;
}

bool sph_render(sph_renderer *r, const sph_sim *sim, const sph_view *v, char *err, size_t n)
{
    sph_gl *gl = &r->gl;
    const unsigned L = v->overlays;
    sph_color_field f = v->field;
    if (sph_color_field_missing(sim, f)) f = sph_color_field_default(sim);
    bool norm;
    const int df = device_field(f, &norm);
    /* Straight from the GL backend's buffers when the simulation runs in this
     * renderer's context (created sharing sph_renderer_context; the view
     * hands over its buffers in v->device) and the colour field is on the
     * device. Otherwise the host copy is refreshed (a copy per frame; nothing
     * to do on the CPU backend), and so it is for overlays that show the
     * particles' data. */
    make_current(r);
    const sph_gl_fields *dev = v->device;
    const bool direct = r->gl43 && df >= 0 && dev && dev->ctx == r->ctx;
    r->drew_direct = direct;
    if (!direct || (L & HOST_LAYERS))
        sph_sim_sync(sim, SPH_SYNC_ALL);
    /* else the HUD's density error and energies are reduced on the device
     * (sph_sim_stats, sph_backend.stats): a few floats, no field */
    make_current(r);
    if (direct && !make_direct(r, err, n)) return false;
    const float fs = r->font.px[SPH_TEXT_SMALL];
    int rc[4], legend_w;
    const bool strip = hud_layout(r, sim, L, v->side_px, rc, &legend_w);
    float dom_lo[3], dom_hi[3]; /* the domain and the wall particles outside it */
    sph_wall_particles_bounds(&sim->def, dom_lo, dom_hi);
    sph_camera_fit(&r->cam, sim->dim, dom_lo, dom_hi, &v->orbit, r->w, r->h, rc);
    keep_box(r, sim, v);

    /* overlays (GL-free) */
    sph_overlay_opts oo = {.layers = L, .selected = v->selected, .slice_z = v->slice_z, .px_per_m = r->cam.px_per_m};
    if (strip) {
        uint32_t big = sim->n > sim->S.table_size ? sim->n : sim->S.table_size;
        float box = sph_font_width(&r->font, SPH_TEXT_SMALL, "0") * (float)digits_of(big ? big - 1 : 0) + 6.0f;
        box = fmaxf(box, 1.6f * fs);
        oo.strip_cols = (int)((float)r->strip[2] / box) - 3;
        if (oo.strip_cols < 4) oo.strip_cols = 4;
    }
    if (!sph_overlay_build(sim, &oo, &r->ov)) {
        snprintf(err, n, "out of memory for the overlays");
        return false;
    }

    /* particle colours */
    float lo = 0, hi = 0;
    unsigned range_buf = 0, pos_buf = 0, val_buf = 0, fixed_buf = 0;
    if (direct) {
        /* the range is computed on the device for the vertex shader; read
         * back (8 bytes) only for the legend's numbers */
        float lo_hi[2] = {0, 0};
        bool need = legend_w && !v->fixed_range;
        if (!dev->range(sim, df, norm, &range_buf, need ? lo_hi : NULL) || !dev->buffer(sim, SPH_FIELD_POS, &pos_buf) ||
            !dev->buffer(sim, df, &val_buf)) {
            snprintf(err, n, "the GL backend has no buffer for %s", sph_color_field_names[f]);
            return false;
        }
        /* the wall flag: no buffer where the scene has no wall particle */
        if (sim->P.fixed && !dev->buffer(sim, SPH_FIELD_FIXED, &fixed_buf)) {
            snprintf(err, n, "the GL backend has no buffer for the wall particles' flag");
            return false;
        }
        make_current(r);
        lo = lo_hi[0];
        hi = lo_hi[1];
    } else {
        if (!grow_particles(r, sim->n)) {
            snprintf(err, n, "out of memory for %u particles", sim->n);
            return false;
        }
        sph_color_field_values(sim, f, r->vals, &lo, &hi);
    }
    if (v->fixed_range) {
        lo = v->range[0];
        hi = v->range[1];
    }
    /* the same function the legend and the tests use */
    for (uint32_t i = 0; !direct && i < sim->n; i++) {
        inst *p = &r->inst[i];
        p->x = sim->P.pos[0][i];
        p->y = sim->P.pos[1][i];
        p->z = sim->dim == 3 ? sim->P.pos[2][i] : 0.0f;
        p->rgba = sph_color_of(f, r->vals[i], lo, hi);
        if (sph_is_wall(&sim->P, i)) p->rgba = sph_color_dimmed(p->rgba); /* the fluid stands out */
    }

    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    gl->Viewport(0, 0, r->w, r->h);
    gl->Disable(GL_SCISSOR_TEST);
    gl->ClearColor((float)(BG & 255) / 255.0f, (float)((BG >> 8) & 255) / 255.0f, (float)((BG >> 16) & 255) / 255.0f, 1.0f);
    gl->ClearDepth(1.0);
    gl->DepthMask(GL_TRUE);
    gl->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    clip_to_view(r, true);

    /* canvas under: the domain */
    float dl[3], dh[3]; /* the domain in the particles' frame (sim->origin: the domain's point nearest 0) */
    for (int d = 0; d < 3; d++) dl[d] = (float)sim->def.domain_min[d], dh[d] = (float)sim->def.domain_max[d];
    if (sim->dim == 2) {
        float a[2], b[2];
        float p0[3] = {dl[0], dl[1], 0}, p1[3] = {dh[0], dh[1], 0};
        sph_camera_project(&r->cam, p0, a, NULL);
        sph_camera_project(&r->cam, p1, b, NULL);
        canvas_rect(r, a[0], b[1], b[0], a[1], SPH_RGBA(42, 45, 54, 255));
        canvas_outline(r, a[0] - 1, b[1] - 1, b[0] + 1, a[1] + 1, 1, SPH_RGBA(110, 115, 130, 255));
    } else {
        for (int e = 0; e < 12; e++) { /* the 12 edges of the box */
            int axis = e / 4, o1 = e & 1, o2 = (e >> 1) & 1;
            float a[3], b[3], pa[2], pb[2];
            int u = (axis + 1) % 3, w = (axis + 2) % 3;
            a[axis] = dl[axis];
            b[axis] = dh[axis];
            a[u] = b[u] = o1 ? dh[u] : dl[u];
            a[w] = b[w] = o2 ? dh[w] : dl[w];
            if (sph_camera_project(&r->cam, a, pa, NULL) && sph_camera_project(&r->cam, b, pb, NULL))
                canvas_line(r, pa[0], pa[1], pb[0], pb[1], 1.0f, SPH_RGBA(110, 115, 130, 255));
        }
        if (L & (SPH_OV_BIT(GRID) | SPH_OV_BIT(KEYS) | SPH_OV_BIT(COLLISIONS))) {
            float c[4][3] = {{dl[0], dl[1], v->slice_z}, {dh[0], dl[1], v->slice_z}, {dh[0], dh[1], v->slice_z},
                             {dl[0], dh[1], v->slice_z}};
            float p[4][2];
            bool ok = true;
            for (int k = 0; k < 4; k++) ok &= sph_camera_project(&r->cam, c[k], p[k], NULL);
            if (ok) {
                canvas_tri(r, p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1], SPH_RGBA(80, 90, 120, 60));
                canvas_tri(r, p[0][0], p[0][1], p[2][0], p[2][1], p[3][0], p[3][1], SPH_RGBA(80, 90, 120, 60));
            }
        }
    }
    if (!canvas_flush(r)) goto oom;

    /* particles: one instanced draw */
    float rad = sph_particle_radius(sim);
    float min_px = 1.0f;
    if (r->cam.px_per_m > 0 && rad * r->cam.px_per_m < min_px) rad = min_px / r->cam.px_per_m;
    r->radius_px = rad * r->cam.px_per_m;
    if (sim->n) {
        const ploc *pl = direct ? &r->ld : &r->lp;
        gl->UseProgram(direct ? r->prog_d : r->prog_p);
        gl->UniformMatrix4fv(pl->view, 1, GL_FALSE, r->cam.view);
        gl->UniformMatrix4fv(pl->proj, 1, GL_FALSE, r->cam.proj);
        gl->Uniform1f(pl->radius, rad);
        /* a rim keeps touching discs apart; on discs of a few pixels it would be all there is */
        gl->Uniform1f(pl->rim, r->radius_px >= 4.0f ? 0.35f : 0.0f);
        gl->Uniform1i(pl->sphere, sim->dim == 3);
        /* the cut-aways (keep_box) */
        gl->Uniform3f(pl->keep_lo, r->keep_lo[0], r->keep_lo[1], r->keep_lo[2]);
        gl->Uniform3f(pl->keep_hi, r->keep_hi[0], r->keep_hi[1], r->keep_hi[2]);
        if (sim->dim == 3) {
            gl->Enable(GL_DEPTH_TEST);
            gl->DepthFunc(GL_LESS);
        } else {
            gl->Disable(GL_DEPTH_TEST);
        }
        if (direct) {
            gl->Uniform1i(pl->dim, sim->dim);
            gl->Uniform1i(pl->comps, norm ? sim->dim : 1);
            gl->Uniform1i(pl->fixed, v->fixed_range);
            gl->Uniform2f(pl->range, lo, hi);
            gl->Uniform1i(pl->walls, fixed_buf != 0);
            bind_direct(r, sim, pos_buf, val_buf, norm ? sim->dim : 1, fixed_buf);
            r->gc.BindBufferBase(GL_UNIFORM_BUFFER, 0, range_buf);
            gl->ActiveTexture(GL_TEXTURE1);
            gl->BindTexture(GL_TEXTURE_2D, r->tex_cmap);
            gl->ActiveTexture(GL_TEXTURE0);
            /* the compute passes' writes, seen as vertices and a uniform block */
            r->gc.MemoryBarrier(GL_VERTEX_ATTRIB_ARRAY_BARRIER_BIT | GL_UNIFORM_BARRIER_BIT);
        } else {
            gl->BindVertexArray(r->vao_p);
            gl->BindBuffer(GL_ARRAY_BUFFER, r->vbo_inst);
            gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)((size_t)sim->n * sizeof(inst)), r->inst, GL_STREAM_DRAW);
        }
        gl->DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, (GLsizei)sim->n);
        if (direct) { /* the vertex array lets go of the backend's buffers: a reset's deleted ones are freed at once */
            gl->BindBuffer(GL_ARRAY_BUFFER, 0);
            for (GLuint k = 1; k <= 7; k++) gl->VertexAttribPointer(k, 1, GL_FLOAT, GL_FALSE, 0, NULL);
        }
        gl->Disable(GL_DEPTH_TEST);
    }

    /* canvas over: world overlays (clipped), then the strip, notes, HUD, legend */
    canvas_overlay(r, SPH_SPACE_WORLD);
    if (v->ring_radius > 0) draw_ring(r, v);
    if (!canvas_flush(r)) goto oom;
    clip_to_view(r, false);
    canvas_overlay(r, SPH_SPACE_STRIP);
    if (L & ~(SPH_OV_BIT(HUD) | SPH_OV_BIT(LEGEND) | SPH_OV_BIT(TIMINGS))) hud_notes(r, rc);
    if (r->side[2] > 0) canvas_rect(r, (float)r->side[0], (float)r->side[1], (float)(r->side[0] + r->side[2]),
                                    (float)(r->side[1] + r->side[3]), SPH_RGBA(24, 26, 32, 255));
    if (L & (SPH_OV_BIT(HUD) | SPH_OV_BIT(TIMINGS))) hud_draw(r, sim, v);
    if (legend_w) hud_legend(r, sim, f, lo, hi);
    if (v->panel && v->panel_lines > 0) hud_panel(r, v->panel, v->panel_lines, v->panel_keep_px);
    if (!canvas_flush(r)) goto oom;
    gl->BindVertexArray(0);
    GLenum e = gl->GetError();
    if (e != GL_NO_ERROR) {
        snprintf(err, n, "%s: GL error 0x%x while drawing", sph_gl_backend_names[r->backend], (unsigned)e);
        return false;
    }
    return true;
oom:
    clip_to_view(r, false);
    r->oom = false;
    r->nv = 0;
    snprintf(err, n, "out of memory for the overlays");
    return false;
}

void sph_renderer_read_rgb(sph_renderer *r, uint8_t *rgb)
{
    sph_gl *gl = &r->gl;
    make_current(r);
    uint8_t *row = malloc((size_t)r->w * 4);
    if (!row) {
        memset(rgb, 0, (size_t)r->w * r->h * 3);
        return;
    }
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    gl->PixelStorei(GL_PACK_ALIGNMENT, 1);
    for (int y = 0; y < r->h; y++) {
        /* GL's rows start at the bottom; the image's at the top */
        gl->ReadPixels(0, r->h - 1 - y, r->w, 1, GL_RGBA, GL_UNSIGNED_BYTE, row);
        uint8_t *out = rgb + (size_t)y * r->w * 3;
        for (int x = 0; x < r->w; x++) {
            out[3 * x] = row[4 * x];
            out[3 * x + 1] = row[4 * x + 1];
            out[3 * x + 2] = row[4 * x + 2];
        }
    }
    free(row);
}

void sph_renderer_present(sph_renderer *r, int w, int h)
{
    sph_gl *gl = &r->gl;
    gl->BindFramebuffer(GL_READ_FRAMEBUFFER, r->fbo);
    gl->BindFramebuffer(GL_DRAW_FRAMEBUFFER, 0);
    gl->Viewport(0, 0, w, h);
    gl->ClearColor(0, 0, 0, 1);
    gl->Clear(GL_COLOR_BUFFER_BIT);
    gl->BlitFramebuffer(0, 0, r->w, r->h, 0, 0, r->w, r->h, GL_COLOR_BUFFER_BIT, GL_NEAREST);
    gl->BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
}

bool sph_renderer_drew_direct(const sph_renderer *r)
{
    return r->drew_direct;
}

int32_t sph_renderer_pick(const sph_renderer *r, const sph_sim *sim, const float px[2], float max_px)
{
    /* a click, not a frame: positions from the host, and the ids the caller
     * names the particle by (the reorder pass moves them every step) */
    sph_sim_sync(sim, SPH_SYNC_FIELD(SPH_FIELD_POS) | SPH_SYNC_ID);
    int32_t best = -1;
    float best_d = max_px * max_px, best_depth = INFINITY;
    for (uint32_t i = 0; i < sim->n; i++) {
        float x[3] = {sim->P.pos[0][i], sim->P.pos[1][i], sim->dim == 3 ? sim->P.pos[2][i] : 0.0f}, p[2], depth = 0;
        if (!sph_renderer_shows(r, x) || !sph_camera_project(&r->cam, x, p, &depth)) continue;
        float d = (p[0] - px[0]) * (p[0] - px[0]) + (p[1] - px[1]) * (p[1] - px[1]);
        /* nearest on screen; among those under the cursor, nearest to the eye */
        bool under = d <= r->radius_px * r->radius_px;
        if ((under && depth < best_depth) || (best_depth == INFINITY && d < best_d)) {
            best = (int32_t)i;
            best_d = d;
            if (under) best_depth = depth;
        }
    }
    return best;
}

bool sph_write_png(const char *path, const uint8_t *rgb, int w, int h, char *err, size_t n)
{
    return sph_io_write_png(path, rgb, w, h, err, n); /* checked writes, a temporary, a rename */
}
