#define _GNU_SOURCE /* memmem */
/* The overlay builder, without GL: what the overlays would draw is checked
 * against the simulation's own data (the hash pass's keys, the offsets, the
 * neighbour lists). Also the colour maps and the VTK writer. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_hash_health.h"
#include "sph_overlay.h"
#include "sph_search.h"
#include "sph_walls.h"
#include "test_util.h"
#include "vtk.h"

/* A 2D box, 0.4 x 0.3 m, h = 0.04 m: 10 x 7.5 cells; 100 particles in a
 * corner; a hash table of 37 keys, so different cells share keys. */
static const char *scene_2d = "[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.4 0.3\n"
                              "[fluid a]\nmin=0 0\nmax=0.2 0.2\nspacing=0.02\n[kernels]\nh=0.04\n"
                              "[search]\ntable_size=37\n";

static sph_overlay build(const sph_sim *sim, unsigned layers, int32_t selected)
{
    sph_overlay ov;
    memset(&ov, 0, sizeof ov);
    sph_overlay_opts o = {.layers = layers, .selected = selected};
    cr_assert(sph_overlay_build(sim, &o, &ov));
    return ov;
}

Test(render_overlay, grid_has_a_line_at_every_cell_border)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_overlay ov = build(sim, SPH_OV_BIT(GRID), -1);
    /* cells are a hair above h = 0.04 m wide (sim->S.cells.size), from 0:
     * borders at x = 0 .. 0.36 (10 lines; 0.40 is a hair short of the 11th), y = 0 .. 0.28: 8 */
    const float size = sim->S.cells.size[0];
    cr_assert(size > sim->def.h && size < 1.001f * sim->def.h);
    cr_expect_eq(ov.grid_lines[0], 10);
    cr_expect_eq(ov.grid_lines[1], 8);
    cr_expect_eq(ov.n_lines, 18);
    for (int i = 0; i < ov.grid_lines[0]; i++) {
        const sph_ov_line *l = &ov.lines[i];
        float k = l->a[0] / size;
        cr_expect(fabsf(k - roundf(k)) < 1e-4f, "vertical line at x = %g is not a cell border", l->a[0]);
        cr_expect_eq(l->a[0], l->b[0]);
        /* a particle just right of the line is in cell k, just left in cell k - 1 */
        /* (at step 0 the search would see pos, pred = pos: both are set) */
        sim->P.pred[0][0] = sim->P.pos[0][0] = l->a[0] + 1e-4f;
        sim->P.pred[1][0] = sim->P.pos[1][0] = 0.01f;
        int32_t c[3];
        sph_overlay_cell_of(sim, 0, c);
        cr_expect_eq(c[0], (int32_t)roundf(k));
        sim->P.pred[0][0] = sim->P.pos[0][0] = l->a[0] - 1e-4f;
        sph_overlay_cell_of(sim, 0, c);
        cr_expect_eq(c[0], (int32_t)roundf(k) - 1);
    }
    sph_overlay_free(&ov);
    sph_sim_destroy(sim);
}

Test(render_overlay, key_labels_are_the_hash_pass_keys)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    sph_overlay ov = build(sim, SPH_OV_BIT(KEYS), -1);
    cr_assert_gt(ov.n_cells, 4);
    cr_assert_eq(ov.n_labels, ov.n_cells, "one label per occupied cell");
    uint32_t counted = 0;
    for (int k = 0; k < ov.n_cells; k++) {
        const sph_ov_cell *c = &ov.cells[k];
        counted += c->count;
        /* the label at the cell's centre reads the cell's key */
        float cx = ((float)c->c[0] + 0.5f) * sim->S.cells.size[0], cy = ((float)c->c[1] + 0.5f) * sim->S.cells.size[1];
        bool found = false;
        for (int l = 0; l < ov.n_labels; l++)
            if (fabsf(ov.labels[l].pos[0] - cx) < 1e-5f && fabsf(ov.labels[l].pos[1] - cy) < 1e-5f) {
                char want[24];
                snprintf(want, sizeof want, "%u", c->key);
                cr_expect_str_eq(ov.labels[l].text, want);
                found = true;
            }
        cr_expect(found, "no label in cell (%d, %d)", c->c[0], c->c[1]);
    }
    cr_expect_eq(counted, sim->n, "every particle is in one occupied cell");
    /* and each particle's entry, as the hash pass wrote it, has its cell's key */
    for (uint32_t s = 0; s < sim->n; s++) {
        const sph_entry *e = &sim->S.entries[s];
        int32_t c[3];
        sph_overlay_cell_of(sim, e->index, c);
        for (int k = 0; k < ov.n_cells; k++)
            if (ov.cells[k].c[0] == c[0] && ov.cells[k].c[1] == c[1]) {
                cr_expect_eq(ov.cells[k].key, e->key, "particle %u: cell key %u, hash pass key %u", e->index,
                             ov.cells[k].key, e->key);
                cr_expect_eq(e->key, sph_hash_cell(2, c[0], c[1], 0) % 37);
            }
    }
    sph_overlay_free(&ov);
    sph_sim_destroy(sim);
}

