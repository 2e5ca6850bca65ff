/* Overlay content as primitives, without GL (see sph_overlay.h). */
#include "sph_overlay.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "overlay_internal.h"
#include "sph_search.h"
#include "sph_walls.h"

const char *const sph_overlay_names[SPH_OV_COUNT] = {
#define SPH_OVERLAY_NAME(id, name, about) name,
    SPH_OVERLAYS(SPH_OVERLAY_NAME)
#undef SPH_OVERLAY_NAME
};
const char *const sph_overlay_about[SPH_OV_COUNT] = {
#define SPH_OVERLAY_ABOUT(id, name, about) about,
    SPH_OVERLAYS(SPH_OVERLAY_ABOUT)
#undef SPH_OVERLAY_ABOUT
};

int sph_overlay_find(const char *name)
{
    for (int i = 0; i < SPH_OV_COUNT; i++)
        if (strcmp(name, sph_overlay_names[i]) == 0) return i;
    return -1;
}

/* ---- shared by the overlay's files (overlay_internal.h) ---------------- */

static sph_cells cells_of(const sph_sim *sim);




/* The hash the hash pass gives a cell (the dense cell number for the grid search). */
uint32_t sph_ov_cell_hash(const sph_sim *sim, const int32_t c[3])
{
    const sph_cells g = cells_of(sim);
    return sph_cells_hash(&g, c);
}

/* ---- building ------------------------------------------------------------ */

static bool grow(void **p, int *cap, int need, size_t size)
{
    if (need <= *cap) return true;
    int c = *cap ? *cap : 64;
    while (c < need) c *= 2;
    void *q = realloc(*p, (size_t)c * size);
    if (!q) return false;
    *p = q;
    *cap = c;
    return true;
}

typedef struct builder {
    sph_overlay *ov;
    bool ok;
} builder;

static void add_line(builder *b, const float a[3], const float e[3], uint32_t rgba, float width, sph_space sp,
                     bool arrow)
{
    sph_overlay *ov = b->ov;
    if (!grow((void **)&ov->lines, &ov->cap_lines, ov->n_lines + 1, sizeof *ov->lines)) {
        b->ok = false;
        return;
    }
    sph_ov_line *l = &ov->lines[ov->n_lines++];
    memcpy(l->a, a, sizeof l->a);
    memcpy(l->b, e, sizeof l->b);
    l->rgba = rgba;
    l->width = width;
    l->space = (uint8_t)sp;
    l->arrow = arrow;
}

static void add_disc(builder *b, const float c[3], float r, float r_min_px, uint32_t fill, uint32_t edge)
{
    sph_overlay *ov = b->ov;
    if (!grow((void **)&ov->discs, &ov->cap_discs, ov->n_discs + 1, sizeof *ov->discs)) {
        b->ok = false;
        return;
    }
    ov->discs[ov->n_discs++] = (sph_ov_disc){{c[0], c[1], c[2]}, r, r_min_px, fill, edge, SPH_SPACE_WORLD};
}

static void add_box(builder *b, float x0, float y0, float x1, float y1, float z, uint32_t fill, uint32_t edge,
                    sph_space sp)
{
    sph_overlay *ov = b->ov;
    if (!grow((void **)&ov->boxes, &ov->cap_boxes, ov->n_boxes + 1, sizeof *ov->boxes)) {
        b->ok = false;
        return;
    }
    ov->boxes[ov->n_boxes++] = (sph_ov_box){{x0, y0}, {x1, y1}, z, fill, edge, (uint8_t)sp};
}

static void add_label(builder *b, float x, float y, float z, uint32_t rgba, sph_text_size size, sph_align align,
                      sph_space sp, const char *fmt, ...) __attribute__((format(printf, 9, 10)));

