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

#include "font.h"
#include "gl_context.h"
#include "gl_table.h"
#include "gpu.h"
#include "shaders.h" /* generated from shaders/ by src/render/module.mk */

const char *const sph_gl_backend_names[SPH_GL_BACKEND_COUNT] = {
#define SPH_GL_BACKEND_NAME(id, name, about) name,
    SPH_GL_BACKENDS(SPH_GL_BACKEND_NAME)
#undef SPH_GL_BACKEND_NAME
};

typedef struct vtx {
    float x, y, u, v; /* [px], atlas */
    uint32_t rgba;
} vtx;

typedef struct inst {
    float x, y, z; /* [m] */
    uint32_t rgba;
} inst;

/* Uniforms of a particle program. */
typedef struct ploc {
    GLint view, proj, radius, sphere, cut, rim, dim, comps, fixed, range;
} ploc;

struct sph_renderer {
    sph_gl gl;
    sph_gl_backend backend;
    sph_glctx *ctx;
    char info[256];
    int w, h;
    GLuint fbo, rb_color, rb_depth;
    GLuint prog_p, prog_c;
    ploc lp;
    GLint uc_size, uc_atlas;
    GLuint vao_p, vbo_corner, vbo_inst, vao_c, vbo_c, tex;
    /* Drawing from the GL backend's buffers (OpenGL 4.3): its program, with
     * the colour map as a texture, made on first use. */
    bool gl43;
    sph_gl_compute gc;
    GLuint prog_d, vao_d, tex_cmap;
    ploc ld;
    bool drew_direct;
    sph_font font;
    bool have_font;
    inst *inst;
    float *vals;
    size_t cap_inst;
    vtx *v;
    size_t nv, cap_v;
    bool oom;
    sph_camera cam;
    sph_overlay ov;
    float radius_px;
    int strip[4], legend[4];
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
static void font_sizes(int h, float *small, float *normal)
{
    float nm = roundf((float)h / 42.0f);
    nm = nm < 11 ? 11 : nm > 24 ? 24 : nm;
    *normal = nm;
    *small = roundf(nm * 0.85f) < 10 ? 10 : roundf(nm * 0.85f);
}

static bool make_font(sph_renderer *r, char *err, size_t n)
{
    float s, nm;
    font_sizes(r->h, &s, &nm);
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
    l->cut = gl->GetUniformLocation(prog, "u_cut");
    l->rim = gl->GetUniformLocation(prog, "u_rim");
    l->dim = gl->GetUniformLocation(prog, "u_dim");
    l->comps = gl->GetUniformLocation(prog, "u_comps");
    l->fixed = gl->GetUniformLocation(prog, "u_fixed");
    l->range = gl->GetUniformLocation(prog, "u_range");
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
        sph_gl_load_epoxy(&r->gl);
    if (backend != SPH_GL_CURRENT && !r->ctx) {
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
    for (GLuint a = 1; a <= 6; a++) {
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
    if (r->backend == SPH_GL_EGL) sph_glctx_make_current(r->ctx);
    if (r->backend == SPH_GL_OSMESA) sph_glctx_make_current_osmesa(r->ctx);
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
    if (r->backend == SPH_GL_EGL) sph_glctx_destroy(r->ctx);
    if (r->backend == SPH_GL_OSMESA) sph_glctx_destroy_osmesa(r->ctx);
    if (r->have_font) sph_font_free(&r->font);
    sph_overlay_free(&r->ov);
    free(r->inst);
    free(r->vals);
    free(r->v);
    free(r);
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

/* ---- the canvas: triangles in pixels -------------------------------------- */

static void push(sph_renderer *r, float x, float y, float u, float v, uint32_t c)
{
    if (r->nv == r->cap_v) {
        size_t cap = r->cap_v ? 2 * r->cap_v : 4096;
        vtx *p = realloc(r->v, cap * sizeof *p);
        if (!p) {
            r->oom = true;
            return;
        }
        r->v = p;
        r->cap_v = cap;
    }
    r->v[r->nv++] = (vtx){x, y, u, v, c};
}

static void tri(sph_renderer *r, float x0, float y0, float x1, float y1, float x2, float y2, uint32_t c)
{
    float u = r->font.white_uv[0], v = r->font.white_uv[1];
    push(r, x0, y0, u, v, c);
    push(r, x1, y1, u, v, c);
    push(r, x2, y2, u, v, c);
}

static void rect(sph_renderer *r, float x0, float y0, float x1, float y1, uint32_t c)
{
    tri(r, x0, y0, x1, y0, x1, y1, c);
    tri(r, x0, y0, x1, y1, x0, y1, c);
}

static void line(sph_renderer *r, float ax, float ay, float bx, float by, float w, uint32_t c)
{
    float dx = bx - ax, dy = by - ay, len = sqrtf(dx * dx + dy * dy);
    if (!(len > 0)) return;
    float nx = -dy / len * 0.5f * w, ny = dx / len * 0.5f * w;
    tri(r, ax + nx, ay + ny, bx + nx, by + ny, bx - nx, by - ny, c);
    tri(r, ax + nx, ay + ny, bx - nx, by - ny, ax - nx, ay - ny, c);
}

static void arrow_head(sph_renderer *r, float ax, float ay, float bx, float by, float size, uint32_t c)
{
    float dx = bx - ax, dy = by - ay, len = sqrtf(dx * dx + dy * dy);
    if (!(len > 0)) return;
    float s = fminf(size, 0.5f * len);
    float ux = dx / len, uy = dy / len;
    tri(r, bx, by, bx - s * ux - 0.5f * s * uy, by - s * uy + 0.5f * s * ux, bx - s * ux + 0.5f * s * uy,
        by - s * uy - 0.5f * s * ux, c);
}

static int segments(float rad)
{
    int k = (int)(rad * 1.5f);
    return k < 12 ? 12 : k > 96 ? 96 : k;
}

static void disc(sph_renderer *r, float cx, float cy, float rad, uint32_t fill, uint32_t edge)
{
    const int k = segments(rad);
    const float step = 6.2831853f / (float)k;
    for (int i = 0; i < k; i++) {
        float a0 = step * (float)i, a1 = step * (float)(i + 1);
        float x0 = cx + rad * cosf(a0), y0 = cy + rad * sinf(a0), x1 = cx + rad * cosf(a1), y1 = cy + rad * sinf(a1);
        if (fill >> 24) tri(r, cx, cy, x0, y0, x1, y1, fill);
        if (edge >> 24) line(r, x0, y0, x1, y1, 1.5f, edge);
    }
}

static void outline(sph_renderer *r, float x0, float y0, float x1, float y1, float w, uint32_t c)
{
    rect(r, x0, y0, x1, y0 + w, c);
    rect(r, x0, y1 - w, x1, y1, c);
    rect(r, x0, y0 + w, x0 + w, y1 - w, c);
    rect(r, x1 - w, y0 + w, x1, y1 - w, c);
}

/* Text with its top-left at (x, y). */
static void text(sph_renderer *r, int size, float x, float y, uint32_t c, const char *s)
{
    sph_glyph_quad q[128];
    int n = sph_font_quads(&r->font, size, x, y, s, q, 128);
    for (int i = 0; i < n; i++) {
        push(r, q[i].x0, q[i].y0, q[i].s0, q[i].t0, c);
        push(r, q[i].x1, q[i].y0, q[i].s1, q[i].t0, c);
        push(r, q[i].x1, q[i].y1, q[i].s1, q[i].t1, c);
        push(r, q[i].x0, q[i].y0, q[i].s0, q[i].t0, c);
        push(r, q[i].x1, q[i].y1, q[i].s1, q[i].t1, c);
        push(r, q[i].x0, q[i].y1, q[i].s0, q[i].t1, c);
    }
}

/* Text centred vertically on y, aligned on x; an optional dark backdrop. */
static void text_at(sph_renderer *r, int size, float x, float y, sph_align al, uint32_t c, const char *s,
                    bool backdrop)
{
    float w = sph_font_width(&r->font, size, s), hgt = r->font.px[size];
    float x0 = al == SPH_ALIGN_CENTER ? x - 0.5f * w : al == SPH_ALIGN_RIGHT ? x - w : x;
    float y0 = y - 0.5f * hgt;
    x0 = roundf(x0);
    y0 = roundf(y0);
    if (backdrop) rect(r, x0 - 2, y0, x0 + w + 2, y0 + hgt, SPH_RGBA(0, 0, 0, 150));
    text(r, size, x0, y0, c, s);
}

static bool flush(sph_renderer *r)
{
    if (r->oom) return false;
    if (!r->nv) return true;
    sph_gl *gl = &r->gl;
    gl->UseProgram(r->prog_c);
    gl->Uniform2f(r->uc_size, (float)r->w, (float)r->h);
    gl->Uniform1i(r->uc_atlas, 0);
    gl->ActiveTexture(GL_TEXTURE0);
    gl->BindTexture(GL_TEXTURE_2D, r->tex);
    gl->Disable(GL_DEPTH_TEST);
    gl->Enable(GL_BLEND);
    gl->BlendFuncSeparate(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
    gl->BindVertexArray(r->vao_c);
    gl->BindBuffer(GL_ARRAY_BUFFER, r->vbo_c);
    gl->BufferData(GL_ARRAY_BUFFER, (GLsizeiptr)(r->nv * sizeof(vtx)), r->v, GL_STREAM_DRAW);
    gl->DrawArrays(GL_TRIANGLES, 0, (GLsizei)r->nv);
    gl->Disable(GL_BLEND);
    r->nv = 0;
    return true;
}

/* ---- world and strip primitives ------------------------------------------ */

static bool to_px(const sph_renderer *r, const float x[3], sph_space sp, float px[2])
{
    if (sp == SPH_SPACE_STRIP) {
        const sph_overlay *ov = &r->ov;
        px[0] = (float)r->strip[0] + x[0] * (float)r->strip[2] / (float)(ov->strip_cols ? ov->strip_cols : 1);
        px[1] = (float)r->strip[1] + x[1] * (float)r->strip[3] / (float)(ov->strip_rows ? ov->strip_rows : 1);
        return true;
    }
    return sph_camera_project(&r->cam, x, px, NULL);
}

/* [px per m] at a world point (perspective: varies with depth). */
static float scale_at(const sph_renderer *r, const float x[3])
{
    if (r->cam.dim != 3) return r->cam.px_per_m;
    float a[2], b[2], y[3];
    /* along the camera's right axis (first row of the view's rotation) */
    for (int k = 0; k < 3; k++) y[k] = x[k] + r->cam.view[k * 4];
    if (!sph_camera_project(&r->cam, x, a, NULL) || !sph_camera_project(&r->cam, y, b, NULL)) return 0;
    return sqrtf((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]));
}

/* The primitives of one space: the world's (clipped to the view) or the strip's. */
static void draw_overlay(sph_renderer *r, sph_space space)
{
    const sph_overlay *ov = &r->ov;
    for (int i = 0; i < ov->n_boxes; i++) {
        const sph_ov_box *b = &ov->boxes[i];
        if (b->space != space) continue;
        float c[4][3] = {{b->min[0], b->min[1], b->z}, {b->max[0], b->min[1], b->z},
                         {b->max[0], b->max[1], b->z}, {b->min[0], b->max[1], b->z}};
        float p[4][2];
        bool ok = true;
        for (int k = 0; k < 4; k++) ok &= to_px(r, c[k], (sph_space)b->space, p[k]);
        if (!ok) continue;
        if (b->fill >> 24) {
            tri(r, p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1], b->fill);
            tri(r, p[0][0], p[0][1], p[2][0], p[2][1], p[3][0], p[3][1], b->fill);
        }
        if (b->edge >> 24) {
            if (b->space == SPH_SPACE_STRIP) {
                outline(r, p[0][0], p[0][1], p[2][0], p[2][1], 1.0f, b->edge);
            } else {
                for (int k = 0; k < 4; k++) line(r, p[k][0], p[k][1], p[(k + 1) % 4][0], p[(k + 1) % 4][1], 1.0f, b->edge);
            }
        }
    }
    for (int i = 0; i < ov->n_lines; i++) {
        const sph_ov_line *l = &ov->lines[i];
        if (l->space != space) continue;
        float a[2], b[2];
        if (!to_px(r, l->a, (sph_space)l->space, a) || !to_px(r, l->b, (sph_space)l->space, b)) continue;
        line(r, a[0], a[1], b[0], b[1], l->width, l->rgba);
        if (l->arrow) arrow_head(r, a[0], a[1], b[0], b[1], 3.0f + 2.5f * l->width, l->rgba);
    }
    for (int i = 0; i < ov->n_discs; i++) {
        const sph_ov_disc *d = &ov->discs[i];
        if (d->space != space) continue;
        float c[2];
        if (!to_px(r, d->c, (sph_space)d->space, c)) continue;
        float rad = fmaxf(d->r * scale_at(r, d->c), d->r_min_px);
        disc(r, c[0], c[1], rad, d->fill, d->edge);
    }
    for (int i = 0; i < ov->n_labels; i++) {
        const sph_ov_label *l = &ov->labels[i];
        if (l->space != space) continue;
        float p[2];
        if (!to_px(r, l->pos, (sph_space)l->space, p)) continue;
        text_at(r, l->size, p[0], p[1], (sph_align)l->align, l->rgba, l->text, l->space == SPH_SPACE_WORLD);
    }
}

/* ---- HUD, legend --------------------------------------------------------- */

static void draw_hud(sph_renderer *r, const sph_sim *sim, const sph_view *v)
{
    const float fn = r->font.px[SPH_TEXT_NORMAL], fs = r->font.px[SPH_TEXT_SMALL];
    const bool timings = v->overlays & SPH_OV_BIT(TIMINGS), hud = v->overlays & SPH_OV_BIT(HUD);
    char lines[10][128];
    int nl = 0;
    if (hud) {
        sph_hud_info info = v->hud;
        if (!timings) info.steps_per_s = -1; /* changes from run to run: only with the timings */
        nl = sph_hud_lines(sim, &info, lines, 10);
    }
    int bars = 0;
    double mx = 0;
    if (timings)
        for (int p = 0; p < SPH_PASS_COUNT; p++)
            if (sim->in_pipeline[p]) {
                bars++;
                if (sim->timing[p].last_ms > mx) mx = sim->timing[p].last_ms;
            }
    if (!nl && !bars) return;
    float w = 0;
    for (int i = 0; i < nl; i++) w = fmaxf(w, sph_font_width(&r->font, SPH_TEXT_NORMAL, lines[i]));
    const float name_w = sph_font_width(&r->font, SPH_TEXT_SMALL, "pressure_force  "), bar_w = 6.0f * fn;
    const float ms_w = sph_font_width(&r->font, SPH_TEXT_SMALL, " 00.000 ms");
    if (bars) w = fmaxf(w, name_w + bar_w + ms_w);
    float x0 = (float)r->cam.rect[0] + 4, y0 = (float)r->cam.rect[1] + 4;
    float hgt = (float)nl * fn * 1.2f + (float)bars * fs * 1.25f + (bars ? 0.3f * fn : 0) + 8;
    rect(r, x0, y0, x0 + w + 12, y0 + hgt, SPH_RGBA(0, 0, 0, 160));
    float y = y0 + 4;
    for (int i = 0; i < nl; i++, y += fn * 1.2f) text(r, SPH_TEXT_NORMAL, x0 + 6, y, SPH_RGBA(235, 235, 240, 255), lines[i]);
    if (bars) y += 0.3f * fn;
    for (int p = 0; p < SPH_PASS_COUNT && bars; p++) {
        if (!sim->in_pipeline[p]) continue;
        bool on = sim->enabled[p];
        uint32_t col = on ? SPH_RGBA(220, 220, 225, 255) : SPH_RGBA(120, 120, 125, 255);
        text(r, SPH_TEXT_SMALL, x0 + 6, y, col, sph_passes[p]->name);
        double ms = sim->timing[p].last_ms;
        float bw = mx > 0 ? (float)(ms / mx) * bar_w : 0;
        float bx = x0 + 6 + name_w;
        rect(r, bx, y + 0.2f * fs, bx + bar_w, y + 1.0f * fs, SPH_RGBA(60, 60, 70, 255));
        if (on) rect(r, bx, y + 0.2f * fs, bx + roundf(bw), y + 1.0f * fs, SPH_RGBA(240, 160, 60, 255));
        char ms_s[32];
        snprintf(ms_s, sizeof ms_s, " %.3f ms", ms);
        text(r, SPH_TEXT_SMALL, bx + bar_w, y, col, on ? ms_s : " off");
        y += fs * 1.25f;
    }
}

/* A box of text lines at the view's top-right corner. */
static void draw_panel(sph_renderer *r, const char (*lines)[128], int n)
{
    const float fs = r->font.px[SPH_TEXT_SMALL];
    float w = 0;
    for (int i = 0; i < n; i++) w = fmaxf(w, sph_font_width(&r->font, SPH_TEXT_SMALL, lines[i]));
    float x1 = (float)(r->cam.rect[0] + r->cam.rect[2]) - 4, x0 = x1 - w - 12, y0 = (float)r->cam.rect[1] + 4;
    rect(r, x0, y0, x1, y0 + (float)n * 1.25f * fs + 8, SPH_RGBA(0, 0, 0, 185));
    for (int i = 0; i < n; i++)
        text(r, SPH_TEXT_SMALL, x0 + 6, y0 + 4 + (float)i * 1.25f * fs, SPH_RGBA(235, 235, 240, 255), lines[i]);
}

static void fmt_num(char *out, size_t n, float v)
{
    snprintf(out, n, "%.4g", (double)v);
}

static void draw_legend(sph_renderer *r, const sph_sim *sim, sph_color_field f, float lo, float hi)
{
    const float fn = r->font.px[SPH_TEXT_NORMAL], fs = r->font.px[SPH_TEXT_SMALL];
    const float x0 = (float)r->legend[0], y0 = (float)r->legend[1], w = (float)r->legend[2], hgt = (float)r->legend[3];
    const uint32_t white = SPH_RGBA(235, 235, 240, 255), grey = SPH_RGBA(170, 170, 180, 255);
    char unit[48];
    snprintf(unit, sizeof unit, "[%s]", sph_color_field_unit(f, sim->dim));
    text_at(r, SPH_TEXT_NORMAL, x0 + 0.5f * w, y0 + 0.6f * fn, SPH_ALIGN_CENTER, white, sph_color_field_names[f], false);
    text_at(r, SPH_TEXT_SMALL, x0 + 0.5f * w, y0 + 0.6f * fn + 1.2f * fs, SPH_ALIGN_CENTER, grey, unit, false);
    float top = y0 + 1.4f * fn + 1.6f * fs, bot = y0 + hgt - fs;
    float bx0 = x0 + 4, bx1 = bx0 + fn;
    if (bot - top < 20) return;
    char s[32];
    if (sph_color_field_categorical(f)) {
        float cell = (bot - top) / 10.0f;
        for (int k = 0; k < 10; k++) {
            float ya = top + cell * (float)k;
            rect(r, bx0, ya + 1, bx1, ya + cell - 1, sph_colormap_category((uint32_t)k));
            snprintf(s, sizeof s, "%d", k);
            text_at(r, SPH_TEXT_SMALL, bx1 + 4, ya + 0.5f * cell, SPH_ALIGN_LEFT, white, s, false);
        }
        text_at(r, SPH_TEXT_SMALL, x0 + 0.5f * w, bot + 0.5f * fs, SPH_ALIGN_CENTER, grey, "key mod 10", false);
        return;
    }
    /* the bar, top = max; one band per pixel row */
    for (float y = top; y < bot; y += 1.0f) {
        float t = 1.0f - (y + 0.5f - top) / (bot - top);
        rect(r, bx0, y, bx1, fminf(y + 1.0f, bot), sph_colormap_viridis(t));
    }
    outline(r, bx0 - 1, top - 1, bx1 + 1, bot + 1, 1, grey);
    fmt_num(s, sizeof s, hi);
    text_at(r, SPH_TEXT_SMALL, bx1 + 4, top + 0.5f * fs, SPH_ALIGN_LEFT, white, s, false);
    fmt_num(s, sizeof s, 0.5f * (lo + hi));
    text_at(r, SPH_TEXT_SMALL, bx1 + 4, 0.5f * (top + bot), SPH_ALIGN_LEFT, white, s, false);
    fmt_num(s, sizeof s, lo);
    text_at(r, SPH_TEXT_SMALL, bx1 + 4, bot - 0.5f * fs, SPH_ALIGN_LEFT, white, s, false);
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

/* The backend's field a colour field is made of (norm: a vector's length);
 * -1 for those the device does not hold (keys, neighbour counts). */
static int device_field(sph_color_field f, bool *norm)
{
    *norm = f == SPH_COLOR_SPEED || f == SPH_COLOR_ACC_P || f == SPH_COLOR_ACC_V;
    switch (f) {
    case SPH_COLOR_DENSITY: return SPH_FIELD_RHO;
    case SPH_COLOR_PRESSURE: return SPH_FIELD_P;
    case SPH_COLOR_SPEED: return SPH_FIELD_VEL;
    case SPH_COLOR_ACC_P: return SPH_FIELD_ACC_P;
    case SPH_COLOR_ACC_V: return SPH_FIELD_ACC_V;
    default: return -1;
    }
}

/* Overlays built from the particles' data on the host (the grid needs only
 * the cells, the HUD syncs what it shows, the legend reads its range). */
#define HOST_LAYERS                                                                                                \
    (SPH_OV_BIT(KEYS) | SPH_OV_BIT(COLLISIONS) | SPH_OV_BIT(NEIGHBOURS) | SPH_OV_BIT(FORCES) | SPH_OV_BIT(INDEX))

/* The particles as attributes read from the backend's buffers: a coordinate
 * or component each, at offset d * N floats (unused ones alias the first). */
static void bind_direct(sph_renderer *r, const sph_sim *sim, unsigned pos, unsigned val, int comps)
{
    sph_gl *gl = &r->gl;
    const size_t row = (size_t)sim->n * sizeof(float);
    gl->BindVertexArray(r->vao_d);
    gl->BindBuffer(GL_ARRAY_BUFFER, pos);
    for (int d = 0; d < 3; d++)
        gl->VertexAttribPointer((GLuint)(1 + d), 1, GL_FLOAT, GL_FALSE, 0,
                                (const void *)(uintptr_t)(d < sim->dim ? (size_t)d * row : 0));
    gl->BindBuffer(GL_ARRAY_BUFFER, val);
    for (int c = 0; c < 3; c++)
        gl->VertexAttribPointer((GLuint)(4 + c), 1, GL_FLOAT, GL_FALSE, 0,
                                (const void *)(uintptr_t)(c < comps ? (size_t)c * row : 0));
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
     * renderer's context (sph_gpu_adopt_current_context: the caller's
     * contract) and the colour field is on the device. Otherwise the host
     * copy is refreshed (a copy per frame; nothing to do on the CPU backend),
     * and so it is for overlays that show the particles' data. */
    make_current(r);
    const bool direct = r->gl43 && df >= 0 && sph_gpu_context_is_current(sim);
    r->drew_direct = direct;
    if (!direct || (L & HOST_LAYERS))
        sph_sim_sync(sim, SPH_SYNC_ALL);
    else if (L & SPH_OV_BIT(HUD))
        sph_sim_sync(sim, SPH_SYNC_FIELD(SPH_FIELD_RHO)); /* the density error; sph_sim_stats syncs the rest */
    make_current(r);
    if (direct && !make_direct(r, err, n)) return false;
    const float fn = r->font.px[SPH_TEXT_NORMAL], fs = r->font.px[SPH_TEXT_SMALL];
    /* layout: legend on the right, index strip at the bottom, the view in the rest */
    const int pad = (int)roundf(0.6f * fn);
    const int legend_w = (L & SPH_OV_BIT(LEGEND)) ? (int)roundf(6.0f * fn) : 0;
    const bool strip = (L & SPH_OV_BIT(INDEX)) && sim->in_pipeline[SPH_PASS_HASH];
    const int row_h = (int)roundf(1.5f * fs);
    const int strip_h = strip ? 6 * row_h + pad : 0;
    int rc[4] = {pad, pad, r->w - legend_w - 2 * pad, r->h - strip_h - 2 * pad};
    sph_camera_fit(&r->cam, sim->dim, sim->def.domain_min, sim->def.domain_max, &v->orbit, r->w, r->h, rc);
    r->legend[0] = r->w - legend_w;
    r->legend[1] = pad;
    r->legend[2] = legend_w - pad / 2;
    r->legend[3] = r->h - strip_h - 2 * pad;
    r->strip[0] = pad;
    r->strip[1] = r->h - strip_h;
    r->strip[2] = r->w - 2 * pad;
    r->strip[3] = strip_h - pad;

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
    unsigned range_buf = 0, pos_buf = 0, val_buf = 0;
    if (direct) {
        /* the range is computed on the device for the vertex shader; read
         * back (8 bytes) only for the legend's numbers */
        float lo_hi[2] = {0, 0};
        bool need = legend_w && !v->fixed_range;
        if (!sph_gpu_field_range(sim, (sph_field_id)df, norm, &range_buf, need ? lo_hi : NULL) ||
            !sph_gpu_field_buffer(sim, SPH_FIELD_POS, &pos_buf) ||
            !sph_gpu_field_buffer(sim, (sph_field_id)df, &val_buf)) {
            snprintf(err, n, "the GL backend has no buffer for %s", sph_color_field_names[f]);
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
    const float *dl = sim->def.domain_min, *dh = sim->def.domain_max;
    if (sim->dim == 2) {
        float a[2], b[2];
        float p0[3] = {dl[0], dl[1], 0}, p1[3] = {dh[0], dh[1], 0};
        sph_camera_project(&r->cam, p0, a, NULL);
        sph_camera_project(&r->cam, p1, b, NULL);
        rect(r, a[0], b[1], b[0], a[1], SPH_RGBA(42, 45, 54, 255));
        outline(r, a[0] - 1, b[1] - 1, b[0] + 1, a[1] + 1, 1, SPH_RGBA(110, 115, 130, 255));
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
                line(r, pa[0], pa[1], pb[0], pb[1], 1.0f, SPH_RGBA(110, 115, 130, 255));
        }
        if (L & (SPH_OV_BIT(GRID) | SPH_OV_BIT(KEYS) | SPH_OV_BIT(COLLISIONS))) {
            float c[4][3] = {{dl[0], dl[1], v->slice_z}, {dh[0], dl[1], v->slice_z}, {dh[0], dh[1], v->slice_z},
                             {dl[0], dh[1], v->slice_z}};
            float p[4][2];
            bool ok = true;
            for (int k = 0; k < 4; k++) ok &= sph_camera_project(&r->cam, c[k], p[k], NULL);
            if (ok) {
                tri(r, p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1], SPH_RGBA(80, 90, 120, 60));
                tri(r, p[0][0], p[0][1], p[2][0], p[2][1], p[3][0], p[3][1], SPH_RGBA(80, 90, 120, 60));
            }
        }
    }
    if (!flush(r)) goto oom;

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
        /* 3D with the slice's overlays: cut the fluid open at the slice, the
         * camera's side removed, so the slice's cells are seen, not hidden */
        bool cut = sim->dim == 3 && (L & (SPH_OV_BIT(GRID) | SPH_OV_BIT(KEYS) | SPH_OV_BIT(COLLISIONS)));
        gl->Uniform1f(pl->cut, cut ? v->slice_z + 0.5f * sph_particle_radius(sim) : 3.0e38f);
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
            bind_direct(r, sim, pos_buf, val_buf, norm ? sim->dim : 1);
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
        gl->Disable(GL_DEPTH_TEST);
    }

    /* canvas over: world overlays (clipped), then the strip, notes, HUD, legend */
    draw_overlay(r, SPH_SPACE_WORLD);
    if (!flush(r)) goto oom;
    clip_to_view(r, false);
    draw_overlay(r, SPH_SPACE_STRIP);
    if (r->ov.note[0] && (L & ~(SPH_OV_BIT(HUD) | SPH_OV_BIT(LEGEND) | SPH_OV_BIT(TIMINGS)))) {
        /* the builder joins its notes with "; ": one line each, upwards from the view's bottom */
        char notes[sizeof r->ov.note];
        snprintf(notes, sizeof notes, "%s", r->ov.note);
        float y = (float)(rc[1] + rc[3]) - 0.8f * fs;
        char *parts[8];
        int np = 0;
        for (char *save = NULL, *t = strtok_r(notes, ";", &save); t && np < 8; t = strtok_r(NULL, ";", &save))
            parts[np++] = t + (*t == ' ');
        for (int k = np - 1; k >= 0; k--, y -= 1.3f * fs)
            text_at(r, SPH_TEXT_SMALL, (float)rc[0] + 4, y, SPH_ALIGN_LEFT, SPH_RGBA(255, 220, 120, 255), parts[k], true);
    }
    if (L & (SPH_OV_BIT(HUD) | SPH_OV_BIT(TIMINGS))) draw_hud(r, sim, v);
    if (legend_w) draw_legend(r, sim, f, lo, hi);
    if (v->panel && v->panel_lines > 0) draw_panel(r, v->panel, v->panel_lines);
    if (!flush(r)) goto oom;
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
        if (!sph_camera_project(&r->cam, x, p, &depth)) continue;
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