Test(render_overlay, colliding_cells_really_share_keys)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    sph_overlay ov = build(sim, SPH_OV_BIT(COLLISIONS), -1);
    cr_assert_gt(ov.n_colliding, 0, "with 37 keys for about 25 cells, some share a key");
    int boxes = 0;
    for (int a = 0; a < ov.n_cells; a++) {
        int others = 0;
        for (int b = 0; b < ov.n_cells; b++)
            if (b != a && ov.cells[b].key == ov.cells[a].key) {
                others++;
                cr_expect(ov.cells[b].c[0] != ov.cells[a].c[0] || ov.cells[b].c[1] != ov.cells[a].c[1]);
            }
        cr_expect_eq(ov.cells[a].collides, others > 0, "cell (%d, %d) key %u", ov.cells[a].c[0], ov.cells[a].c[1],
                     ov.cells[a].key);
        boxes += ov.cells[a].collides;
    }
    cr_expect_eq(ov.n_boxes, boxes, "one marked box per colliding cell");
    cr_expect_eq(ov.n_labels, 0, "keys off: no labels");
    sph_overlay_free(&ov);
    sph_sim_destroy(sim);
}

Test(render_overlay, selected_particle_neighbours_are_its_row)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    const int32_t sel = 45;
    sph_overlay ov = build(sim, SPH_OV_BIT(NEIGHBOURS), sel);
    uint32_t s = sim->S.nbr_start[sel], e = sim->S.nbr_start[sel + 1];
    cr_assert_gt(e - s, 3u);
    cr_assert_eq(ov.n_nbr, (int)(e - s));
    for (int m = 0; m < ov.n_nbr; m++) {
        cr_expect_eq(ov.nbr[m], sim->S.nbr[s + m]);
        cr_expect(ov.weights[m] >= 0 && ov.weights[m] <= 1, "weight %g", ov.weights[m]);
    }
    /* the 3^2 cells it visits, around its own */
    int32_t c[3];
    sph_overlay_cell_of(sim, (uint32_t)sel, c);
    cr_expect_eq(ov.sel_cell[0], c[0]);
    cr_expect_eq(ov.sel_cell[1], c[1]);
    cr_expect_eq(ov.n_boxes, 9);
    cr_expect_eq(ov.sel_key, sph_hash_cell(2, c[0], c[1], 0) % 37);
    sph_overlay_free(&ov);
    sph_sim_destroy(sim);
}