static void add_label(builder *b, float x, float y, float z, uint32_t rgba, sph_text_size size, sph_align align,
                      sph_space sp, const char *fmt, ...)
{
    sph_overlay *ov = b->ov;
    if (!grow((void **)&ov->labels, &ov->cap_labels, ov->n_labels + 1, sizeof *ov->labels)) {
        b->ok = false;
        return;
    }
    sph_ov_label *l = &ov->labels[ov->n_labels++];
    l->pos[0] = x;
    l->pos[1] = y;
    l->pos[2] = z;
    l->rgba = rgba;
    l->size = (uint8_t)size;
    l->align = (uint8_t)align;
    l->space = (uint8_t)sp;
    l->fit[0] = l->fit[1] = 0;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(l->text, sizeof l->text, fmt, ap);
    va_end(ap);
}

static void note(sph_overlay *ov, const char *text)
{
    size_t len = strlen(ov->note);
    snprintf(ov->note + len, sizeof ov->note - len, "%s%s", len ? "; " : "", text);
}

/* The search's cells (sph_sim_create sets them up when the scene has a hash
 * pass); without one (search = brute), cells of h from 0, for the picture. */
static sph_cells cells_of(const sph_sim *sim)
{
    if (sim->S.cells.dim) return sim->S.cells;
    sph_cells g;
    memset(&g, 0, sizeof g);
    g.dim = sim->dim;
    for (int d = 0; d < 3; d++) {
        g.size[d] = sim->def.h;
        g.inv_size[d] = 1.0f / sim->def.h;
    }
    return g;
}

float sph_grid_origin(const sph_sim *sim, int d)
{
    return cells_of(sim).origin[d];
}

float sph_grid_size(const sph_sim *sim, int d)
{
    return cells_of(sim).size[d];
}

/* Where the search sees the particles: the predicted positions once this
 * state's external pass has written them (from the second pass of the
 * first step on), else the positions. Before any pass of the first step
 * pred holds what nothing of this step wrote (zeros of a fresh array, a
 * device buffer never filled, the placement before a carried state), and
 * the selection was drawn at cell (0,0) with "hash 0 key 0": at that point
 * the search would see pos anyway (pred = pos + v dt, and no step ran). */
static float *const *search_pos(const sph_sim *sim)
{
    const bool written = sim->P.pred[0] && sim->in_pipeline[SPH_PASS_EXTERNAL] &&
                         (sim->step > 0 || sim->next_pass > SPH_PASS_EXTERNAL);
    return written ? sim->P.pred : sim->P.pos;
}

void sph_overlay_cell_of(const sph_sim *sim, uint32_t i, int32_t c[3])
{
    const sph_cells g = cells_of(sim);
    float *const *x = search_pos(sim);
    c[0] = c[1] = c[2] = 0;
    for (int d = 0; d < sim->dim; d++) c[d] = sph_cells_coord(&g, d, x[d][i]);
}


static int cmp_cell(const void *pa, const void *pb)
{
    const sph_ov_cell *a = pa, *b = pb;
    for (int d = 2; d >= 0; d--)
        if (a->c[d] != b->c[d]) return a->c[d] < b->c[d] ? -1 : 1;
    return 0;
}

static int cmp_key(const void *pa, const void *pb)
{
    const sph_ov_cell *a = pa, *b = pb;
    if (a->key != b->key) return a->key < b->key ? -1 : 1;
    return cmp_cell(pa, pb);
}

/* Occupied cells from the index: one per distinct cell, with the key and
 * hash the hash pass stored, sorted by cell; collisions marked. */
