/* The renderer: draws a simulation's state (particles, overlays, HUD,
 * legend) into an offscreen framebuffer, headless (EGL surfaceless or
 * OSMesa) or in the current context of a window (SDL). It stands on the GL
 * platform layer (src/gl/) and draws the overlay lists of src/overlay/; this
 * header has no GL type in it. */
#ifndef SPH_RENDER_H
#define SPH_RENDER_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "camera.h"
#include "sph_overlay.h"
#include "sph_sim.h"

/* src/gl/gl_context.h and gl_fields.h; only pointers to them pass through here. */
typedef struct sph_glctx sph_glctx;
typedef struct sph_gl_fields sph_gl_fields;

#define SPH_GL_BACKENDS(X)                                     \
    X(EGL, "egl", "EGL surfaceless, GL through libepoxy")       \
    X(OSMESA, "osmesa", "OSMesa, GL through OSMesaGetProcAddress") \
    X(CURRENT, "current", "the caller's current context (the SDL window), GL through libepoxy")

typedef enum sph_gl_backend {
#define SPH_GL_BACKEND_ENUM(id, name, about) SPH_GL_##id,
    SPH_GL_BACKENDS(SPH_GL_BACKEND_ENUM)
#undef SPH_GL_BACKEND_ENUM
    SPH_GL_BACKEND_COUNT
} sph_gl_backend;
extern const char *const sph_gl_backend_names[SPH_GL_BACKEND_COUNT];

/* What to draw and how; sph_view_default() fills it for a simulation. */
typedef struct sph_view {
    sph_color_field field;
    unsigned overlays;       /* SPH_OV_BIT(...) */
    int32_t selected;        /* particle index, or -1 */
    float slice_z;           /* [m] 3D: the plane of the grid, keys and collisions */
    sph_orbit orbit;         /* 3D camera; 2D uses zoom and pan */
    bool fixed_range;        /* colour range from range[] instead of the data */
    float range[2];
    sph_hud_info hud;
    /* A text panel at the view's top right (the window's inspector or key
     * list); NULL or 0 lines: none. */
    const char (*panel)[128];
    int panel_lines;
    /* [px] width of a column at the right edge that holds the HUD, timings
     * and text panel beside the view, never over it (the window's, with its
     * parameter panel; sph_layout_side_width); 0: none, they sit over the
     * view's top corners (sphlab render). */
    int side_px;
    /* [px] the least height the window's parameter panel keeps at the column's
     * bottom (sph_layout_panel_keep; the HUD and the text panel shrink for it);
     * 0: no panel. */
    int panel_keep_px;
    /* A circle of radius ring_radius [m] about ring_at [m] in the x-y plane
     * (the window's push/pull reach at the cursor); radius 0: none. */
    float ring_at[3];
    float ring_radius;
    bool ring_active; /* drawn brighter: the push/pull is on */
    /* The GL backend's buffers of the simulation drawn (sph_gpu_fields in
     * src/gpu/gpu.h), or NULL: the particles are drawn straight from them
     * when they live in the renderer's own context. Set it before each
     * frame (a reset makes another simulation). */
    const sph_gl_fields *device;
} sph_view;

sph_view sph_view_default(const sph_sim *sim);

typedef struct sph_renderer sph_renderer;

/* Makes the context (EGL, OSMesa) or takes the current one (CURRENT), and a
 * w x h framebuffer. NULL on failure, with the reason in err. */
sph_renderer *sph_renderer_create(sph_gl_backend backend, int w, int h, char *err, size_t n);
/* The same with an OpenGL 4.3 core context (EGL; CURRENT: the caller's must
 * be 4.3), which a GL simulation may then share (sph_sim_create_shared with
 * sph_renderer_context(r)): sph_render then draws its particles straight
 * from the backend's buffers (sph_view.device). */
sph_renderer *sph_renderer_create_gl43(sph_gl_backend backend, int w, int h, char *err, size_t n);
/* The context it draws in: its own (EGL, OSMesa) or the caller's (CURRENT),
 * valid until sph_renderer_destroy. */
sph_glctx *sph_renderer_context(const sph_renderer *r);
bool sph_renderer_resize(sph_renderer *r, int w, int h, char *err, size_t n);
void sph_renderer_destroy(sph_renderer *r);
/* "llvmpipe (LLVM 15.0.6, 256 bits), OpenGL 4.5 (Core Profile) Mesa 22.3.6" */
const char *sph_renderer_info(const sph_renderer *r);
void sph_renderer_size(const sph_renderer *r, int *w, int *h);

/* Draws the state; false (with the reason) on a GL error or out of memory. */
bool sph_render(sph_renderer *r, const sph_sim *sim, const sph_view *v, char *err, size_t n);
/* Whether the last frame's particles were drawn from the GL backend's buffers. */
bool sph_renderer_drew_direct(const sph_renderer *r);
/* The frame just drawn, RGB, rows from the top: w * h * 3 bytes. */
void sph_renderer_read_rgb(sph_renderer *r, uint8_t *rgb);
/* Copies the frame to the default framebuffer (the window), w x h pixels. */
void sph_renderer_present(sph_renderer *r, int w, int h);

/* The part of the last frame's side column (sph_view.side_px) that the HUD
 * and text panel left free, in pixels (x, y, width, height; width 0 without
 * a column): the window puts its parameter panel there. */
void sph_renderer_side_free(const sph_renderer *r, int rc[4]);
/* The camera and overlays of the last frame (picking, tests). */
const sph_camera *sph_renderer_camera(const sph_renderer *r);
const sph_overlay *sph_renderer_overlay(const sph_renderer *r);
/* Whether a particle centred at x [m] is drawn in the last frame's view. 2D:
 * always. 3D, cut-aways: with the slice's overlays (grid, keys, collisions)
 * none beyond the slice on the camera's side (z > slice_z + r / 2); with
 * wall particles (wall_model = particles) none beyond a face of the domain
 * that is turned towards the camera (the eye outside the domain past that
 * face) by more than r / 2, r the drawn radius (sph_particle_radius): the
 * box's near walls are left out, the far walls, the water and the
 * obstacles inside the domain are drawn. */
bool sph_renderer_shows(const sph_renderer *r, const float x[3]);
/* Particle drawn nearest to pixel px within max_px; -1 if none (only those
 * sph_renderer_shows). */
int32_t sph_renderer_pick(const sph_renderer *r, const sph_sim *sim, const float px[2], float max_px);
/* [m] radius particles are drawn with. */
float sph_particle_radius(const sph_sim *sim);

/* PNG (RGB) through the I/O layer (io.h): a temporary, checked writes, a rename. */
bool sph_write_png(const char *path, const uint8_t *rgb, int w, int h, char *err, size_t n);

#endif