Test(render_overlay, index_strip_shows_entries_and_offsets)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    sph_overlay_opts o = {.layers = SPH_OV_BIT(INDEX), .selected = 50, .strip_cols = 12};
    sph_overlay ov;
    memset(&ov, 0, sizeof ov);
    cr_assert(sph_overlay_build(sim, &o, &ov));
    uint32_t s0 = ov.strip_first_entry, k0 = ov.strip_first_key;
    /* the window holds the selected particle's entry and its key */
    bool seen = false;
    for (uint32_t s = s0; s < s0 + 12; s++) seen |= sim->S.entries[s].index == 50;
    cr_expect(seen);
    /* row 1 (index) and row 2 (key) labels read the sorted entries; row 5 the offsets */
    for (int l = 0; l < ov.n_labels; l++) {
        const sph_ov_label *lb = &ov.labels[l];
        cr_assert_eq(lb->space, SPH_SPACE_STRIP);
        int col = (int)floorf(lb->pos[0]) - 3, row = (int)floorf(lb->pos[1]);
        if (col < 0) continue; /* the titles */
        char want[24];
        if (row == 1) snprintf(want, sizeof want, "%u", sim->P.id[sim->S.entries[s0 + (uint32_t)col].index]);
        else if (row == 2) snprintf(want, sizeof want, "%u", sim->S.entries[s0 + (uint32_t)col].key);
        else if (row == 5) {
            uint32_t st = sim->S.start[k0 + (uint32_t)col];
            if (st == SPH_EMPTY) snprintf(want, sizeof want, "-");
            else snprintf(want, sizeof want, "%u", st);
        } else continue;
        cr_expect_str_eq(lb->text, want, "row %d column %d", row, col);
    }
    /* each arrow goes from key k's offset box to entry start[k], whose key is k */
    int arrows = 0;
    for (int i = 0; i < ov.n_lines; i++) {
        const sph_ov_line *ln = &ov.lines[i];
        uint32_t k = k0 + (uint32_t)(ln->a[0] - 3.5f + 0.01f), s = s0 + (uint32_t)(ln->b[0] - 3.5f + 0.01f);
        cr_expect_eq(sim->S.start[k], s);
        cr_expect_eq(sim->S.entries[s].key, k);
        arrows++;
    }
    cr_expect_gt(arrows, 0);
    sph_overlay_free(&ov);
    sph_sim_destroy(sim);
}

/* The start's measurement runs the search passes (sph_sim.c, measure_start): at step 0 the index and the lists
 * exist, and the overlays show them (lessons 5 and 6 open at step 0 on the keys, the colliding cells and the
 * index strip; they said "the index is not built yet (run a step)"). Between the counting sort, which borrows
 * the lists' buffer, and the neighbours pass there are no lists: no neighbour count is shown then (it read 0). */
Test(render_overlay, the_start_builds_the_index_and_the_sort_takes_the_lists)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_overlay ov = build(sim, SPH_OV_BIT(KEYS) | SPH_OV_BIT(INDEX), -1);
    cr_expect_gt(ov.n_labels, 0, "note: %s", ov.note);
    cr_expect(strstr(ov.note, "not built") == NULL, "note: %s", ov.note);
    sph_overlay_free(&ov);
    char lines[24][128];
    int n = sph_inspect_lines(sim, 45, lines, 24), nb = 0;
    for (int k = 0; k < n; k++) nb += strncmp(lines[k], "neighbours ", 11) == 0;
    cr_expect_eq(nb, 1, "step 0: the start's lists are shown");
    sph_pass_id p;
    do p = sph_sim_step_pass(sim);
    while (p != SPH_PASS_SORT && p != SPH_PASS_COUNT);
    cr_assert_eq(p, SPH_PASS_SORT);
    n = sph_inspect_lines(sim, 45, lines, 24);
    for (int k = 0; k < n; k++) cr_expect(strncmp(lines[k], "neighbours ", 11) != 0, "after the sort: %s", lines[k]);
    ov = build(sim, SPH_OV_BIT(NEIGHBOURS), 45);
    cr_expect(strstr(ov.note, "no neighbour lists yet") != NULL, "note: %s", ov.note);
    sph_overlay_free(&ov);
    sph_hash_health hh;
    cr_assert(sph_sim_hash_health(sim, false, &hh));
    cr_expect(isnan(hh.share), "no share of candidates within h from the borrowed lists: %g", hh.share);
    do p = sph_sim_step_pass(sim);
    while (p != SPH_PASS_NEIGHBOURS && p != SPH_PASS_COUNT);
    n = sph_inspect_lines(sim, 45, lines, 24);
    nb = 0;
    for (int k = 0; k < n; k++) nb += strncmp(lines[k], "neighbours ", 11) == 0;
    cr_expect_eq(nb, 1, "after the neighbours pass");
    sph_sim_destroy(sim);
}