static bool build_cells(const sph_sim *sim, sph_overlay *ov)
{
    const uint32_t n = sim->n;
    if (!grow((void **)&ov->cells, &ov->cap_cells, (int)(n ? n : 1), sizeof *ov->cells)) return false;
    int stale = 0;
    for (uint32_t s = 0; s < n; s++) {
        const sph_entry *e = &sim->S.entries[s];
        sph_ov_cell *c = &ov->cells[s];
        sph_overlay_cell_of(sim, e->index < n ? e->index : 0, c->c);
        c->hash = e->hash;
        c->key = e->key;
        c->count = 1;
        c->collides = false;
        stale += sph_ov_cell_hash(sim, c->c) != e->hash;
    }
    qsort(ov->cells, n, sizeof *ov->cells, cmp_cell);
    int m = 0;
    for (uint32_t s = 0; s < n; s++) {
        if (m > 0 && cmp_cell(&ov->cells[m - 1], &ov->cells[s]) == 0)
            ov->cells[m - 1].count++;
        else
            ov->cells[m++] = ov->cells[s];
    }
    ov->n_cells = m;
    /* collisions: distinct cells with one key */
    qsort(ov->cells, (size_t)m, sizeof *ov->cells, cmp_key);
    for (int a = 0; a < m;) {
        int b = a + 1;
        while (b < m && ov->cells[b].key == ov->cells[a].key) b++;
        if (b - a > 1)
            for (int k = a; k < b; k++) ov->cells[k].collides = true;
        a = b;
    }
    qsort(ov->cells, (size_t)m, sizeof *ov->cells, cmp_cell);
    ov->n_colliding = 0;
    for (int k = 0; k < m; k++) ov->n_colliding += ov->cells[k].collides;
    if (stale) note(ov, "the index is older than the positions (the hash pass runs next)");
    return true;
}

static int digits(uint32_t v)
{
    int d = 1;
    while (v >= 10) {
        v /= 10;
        d++;
    }
    return d;
}

static void build_grid(builder *b, const sph_sim *sim, const sph_overlay_opts *o, float z)
{
    sph_overlay *ov = b->ov;
    const sph_cells g = cells_of(sim);
    float lo[3], hi[3]; /* the domain in the particles' frame (sim->origin: the domain's point nearest 0) */
    for (int d = 0; d < 3; d++) lo[d] = (float)sim->def.domain_min[d], hi[d] = (float)sim->def.domain_max[d];
    if (o->px_per_m > 0 && fminf(g.size[0], g.size[1]) * o->px_per_m < 3.0f) {
        note(ov, "grid hidden: cells are under 3 px");
        return;
    }
    for (int d = 0; d < 2; d++) {
        const float org = g.origin[d], h = g.size[d];
        /* a hair of slack: a border that rounds just outside the domain is still drawn */
        double k0 = ceil((lo[d] - org) / h - 1e-4), k1 = floor((hi[d] - org) / h + 1e-4);
        if (k1 - k0 > 4000) {
            note(ov, "grid hidden: over 4000 lines");
            return;
        }
        ov->grid_origin[d] = org;
        for (double k = k0; k <= k1; k++) {
            float x = org + (float)k * h;
            float a[3], e[3];
            a[d] = e[d] = x;
            a[1 - d] = lo[1 - d];
            e[1 - d] = hi[1 - d];
            a[2] = e[2] = z;
            add_line(b, a, e, SPH_RGBA(200, 200, 210, 150), 1.0f, SPH_SPACE_WORLD, false);
            ov->grid_lines[d]++;
        }
    }
}

static void cell_rect(const sph_sim *sim, const int32_t c[3], float r[4])
{
    const sph_cells g = cells_of(sim);
    for (int d = 0; d < 2; d++) {
        r[d] = g.origin[d] + (float)c[d] * g.size[d];
        r[d + 2] = g.origin[d] + (float)(c[d] + 1) * g.size[d];
    }
}

