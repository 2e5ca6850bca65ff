/* Inside the renderer (src/render/renderer.c, canvas.c, hud.c): its state
 * and the calls its files share. Not for use outside src/render/. */
#ifndef SPH_RENDERER_IMPL_H
#define SPH_RENDERER_IMPL_H

#include "font.h"
#include "gl_context.h"
#include "gl_table.h"
#include "render.h"

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
    GLint view, proj, radius, sphere, keep_lo, keep_hi, rim, dim, comps, fixed, range, walls;
} ploc;

struct sph_renderer {
    sph_gl gl;
    sph_gl_backend backend;
    sph_glctx *ctx; /* its own (EGL, OSMesa), or the caller's (CURRENT) */
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
    /* [m] 3D: the box outside which particles' centres are not drawn (the
     * cut-aways, sph_renderer_shows); unbounded in 2D */
    float keep_lo[3], keep_hi[3];
    int strip[4], legend[4];
    int side[4];     /* [px] the side column (HUD, timings, text panel); width 0: none */
    float side_used; /* [px] height of the column the HUD and text panel took, from its top */
    /* when the HUD was drawn, for its frames/s: the last SPH_STEP_WINDOW draws, a ring */
    double hud_drawn_ms[SPH_STEP_WINDOW]; /* [ms] sph_now_ms() */
    uint64_t hud_draws;
};

/* ---- the canvas (canvas.c): triangles in pixels, batched, drawn with one
 * texture (the font atlas) by canvas_flush. Out of memory sets r->oom, which
 * canvas_flush reports. */
void canvas_tri(sph_renderer *r, float x0, float y0, float x1, float y1, float x2, float y2, uint32_t c);
void canvas_rect(sph_renderer *r, float x0, float y0, float x1, float y1, uint32_t c);
void canvas_line(sph_renderer *r, float ax, float ay, float bx, float by, float w, uint32_t c);
void canvas_outline(sph_renderer *r, float x0, float y0, float x1, float y1, float w, uint32_t c);
/* Text with its top-left at (x, y). */
void canvas_text(sph_renderer *r, int size, float x, float y, uint32_t c, const char *s);
/* Text centred vertically on y, aligned on x; an optional dark backdrop. */
void canvas_text_at(sph_renderer *r, int size, float x, float y, sph_align al, uint32_t c, const char *s,
                    bool backdrop);
/* Draws what was batched; false if the batch ran out of memory. */
bool canvas_flush(sph_renderer *r);
/* The overlay primitives (r->ov) of one space: the world's or the strip's. */
void canvas_overlay(sph_renderer *r, sph_space space);

/* ---- HUD, panel, legend and layout (hud.c) ----------------------------------- */

/* The frame's layout (layout.c): a side column side_w pixels wide at the
 * right (r->side; 0: none), the legend left of it (r->legend; *legend_w 0
 * without it), the index strip at the bottom (r->strip; returns whether it
 * is shown), the view in the rest (rc: x, y, w, h in pixels). */
bool hud_layout(sph_renderer *r, const sph_sim *sim, unsigned layers, int side_w, int rc[4], int *legend_w);
/* The overlay builder's notes, upwards from the bottom of the view rc. */
void hud_notes(sph_renderer *r, const int rc[4]);
void hud_draw(sph_renderer *r, const sph_sim *sim, const sph_view *v);
/* A box of text lines: in the side column below the HUD, or at the view's top-right corner without one;
 * keep_px [px] left free at the column's bottom for the parameter panel (sph_view's panel_keep_px). */
void hud_panel(sph_renderer *r, const char (*lines)[128], int n, int keep_px);
void hud_legend(sph_renderer *r, const sph_sim *sim, sph_color_field f, float lo, float hi);

#endif