Test(render_overlay, forces_draw_arrows_along_the_accelerations)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    sph_overlay ov = build(sim, SPH_OV_BIT(FORCES), -1);
    cr_assert_gt(ov.n_lines, 0);
    cr_expect_gt(ov.arrow_m_per_acc, 0);
    int gravity = 0;
    for (int i = 0; i < ov.n_lines; i++) {
        cr_expect(ov.lines[i].arrow);
        /* gravity arrows point straight down, 0.8 h long */
        if (ov.lines[i].rgba == SPH_RGBA(90, 220, 90, 230)) {
            gravity++;
            cr_expect(fabsf(ov.lines[i].b[0] - ov.lines[i].a[0]) < 1e-6f);
            cr_expect(fabsf((ov.lines[i].a[1] - ov.lines[i].b[1]) - 0.8f * sim->def.h) < 1e-5f);
        }
    }
    cr_expect_eq(gravity, (int)sim->n);
    sph_overlay_free(&ov);
    sph_sim_destroy(sim);
}

/* Wall particles ([domain] wall_model = particles) never move: their
 * accelerations are never integrated, so an arrow on one means nothing.
 * No arrow may start at a wall particle, and the fluid still gets its own. */
Test(render_overlay, forces_skip_wall_particles)
{
    static const char *ini = "[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.3 0.3\n"
                             "wall_model=particles\n[fluid a]\nmin=0 0\nmax=0.1 0.1\nspacing=0.02\n"
                             "[kernels]\nh=0.04\n";
    sph_sim *sim = test_sim(ini, 1);
    sph_sim_step(sim);
    uint32_t walls = 0;
    for (uint32_t i = 0; i < sim->n; i++) walls += sph_is_wall(&sim->P, i);
    cr_assert_gt(walls, 0, "the scene has wall particles");
    cr_assert_lt(walls, sim->n, "and fluid particles");
    sph_overlay ov = build(sim, SPH_OV_BIT(FORCES), -1);
    cr_assert_gt(ov.n_lines, 0);
    int gravity = 0;
    for (int l = 0; l < ov.n_lines; l++) {
        if (ov.lines[l].rgba == SPH_RGBA(90, 220, 90, 230)) gravity++;
        for (uint32_t i = 0; i < sim->n; i++) {
            if (!sph_is_wall(&sim->P, i)) continue;
            bool at = fabsf(ov.lines[l].a[0] - sim->P.pos[0][i]) < 1e-7f &&
                      fabsf(ov.lines[l].a[1] - sim->P.pos[1][i]) < 1e-7f;
            cr_assert(!at, "an arrow starts at wall particle %u (%g, %g)", i, sim->P.pos[0][i], sim->P.pos[1][i]);
        }
    }
    cr_expect_eq(gravity, (int)(sim->n - walls), "one gravity arrow per fluid particle");
    sph_overlay_free(&ov);
    sph_sim_destroy(sim);
}

Test(render_overlay, colour_fields_and_maps)
{
    sph_sim *sim = test_sim("[scene]\neffects=gravity\n[domain]\nmax=1 1\n[fluid a]\nmax=0.2 0.2\nspacing=0.05\n", 1);
    cr_expect_not_null(sph_color_field_missing(sim, SPH_COLOR_DENSITY));
    cr_expect_eq(sph_color_field_default(sim), SPH_COLOR_SPEED);
    cr_expect_null(sph_color_field_missing(sim, SPH_COLOR_SPEED));
    /* viridis: dark purple to yellow */
    uint32_t a = sph_colormap_viridis(0), b = sph_colormap_viridis(1);
    cr_expect_eq(a & 0xFF, 71u, "r(0) = %u", a & 0xFF);
    cr_expect_lt((b >> 16) & 0xFF, 60u);
    cr_expect_gt(b & 0xFF, 240u);
    cr_expect_eq(sph_colormap_category(3), sph_colormap_category(13));
    cr_expect_neq(sph_colormap_category(3), sph_colormap_category(4));
    sph_sim_destroy(sim);
}