static void build_keys(builder *b, const sph_sim *sim, const sph_overlay_opts *o, int32_t slice, float z)
{
    sph_overlay *ov = b->ov;
    const float h = sim->def.h;
    bool keys = o->layers & SPH_OV_BIT(KEYS), coll = o->layers & SPH_OV_BIT(COLLISIONS);
    bool labels = keys;
    /* 2D: one scale for the whole view; 3D: the renderer holds each label to
     * its own cell as the perspective draws it (sph_ov_label.fit) */
    if (keys && o->px_per_m > 0 && sim->dim == 2) {
        /* a label needs about 7 px per digit at the small size */
        int dg = digits(sim->S.table_size ? sim->S.table_size - 1 : 0);
        if (h * o->px_per_m < 7.0f * (float)dg + 2.0f) {
            labels = false;
            note(ov, "keys hidden: cells too small for their labels (enlarge or zoom)");
        }
    }
    for (int k = 0; k < ov->n_cells; k++) {
        const sph_ov_cell *c = &ov->cells[k];
        if (sim->dim == 3 && c->c[2] != slice) continue;
        float r[4];
        cell_rect(sim, c->c, r);
        if (coll && c->collides)
            add_box(b, r[0], r[1], r[2], r[3], z, SPH_RGBA(230, 40, 40, 90), SPH_RGBA(255, 60, 60, 255), SPH_SPACE_WORLD);
        if (labels) {
            const int at = ov->n_labels;
            add_label(b, 0.5f * (r[0] + r[2]), 0.5f * (r[1] + r[3]), z,
                      c->collides && coll ? SPH_RGBA(255, 200, 200, 255) : SPH_RGBA(255, 255, 255, 255),
                      SPH_TEXT_SMALL, SPH_ALIGN_CENTER, SPH_SPACE_WORLD, "%u", c->key);
            if (ov->n_labels > at) { /* the renderer draws it only where the cell holds it */
                ov->labels[at].fit[0] = r[2] - r[0];
                ov->labels[at].fit[1] = r[3] - r[1];
            }
        }
    }
}

static void particle_pos(const sph_sim *sim, uint32_t i, float x[3], bool predicted)
{
    float *const *p = predicted ? search_pos(sim) : sim->P.pos;
    x[0] = x[1] = x[2] = 0;
    for (int d = 0; d < sim->dim; d++) x[d] = p[d][i];
}

