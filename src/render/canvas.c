/* The renderer's canvas (see renderer_impl.h): overlays, HUD and legend
 * become triangles in pixels, batched in r->v and drawn in one call per
 * flush with the font atlas as texture (a white texel for solid fills). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "renderer_impl.h"

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

void canvas_tri(sph_renderer *r, float x0, float y0, float x1, float y1, float x2, float y2, uint32_t c)
{
    float u = r->font.white_uv[0], v = r->font.white_uv[1];
    push(r, x0, y0, u, v, c);
    push(r, x1, y1, u, v, c);
    push(r, x2, y2, u, v, c);
}

void canvas_rect(sph_renderer *r, float x0, float y0, float x1, float y1, uint32_t c)
{
    canvas_tri(r, x0, y0, x1, y0, x1, y1, c);
    canvas_tri(r, x0, y0, x1, y1, x0, y1, c);
}

void canvas_line(sph_renderer *r, float ax, float ay, float bx, float by, float w, uint32_t c)
{
    float dx = bx - ax, dy = by - ay, len = sqrtf(dx * dx + dy * dy);
    if (!(len > 0)) return;
    float nx = -dy / len * 0.5f * w, ny = dx / len * 0.5f * w;
    canvas_tri(r, ax + nx, ay + ny, bx + nx, by + ny, bx - nx, by - ny, c);
    canvas_tri(r, ax + nx, ay + ny, bx - nx, by - ny, ax - nx, ay - ny, c);
}

static void arrow_head(sph_renderer *r, float ax, float ay, float bx, float by, float size, uint32_t c)
{
    float dx = bx - ax, dy = by - ay, len = sqrtf(dx * dx + dy * dy);
    if (!(len > 0)) return;
    float s = fminf(size, 0.5f * len);
    float ux = dx / len, uy = dy / len;
    canvas_tri(r, bx, by, bx - s * ux - 0.5f * s * uy, by - s * uy + 0.5f * s * ux, bx - s * ux + 0.5f * s * uy,
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
        if (fill >> 24) canvas_tri(r, cx, cy, x0, y0, x1, y1, fill);
        if (edge >> 24) canvas_line(r, x0, y0, x1, y1, 1.5f, edge);
    }
}

void canvas_outline(sph_renderer *r, float x0, float y0, float x1, float y1, float w, uint32_t c)
{
    canvas_rect(r, x0, y0, x1, y0 + w, c);
    canvas_rect(r, x0, y1 - w, x1, y1, c);
    canvas_rect(r, x0, y0 + w, x0 + w, y1 - w, c);
    canvas_rect(r, x1 - w, y0 + w, x1, y1 - w, c);
}

void canvas_text(sph_renderer *r, int size, float x, float y, uint32_t c, const char *s)
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

void canvas_text_at(sph_renderer *r, int size, float x, float y, sph_align al, uint32_t c, const char *s,
                    bool backdrop)
{
    float w = sph_font_width(&r->font, size, s), hgt = r->font.px[size];
    float x0 = al == SPH_ALIGN_CENTER ? x - 0.5f * w : al == SPH_ALIGN_RIGHT ? x - w : x;
    float y0 = y - 0.5f * hgt;
    x0 = roundf(x0);
    y0 = roundf(y0);
    if (backdrop) canvas_rect(r, x0 - 2, y0, x0 + w + 2, y0 + hgt, SPH_RGBA(0, 0, 0, 150));
    canvas_text(r, size, x0, y0, c, s);
}

bool canvas_flush(sph_renderer *r)
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

/* 3D: the label's box (a cell on the slice, seen in perspective and at an
 * angle) is drawn wide and tall enough for its text. 2D keeps its one test
 * for all labels (the overlay builder's, from the view's scale). */
static bool label_fits(const sph_renderer *r, const sph_ov_label *l)
{
    float e[4][3], px[4][2];
    for (int k = 0; k < 4; k++) memcpy(e[k], l->pos, sizeof e[k]);
    e[0][0] -= 0.5f * l->fit[0], e[1][0] += 0.5f * l->fit[0]; /* left and right edges' middles */
    e[2][1] -= 0.5f * l->fit[1], e[3][1] += 0.5f * l->fit[1]; /* bottom and top */
    for (int k = 0; k < 4; k++)
        if (!sph_camera_project(&r->cam, e[k], px[k], NULL)) return false;
    const float w = hypotf(px[1][0] - px[0][0], px[1][1] - px[0][1]);
    const float h = hypotf(px[3][0] - px[2][0], px[3][1] - px[2][1]);
    /* the text's extent across the cell: its width along the cell's x edge, its height along y */
    return w >= sph_font_width(&r->font, l->size, l->text) + 2.0f && h >= r->font.px[l->size];
}

/* The world's primitives are clipped to the view by the caller (scissor). */
void canvas_overlay(sph_renderer *r, sph_space space)
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
            canvas_tri(r, p[0][0], p[0][1], p[1][0], p[1][1], p[2][0], p[2][1], b->fill);
            canvas_tri(r, p[0][0], p[0][1], p[2][0], p[2][1], p[3][0], p[3][1], b->fill);
        }
        if (b->edge >> 24) {
            if (b->space == SPH_SPACE_STRIP) {
                canvas_outline(r, p[0][0], p[0][1], p[2][0], p[2][1], 1.0f, b->edge);
            } else {
                for (int k = 0; k < 4; k++) canvas_line(r, p[k][0], p[k][1], p[(k + 1) % 4][0], p[(k + 1) % 4][1], 1.0f, b->edge);
            }
        }
    }
    for (int i = 0; i < ov->n_lines; i++) {
        const sph_ov_line *l = &ov->lines[i];
        if (l->space != space) continue;
        float a[2], b[2];
        if (!to_px(r, l->a, (sph_space)l->space, a) || !to_px(r, l->b, (sph_space)l->space, b)) continue;
        canvas_line(r, a[0], a[1], b[0], b[1], l->width, l->rgba);
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
        if (r->cam.dim == 3 && l->fit[0] > 0 && !label_fits(r, l)) continue;
        canvas_text_at(r, l->size, p[0], p[1], (sph_align)l->align, l->rgba, l->text, l->space == SPH_SPACE_WORLD);
    }
}