Test(render_overlay, hud_reports_the_density_error)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    sph_stats st;
    sph_sim_stats(sim, &st);
    double want = (st.rho_max - sim->def.rest_density) / sim->def.rest_density;
    cr_expect(fabs(sph_density_error(sim) - want) < 1e-6);
    char lines[8][128];
    sph_hud_info info = {.steps_per_s = -1, .last_pass = -1};
    int n = sph_hud_lines(sim, &info, lines, 8);
    cr_assert_geq(n, 4);
    cr_expect(strstr(lines[1], "step 1") != NULL, "%s", lines[1]);
    /* the dimension once: added to a name that lacks it, not repeated after one that says it */
    snprintf(sim->def.name, sizeof sim->def.name, "%s", "pool");
    sph_hud_lines(sim, &info, lines, 8);
    cr_expect(strncmp(lines[0], "pool   2D   ", 12) == 0, "%s", lines[0]);
    snprintf(sim->def.name, sizeof sim->def.name, "%s", "dam break 2D");
    sph_hud_lines(sim, &info, lines, 8);
    cr_expect(strstr(lines[0], "2D   2D") == NULL && strncmp(lines[0], "dam break 2D   ", 15) == 0, "%s", lines[0]);
    snprintf(sim->def.name, sizeof sim->def.name, "%s", "a 3D-like name in 2D");
    sph_hud_lines(sim, &info, lines, 8);
    cr_expect(strstr(lines[0], "in 2D   ") != NULL && strstr(lines[0], "2D   2D") == NULL, "%s", lines[0]);
    cr_expect(strstr(lines[2], "(rho_max - rho0)/rho0") != NULL, "%s", lines[2]);
    cr_expect(strstr(lines[3], "energy drift since step 1 = +0.00 %") != NULL, "%s", lines[3]);
    sim->enabled[SPH_PASS_VISCOSITY] = false;
    n = sph_hud_lines(sim, &info, lines, 8);
    cr_expect(strstr(lines[4], "off: viscosity") != NULL, "%s", lines[4]);
    /* with surface tension the energy summed leaves out the surface's: no drift is claimed */
    sim->def.effects |= SPH_EFFECT(COHESION);
    sph_hud_lines(sim, &info, lines, 8);
    cr_expect(strstr(lines[3], "not shown (surface energy is not counted)") != NULL, "%s", lines[3]);
    sph_sim_destroy(sim);
}

static uint32_t be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

/* The VTK file holds the positions and every field, big-endian. */
Test(render_overlay, vtk_file_has_positions_and_fields)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    for (int k = 0; k < 3; k++) sph_sim_step(sim);
    const char *path = test_write_temp("", ".vtk");
    char err[256];
    cr_assert(sph_vtk_write(sim, path, err, sizeof err), "%s", err);
    FILE *f = fopen(path, "rb");
    cr_assert_not_null(f);
    static unsigned char buf[1 << 20];
    size_t len = fread(buf, 1, sizeof buf, f);
    fclose(f);
    remove(path);
    cr_assert(len > 100 && len < sizeof buf);
    const char *head = "# vtk DataFile Version 3.0\n";
    cr_assert_eq(memcmp(buf, head, strlen(head)), 0);
    const unsigned char *p = memmem(buf, len, "POINTS 100 float\n", 17);
    cr_assert_not_null(p);
    p += 17;
    for (uint32_t i = 0; i < sim->n; i++)
        for (int d = 0; d < 3; d++) {
            uint32_t u = be32(p + 4 * (3 * i + (uint32_t)d));
            float x;
            memcpy(&x, &u, 4);
            cr_assert_eq(x, d < 2 ? sim->P.pos[d][i] : 0.0f, "particle %u axis %d", i, d);
        }
    const char *fields[] = {"SCALARS id unsigned_int 1", "VECTORS vel float", "SCALARS rho float 1",
                            "SCALARS p float 1", "VECTORS acc_p float", "VECTORS acc_v float", "SCALARS mass float 1"};
    for (size_t k = 0; k < sizeof fields / sizeof *fields; k++)
        cr_expect_not_null(memmem(buf, len, fields[k], strlen(fields[k])), "no '%s'", fields[k]);
    /* density values follow their header */
    const char *rho = "SCALARS rho float 1\nLOOKUP_TABLE default\n";
    p = memmem(buf, len, rho, strlen(rho));
    cr_assert_not_null(p);
    p += strlen(rho);
    for (uint32_t i = 0; i < sim->n; i++) {
        uint32_t u = be32(p + 4 * i);
        float x;
        memcpy(&x, &u, 4);
        cr_assert_eq(x, sim->P.rho[i]);
    }
    sph_sim_destroy(sim);
}