static void build_neighbours(builder *b, const sph_sim *sim, const sph_overlay_opts *o)
{
    sph_overlay *ov = b->ov;
    const uint32_t i = (uint32_t)o->selected;
    const float h = sim->def.h;
    float xi[3];
    /* where the search looked: the predicted position */
    particle_pos(sim, i, xi, true);
    int32_t c[3];
    sph_overlay_cell_of(sim, i, c);
    memcpy(ov->sel_cell, c, sizeof ov->sel_cell);
    ov->sel_key = 0;
    bool hashed = sim->in_pipeline[SPH_PASS_HASH];
    if (hashed) ov->sel_key = sph_ov_cell_hash(sim, c) % (sim->S.table_size ? sim->S.table_size : 1);
    /* the 3^d cells it visits (in 3D: the 9 of its own layer are drawn);
     * at the edge of a bounded grid there are fewer, across a periodic edge
     * they wrap to the other side */
    const sph_cells g = cells_of(sim);
    if (sim->def.search != SPH_SEARCH_BRUTE)
        for (int dy = -1; dy <= 1; dy++)
            for (int dx = -1; dx <= 1; dx++) {
                int32_t v[3] = {c[0], c[1], c[2]};
                if (!sph_cells_step(&g, 0, c[0], dx, &v[0]) || !sph_cells_step(&g, 1, c[1], dy, &v[1])) continue;
                float r[4];
                cell_rect(sim, v, r);
                bool own = dx == 0 && dy == 0;
                add_box(b, r[0], r[1], r[2], r[3], xi[2], SPH_RGBA(255, 220, 60, own ? 50 : 25),
                        SPH_RGBA(255, 220, 60, 220), SPH_SPACE_WORLD);
                if (hashed && (!o->px_per_m || h * o->px_per_m >= 40.0f)) {
                    uint32_t key = sph_ov_cell_hash(sim, v) % (sim->S.table_size ? sim->S.table_size : 1);
                    add_label(b, r[0] + 0.04f * h, r[3] - 0.04f * h, xi[2], SPH_RGBA(255, 230, 120, 255), SPH_TEXT_SMALL,
                              SPH_ALIGN_LEFT, SPH_SPACE_WORLD, "k%u", key);
                }
            }
    /* support circle */
    add_disc(b, xi, h, 0, 0, SPH_RGBA(255, 255, 255, 140));
    ov->n_nbr = 0;
    ov->nbr = NULL;
    if (!sph_ov_lists_built(sim)) {
        note(ov, "no neighbour lists yet: enter makes a step, which builds them (or the scene has none)");
    } else {
        const sph_nbr_row row = sph_nbr_row_of(&sim->S, i);
        ov->n_nbr = (int)row.n;
        if (!grow((void **)&ov->nbr_rows, &ov->cap_nbr, ov->n_nbr + 1, sizeof *ov->nbr_rows)) {
            b->ok = false;
            return;
        }
        for (int m = 0; m < ov->n_nbr; m++) ov->nbr_rows[m] = sph_nbr_at(&row, (uint32_t)m); /* compact lists too */
        ov->nbr = ov->nbr_rows;
        if (!grow((void **)&ov->weights, &ov->cap_weights, ov->n_nbr + 1, sizeof *ov->weights)) {
            b->ok = false;
            return;
        }
        const sph_kernel *k = &sim->k_density;
        float w0 = sph_kernel_w(k, 0.0f);
        bool weight_labels = ov->n_nbr <= 64 && (!o->px_per_m || h * o->px_per_m >= 60.0f);
        for (int m = 0; m < ov->n_nbr; m++) {
            uint32_t j = ov->nbr[m];
            float xj[3], r2 = 0;
            particle_pos(sim, j, xj, true);
            for (int d = 0; d < 3; d++) r2 += (xj[d] - xi[d]) * (xj[d] - xi[d]);
            float w = w0 > 0 ? sph_kernel_w(k, sqrtf(r2)) / w0 : 0.0f;
            ov->weights[m] = w;
            int alpha = 60 + (int)(195.0f * (w < 0 ? 0 : w > 1 ? 1 : w));
            add_line(b, xi, xj, SPH_RGBA(255, 170, 60, alpha), 1.5f, SPH_SPACE_WORLD, false);
            add_disc(b, xj, 0, 4.0f, 0, SPH_RGBA(255, 170, 60, 255));
            if (weight_labels)
                add_label(b, xj[0], xj[1] + 0.12f * h, xj[2], SPH_RGBA(255, 210, 150, 255), SPH_TEXT_SMALL,
                          SPH_ALIGN_CENTER, SPH_SPACE_WORLD, "%.2f", w);
        }
        if (!weight_labels && ov->n_nbr) note(ov, "weights hidden: too many neighbours or too small");
    }
    add_disc(b, xi, 0, 6.0f, 0, SPH_RGBA(255, 255, 255, 255));
}

/* An acceleration field's arrow colour: pressure red, viscosity blue (as the
 * overlay's legend says), other forces from a palette by their number;
 * gravity is green. */
static uint32_t arrow_colour(int f)
{
    static const uint32_t palette[] = {SPH_RGBA(255, 170, 40, 230), SPH_RGBA(220, 90, 220, 230),
                                       SPH_RGBA(60, 220, 220, 230), SPH_RGBA(240, 240, 90, 230)};
    if (f == SPH_FIELD_ACC_P) return SPH_RGBA(255, 80, 70, 230);
    if (f == SPH_FIELD_ACC_V) return SPH_RGBA(80, 160, 255, 230);
    return palette[f % (int)(sizeof palette / sizeof palette[0])];
}

static void build_forces(builder *b, const sph_sim *sim, const sph_overlay_opts *o, float slice_zm)
{
    sph_overlay *ov = b->ov;
    const sph_particles *P = &sim->P;
    const int dim = sim->dim;
    const float h = sim->def.h;
    float g[3] = {0, 0, 0}, gn = 0;
    if (sim->def.effects & SPH_EFFECT(GRAVITY))
        for (int d = 0; d < dim; d++) {
            g[d] = sim->def.gravity[d];
            gn += g[d] * g[d];
        }
    gn = sqrtf(gn);
    /* wall particles never move: their accelerations are never integrated,
     * so they get no arrow and do not set the scale; the subset is taken over
     * the particles that move */
    uint32_t n_moving = 0;
    for (uint32_t i = 0; i < sim->n; i++) n_moving += !sph_is_wall(P, i);
    int max_arrows = o->max_arrows > 0 ? o->max_arrows : 400;
    uint32_t stride =
        n_moving > (uint32_t)max_arrows ? (n_moving + (uint32_t)max_arrows - 1) / (uint32_t)max_arrows : 1;
    /* every acceleration field of the registry the scene has, then gravity */
    float *const *acc[SPH_FIELD_COUNT];
    uint32_t col[SPH_FIELD_COUNT + 1];
    int n_acc = 0;
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if (sph_field_infos[f].kind == SPH_KIND_ACCELERATION && P->field[f][0]) {
            col[n_acc] = arrow_colour(f);
            acc[n_acc++] = P->field[f];
        }
    float ref = gn;
    if (!(ref > 0)) { /* no gravity: the largest drawn acceleration sets the scale */
        for (uint32_t i = 0, m = 0; i < sim->n; i++) {
            if (sph_is_wall(P, i)) continue;
            if (m++ % stride) continue;
            for (int k = 0; k < n_acc; k++) ref = fmaxf(ref, sph_ov_vec_norm(acc[k], dim, i));
        }
    }
    if (!(ref > 0)) {
        note(ov, "no forces to draw");
        return;
    }
    ov->arrow_m_per_acc = 0.8f * h / ref;
    const float cap = 2.5f * h;
    for (uint32_t i = 0, m = 0; i < sim->n; i++) {
        if (sph_is_wall(P, i)) continue;
        if (m++ % stride && (int32_t)i != o->selected) continue;
        float x[3];
        particle_pos(sim, i, x, false);
        if (dim == 3 && fabsf(x[2] - slice_zm) > 0.5f * h && (int32_t)i != o->selected) continue;
        for (int k = 0; k <= n_acc; k++) {
            float a[3] = {0, 0, 0};
            uint32_t c = SPH_RGBA(90, 220, 90, 230); /* gravity */
            if (k < n_acc) {
                for (int d = 0; d < dim; d++) a[d] = acc[k][d][i];
                c = col[k];
            } else {
                if (!(gn > 0)) continue;
                memcpy(a, g, sizeof a);
            }
            float len = sqrtf(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]) * ov->arrow_m_per_acc;
            if (!(len > 1e-6f * h)) continue;
            float s = len > cap ? cap / len : 1.0f;
            float e[3];
            for (int d = 0; d < 3; d++) e[d] = x[d] + a[d] * ov->arrow_m_per_acc * s;
            add_line(b, x, e, c, 1.5f, SPH_SPACE_WORLD, true);
        }
    }
    if (stride > 1) note(ov, "forces: arrows on a regular subset of particles");
}

/* The index strip: rows of boxes, x counts boxes (after a title column of
 * width TITLE), y counts rows from the top. */