Test(render_overlay, inspector_names_cell_key_and_forces)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    char lines[16][128];
    int n = sph_inspect_lines(sim, 45, lines, 16);
    cr_assert_geq(n, 8);
    int32_t c[3];
    sph_overlay_cell_of(sim, 45, c);
    uint32_t hash = sph_hash_cell(2, c[0], c[1], 0);
    char want[128];
    snprintf(want, sizeof want, "cell (%d, %d)  hash %u  key %u", c[0], c[1], hash, hash % 37);
    bool cell = false, nbrs = false, pressure = false;
    for (int k = 0; k < n; k++) {
        cell |= strcmp(lines[k], want) == 0;
        char nb[64];
        snprintf(nb, sizeof nb, "neighbours %u", sim->S.nbr_start[46] - sim->S.nbr_start[45]);
        nbrs |= strcmp(lines[k], nb) == 0;
        pressure |= strncmp(lines[k], "a pressure", 10) == 0;
    }
    cr_expect(cell, "no line '%s'", want);
    cr_expect(nbrs);
    cr_expect(pressure);
    cr_expect_eq(sph_inspect_lines(sim, sim->n, lines, 16), 0);
    sph_sim_destroy(sim);
}

/* Stepping pass by pass: between the reorder (which moves the state, not rho, p or the accelerations) and the
 * passes that write those fields again, the stored values belong to other particles. The inspector and the HUD
 * say so instead of showing another particle's density (a user's review: particle 7's rho read 97.9 before the
 * reorder, 50.9 after it, no density pass between); at step 0 the density the start measured is shown (the HUD
 * said "not computed yet" while the colours showed it). */
Test(render_overlay, inspector_says_which_fields_the_reorder_left_behind)
{
    char ini[1024];
    snprintf(ini, sizeof ini, "%sreorder = on\n", scene_2d); /* its last section is [search] */
    sph_sim *sim = test_sim(ini, 1);
    cr_assert(sim->in_pipeline[SPH_PASS_REORDER]);
    cr_expect(isfinite(sph_density_error(sim)), "at step 0 the start's density is there");
    sph_sim_step(sim);
    sph_pass_id p;
    do p = sph_sim_step_pass(sim);
    while (p != SPH_PASS_REORDER && p != SPH_PASS_COUNT);
    cr_assert_eq(p, SPH_PASS_REORDER);
    cr_expect(!isfinite(sph_density_error(sim)), "rho is in the old order after the reorder");
    char lines[24][128];
    int n = sph_inspect_lines(sim, 45, lines, 24);
    bool said = false, shown = false;
    for (int k = 0; k < n; k++) {
        said |= strstr(lines[k], "left in the old order by the reorder; the density pass writes it next") != NULL;
        shown |= strncmp(lines[k], "rho ", 4) == 0 && strstr(lines[k], "kg/m") != NULL;
    }
    cr_expect(said && !shown, "rho after the reorder:\n%s\n%s", lines[0], n > 8 ? lines[8] : "");
    sph_hud_info info = {.steps_per_s = -1, .last_pass = -1};
    char hud[12][128];
    int h = sph_hud_lines(sim, &info, hud, 12);
    bool hud_said = false;
    for (int k = 0; k < h; k++) hud_said |= strstr(hud[k], "old order since the reorder") != NULL;
    cr_expect(hud_said, "the HUD says why no density error is shown");
    do p = sph_sim_step_pass(sim);
    while (p != SPH_PASS_DENSITY && p != SPH_PASS_COUNT);
    cr_assert_eq(p, SPH_PASS_DENSITY);
    cr_expect(isfinite(sph_density_error(sim)), "the density pass wrote rho in the new order");
    n = sph_inspect_lines(sim, 45, lines, 24);
    for (int k = 0; k < n; k++)
        cr_expect(!(strncmp(lines[k], "rho ", 4) == 0 && strstr(lines[k], "old order")), "%s", lines[k]);
    sph_sim_destroy(sim);
}

/* The HUD's density error is the fluid's, against the density the pressure
 * model holds: wall particles (their sums near the fluid read well above it)
 * are left out, and the solvers' rho_rest (a lattice particle's sum, above
 * rest_density) is the reference, named in the line. */