#define STRIP_TITLE 3
static void build_strip(builder *b, const sph_sim *sim, const sph_overlay_opts *o)
{
    sph_overlay *ov = b->ov;
    const uint32_t n = sim->n, T = sim->S.table_size;
    int cols = o->strip_cols > 0 ? o->strip_cols : 24;
    uint32_t ne = n < (uint32_t)cols ? n : (uint32_t)cols;
    uint32_t nk = T < (uint32_t)cols ? T : (uint32_t)cols;
    const sph_entry *en = sim->S.entries;
    /* entry window: around the selected particle's entry, else from the start */
    uint32_t s_sel = UINT32_MAX;
    if (o->selected >= 0)
        for (uint32_t s = 0; s < n; s++)
            if (en[s].index == (uint32_t)o->selected) s_sel = s;
    uint32_t s0 = 0;
    if (s_sel != UINT32_MAX && s_sel > ne / 2) s0 = s_sel - ne / 2;
    if (s0 + ne > n) s0 = n - ne;
    uint32_t kc = s_sel != UINT32_MAX ? en[s_sel].key : (ne ? en[s0 + ne / 2].key : 0);
    uint32_t k0 = kc > nk / 2 ? kc - nk / 2 : 0;
    if (k0 + nk > T) k0 = T - nk;
    ov->strip_first_entry = s0;
    ov->strip_first_key = k0;
    ov->strip_cols = STRIP_TITLE + cols;
    ov->strip_rows = 6;
    const uint32_t grey = SPH_RGBA(170, 170, 180, 255), white = SPH_RGBA(255, 255, 255, 255);
    const uint32_t edge = SPH_RGBA(20, 20, 26, 255), hl = SPH_RGBA(255, 220, 60, 255);
    const float t = STRIP_TITLE;
    add_label(b, t - 0.2f, 0.5f, 0, grey, SPH_TEXT_SMALL, SPH_ALIGN_RIGHT, SPH_SPACE_STRIP, "entry");
    add_label(b, t - 0.2f, 1.5f, 0, white, SPH_TEXT_SMALL, SPH_ALIGN_RIGHT, SPH_SPACE_STRIP, "particle");
    add_label(b, t - 0.2f, 2.5f, 0, white, SPH_TEXT_SMALL, SPH_ALIGN_RIGHT, SPH_SPACE_STRIP, "key");
    add_label(b, t - 0.2f, 4.5f, 0, grey, SPH_TEXT_SMALL, SPH_ALIGN_RIGHT, SPH_SPACE_STRIP, "key");
    add_label(b, t - 0.2f, 5.5f, 0, white, SPH_TEXT_SMALL, SPH_ALIGN_RIGHT, SPH_SPACE_STRIP, "start");
    for (uint32_t m = 0; m < ne; m++) {
        uint32_t s = s0 + m;
        float x = t + (float)m;
        bool sel = s == s_sel;
        add_label(b, x + 0.5f, 0.5f, 0, grey, SPH_TEXT_SMALL, SPH_ALIGN_CENTER, SPH_SPACE_STRIP, "%u", s);
        add_box(b, x, 1, x + 1, 2, 0, SPH_RGBA(60, 62, 72, 255), sel ? hl : edge, SPH_SPACE_STRIP);
        /* the particle's id: with the reorder pass, the index itself is just s */
        add_label(b, x + 0.5f, 1.5f, 0, white, SPH_TEXT_SMALL, SPH_ALIGN_CENTER, SPH_SPACE_STRIP, "%u",
                  en[s].index < n ? sim->P.id[en[s].index] : en[s].index);
        add_box(b, x, 2, x + 1, 3, 0, SPH_RGBA_ALPHA(sph_colormap_category(en[s].key), 200), sel ? hl : edge,
                SPH_SPACE_STRIP);
        add_label(b, x + 0.5f, 2.5f, 0, white, SPH_TEXT_SMALL, SPH_ALIGN_CENTER, SPH_SPACE_STRIP, "%u", en[s].key);
    }
    for (uint32_t m = 0; m < nk; m++) {
        uint32_t k = k0 + m, st = sim->S.start[k];
        float x = t + (float)m;
        bool sel = s_sel != UINT32_MAX && k == en[s_sel].key;
        add_label(b, x + 0.5f, 4.5f, 0, grey, SPH_TEXT_SMALL, SPH_ALIGN_CENTER, SPH_SPACE_STRIP, "%u", k);
        add_box(b, x, 5, x + 1, 6, 0, st == SPH_EMPTY ? SPH_RGBA(40, 40, 46, 255) : SPH_RGBA_ALPHA(sph_colormap_category(k), 200),
                sel ? hl : edge, SPH_SPACE_STRIP);
        if (st == SPH_EMPTY)
            add_label(b, x + 0.5f, 5.5f, 0, grey, SPH_TEXT_SMALL, SPH_ALIGN_CENTER, SPH_SPACE_STRIP, "-");
        else
            add_label(b, x + 0.5f, 5.5f, 0, white, SPH_TEXT_SMALL, SPH_ALIGN_CENTER, SPH_SPACE_STRIP, "%u", st);
        /* the offset points at the first entry of its key's run */
        if (st != SPH_EMPTY && st >= s0 && st < s0 + ne) {
            float a[3] = {x + 0.5f, 4.0f, 0}, e[3] = {t + (float)(st - s0) + 0.5f, 3.0f, 0};
            add_line(b, a, e, sel ? hl : SPH_RGBA(200, 200, 210, 200), 1.0f, SPH_SPACE_STRIP, true);
        }
    }
}

bool sph_overlay_build(const sph_sim *sim, const sph_overlay_opts *o, sph_overlay *ov)
{
    builder b = {ov, true};
    ov->n_lines = ov->n_discs = ov->n_boxes = ov->n_labels = 0;
    ov->grid_lines[0] = ov->grid_lines[1] = 0;
    ov->n_cells = ov->n_colliding = ov->n_nbr = 0;
    ov->nbr = NULL;
    ov->selected = -1;
    ov->strip_cols = ov->strip_rows = 0;
    ov->arrow_m_per_acc = 0;
    ov->note[0] = '\0';
    const unsigned L = o->layers;
    /* the slice: in 3D the plane z = slice_z; in 2D everything is at z = 0 */
    float z = sim->dim == 3 ? o->slice_z : 0.0f;
    int32_t slice = 0;
    if (sim->dim == 3) {
        const sph_cells g = cells_of(sim);
        slice = sph_cells_coord(&g, 2, z);
    }
    if (L & SPH_OV_BIT(GRID)) build_grid(&b, sim, o, z);
    bool want_cells = L & (SPH_OV_BIT(KEYS) | SPH_OV_BIT(COLLISIONS));
    if (want_cells) {
        if (!sim->in_pipeline[SPH_PASS_HASH])
            note(ov, "no spatial hash in this scene (no neighbours, or search = brute)");
        else if (!sph_ov_index_built(sim))
            note(ov, "the index is not built yet (run a step)");
        else if (!build_cells(sim, ov))
            b.ok = false;
        else
            build_keys(&b, sim, o, slice, z);
    }
    if ((L & SPH_OV_BIT(NEIGHBOURS)) && o->selected >= 0 && (uint32_t)o->selected < sim->n) {
        ov->selected = o->selected;
        build_neighbours(&b, sim, o);
    }
    if (L & SPH_OV_BIT(FORCES)) build_forces(&b, sim, o, z);
    if (L & SPH_OV_BIT(INDEX)) {
        if (!sim->in_pipeline[SPH_PASS_HASH])
            note(ov, "no index strip: the scene has no spatial hash");
        else if (!sph_ov_index_built(sim))
            note(ov, "no index strip: the index is not built yet (run a step)");
        else
            build_strip(&b, sim, o);
    }
    return b.ok;
}

void sph_overlay_free(sph_overlay *ov)
{
    free(ov->lines);
    free(ov->discs);
    free(ov->boxes);
    free(ov->labels);
    free(ov->cells);
    free(ov->weights);
    free(ov->nbr_rows);
    memset(ov, 0, sizeof *ov);
}