Test(render_overlay, hud_density_error_is_the_fluids_against_the_held_density)
{
    const char *ini = "[scene]\neffects=gravity pressure viscosity walls\n[domain]\nmin=0 0\nmax=0.2 0.2\n"
                      "wall_model=particles\n[fluid a]\nmin=0 0\nmax=0.1 0.1\nspacing=0.005\n"
                      "[physics]\npressure_solver=%s\n[kernels]\nh=0.015\ndensity=wendland\npressure=wendland\n"
                      "[time]\ndt=0.001\n";
    const char *solvers[] = {"pcisph", "dfsph", "eos"};
    for (int k = 0; k < 3; k++) {
        char buf[512];
        snprintf(buf, sizeof buf, ini, solvers[k]);
        sph_sim *sim = test_sim(buf, 1);
        for (int s = 0; s < 5; s++) sph_sim_step(sim);
        const bool solver = k < 2;
        double fluid = -INFINITY, all = -INFINITY;
        for (uint32_t i = 0; i < sim->n; i++) {
            all = fmax(all, sim->P.rho[i]);
            if (!sph_is_wall(&sim->P, i)) fluid = fmax(fluid, sim->P.rho[i]);
        }
        cr_assert_gt(all, fluid, "%s: the walls' sums read above the fluid's (%g, %g)", solvers[k], all, fluid);
        const double held = solver ? sim->solver.rho_rest : sim->eos_rho0;
        cr_assert_gt(held, 0);
        if (solver) cr_assert_gt(held, sim->def.rest_density * 1.001, "%s: rho_rest %g", solvers[k], held);
        cr_expect(fabs(sph_density_error(sim) - (fluid - held) / held) < 1e-6, "%s: %g, want %g", solvers[k],
                  sph_density_error(sim), (fluid - held) / held);
        char lines[8][128];
        sph_hud_info info = {.steps_per_s = -1, .last_pass = -1};
        sph_hud_lines(sim, &info, lines, 8);
        cr_expect(strstr(lines[2], solver ? "(rho_max - rho_rest)/rho_rest" : "(rho_max - rho0)/rho0") != NULL,
                  "%s: %s", solvers[k], lines[2]);
        cr_expect(strstr(lines[2], "fluid") != NULL, "%s: %s", solvers[k], lines[2]);
        sph_sim_destroy(sim);
    }
}

/* DFSPH's pressure, rho (kappa + kappa_v) as sph_sim_pressure gives it, has a
 * colour (`pressure` is the equation of state's, which a DFSPH run lacks). */
Test(render_overlay, dfsph_pressure_is_a_colour)
{
    const int f = sph_color_field_find("dfsph-pressure");
    cr_assert_geq(f, 0, "no colour dfsph-pressure");
    sph_sim *eos = test_sim(scene_2d, 1);
    cr_expect_not_null(sph_color_field_missing(eos, (sph_color_field)f), "an eos run has no DFSPH pressure");
    sph_sim_destroy(eos);
    char ini[512];
    snprintf(ini, sizeof ini, "%s[physics]\npressure_solver=dfsph\n", scene_2d);
    sph_sim *sim = test_sim(ini, 1);
    for (int s = 0; s < 100; s++) sph_sim_step(sim);
    cr_assert_null(sph_color_field_missing(sim, (sph_color_field)f), "%s", sph_color_field_missing(sim, f));
    cr_expect_str_eq(sph_color_field_unit((sph_color_field)f, 2), "N/m");
    float *v = malloc(sizeof *v * sim->n), lo, hi;
    cr_assert(sph_color_field_values(sim, (sph_color_field)f, v, &lo, &hi));
    float top = 0;
    for (uint32_t i = 0; i < sim->n; i++) {
        cr_expect_float_eq(v[i], sph_sim_pressure(sim, i), 1e-6f * (1 + fabsf(v[i])), "particle %u", i);
        top = fmaxf(top, v[i]);
    }
    cr_expect_gt(top, 0, "water under gravity has a pressure (t = %g s)", sim->t);
    cr_expect_eq(hi, top);
    free(v);
    sph_sim_destroy(sim);
}
