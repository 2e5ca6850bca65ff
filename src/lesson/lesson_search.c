/* Lessons 5 and 6: the spatial hash (the seed's worked example, its traps,
 * collisions against the table's size) and sorting (the bitonic network step
 * by step, the counting sort, the start table, what each sort costs). */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#include "lesson_steps.h"
#include "sph_search.h"
#include "../io/io.h"

/* ---- lesson 5: the spatial hash ---------------------------------------------------------- */

int lx_lesson5(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    lx_pipeline(x, "lesson.ini", NULL, 0);

    /* 1. the seed's worked example */
    lx_hash_row rows[64];
    memset(rows, 0, sizeof rows);
    int cells = 0, coll = 0;
    uint32_t T = 0;
    int n = lx_hash_example(scene, NULL, 0, rows, 64, &cells, &coll, &T);
    if (n < 0) {
        x->failed++;
        return 1;
    }
    lx_val(x, "particles", "%d", n);
    lx_val(x, "cell_size", "%.7g", def.h * (1 + 1.0 / 1024));
    lx_val(x, "table_size", "%u", T);
    lx_block(x, "hash_table");
    lx_md(x, "| {{@particle|particule}} | x [m] | y [m] | {{@cell|cellule}} | {{@hash|hachage}} | {{@key|clé}} "
             "|\n|---|---|---|---|---|---|\n");
    FILE *f = lx_csv_open(x, "hash-example.csv");
    if (f) fprintf(f, "particle,x,y,cell_x,cell_y,hash,key\n");
    for (int i = 0; i < n; i++) {
        lx_md(x, "| %u | %.3f | %.3f | (%d, %d) | %u | %u |\n", rows[i].id, rows[i].x, rows[i].y, rows[i].cx,
              rows[i].cy, rows[i].hash, rows[i].key);
        if (f)
            fprintf(f, "%u,%.6f,%.6f,%d,%d,%u,%u\n", rows[i].id, rows[i].x, rows[i].y, rows[i].cx, rows[i].cy,
                    rows[i].hash, rows[i].key);
    }
    lx_block_end(x);
    if (f)
        lx_csv_close(x, f, "hash-example.csv",
                     "{{@cell, hash and key of each of the ten particles|case, hachage et clé de chacune des dix "
                     "particules}}");
    if (n > 7) {
        lx_val(x, "p7_cell", "(%d, %d)", rows[7].cx, rows[7].cy);
        lx_val(x, "p7_hash", "%u", rows[7].hash);
        lx_val(x, "p7_key", "%u", rows[7].key);
    }
    lx_val(x, "cells", "%d", cells);
    lx_val(x, "colliding_cells", "%d", coll);
    const char *sub = "render-hash";
    /* frames come from `sphlab render` in a child process: its GL context and the
     * software rendering that keeps frames byte-identical are set up per process */
    if (lx_sphlab(x, sub, NULL, NULL, NULL, "render", scene, "--out", lx_work(x, sub), "--steps", "1", "--every", "1",
                  "--threads", "1", "--quiet", "--color", "key", "--overlay",
                  "grid,keys,collisions,neighbours,index,hud,legend", "--select", "7", "--size", "1100x760",
                  LX_END) == 0 &&
        lx_take(x, sub, "frame_00001.png", "hash.png"))
        lx_fig(x, "hash.png", "{{@the ten particles coloured by key: cells, keys, colliding cells (red), particle 7's "
                              "neighbours, and the sorted index with its start table under the view|les dix "
                              "particules colorées par clé : cases, clés, cases en collision (en rouge), les voisins "
                              "de la particule 7, et l'index trié avec sa table des débuts sous la vue}}");

    /* 2. the traps */
    lx_block(x, "floor_table");
    lx_md(x, "| x [m] | int(x / h) | floor(x / h) |\n|---|---|---|\n");
    const float xs[] = {-0.15f, -0.05f, 0.05f, 0.15f};
    for (int i = 0; i < 4; i++)
        lx_md(x, "| %g | %d | %d |\n", xs[i], (int)(xs[i] / 0.1f), sph_cell_coord(xs[i], 1.0f / 0.1f));
    int32_t bx = 200000, by = 300;
    int64_t exact = (int64_t)bx * SPH_HASH_P1 + (int64_t)by * SPH_HASH_P2;
    lx_block_end(x);
    lx_val(x, "big_cell", "(%d, %d)", bx, by);
    lx_val(x, "big_sum", "%lld", (long long)exact);
    lx_val(x, "big_wrapped", "%u", sph_hash_cell(2, bx, by, 0));
    const float h6 = 0.06f, xa = 0.0599999949f, xb = -1e-9f;
    float inv_h = 1.0f / h6, inv_c = 1.0f / (h6 * (1.0f + 1.0f / 1024.0f));
    lx_val(x, "xa", "%.10g", xa);
    lx_val(x, "xb", "%.3g", xb);
    lx_val(x, "h6", "%g", h6);
    lx_val(x, "gap", "%.10g", (double)xa - (double)xb);
    lx_val(x, "cells_exact", "%d {{@and|et}} %d", sph_cell_coord(xa, inv_h), sph_cell_coord(xb, inv_h));
    lx_val(x, "cells_wider", "%d {{@and|et}} %d", sph_cell_coord(xa, inv_c), sph_cell_coord(xb, inv_c));

    /* 3. collisions and the table size */
    const char *block = lx_src(x, "block.ini");
    static const unsigned tq[] = {0, 16}, tf[] = {0, 4096, 97, 16, 1};
    const unsigned *ts = x->quick ? tq : tf;
    int nt = x->quick ? 2 : 5;
    f = lx_csv_open(x, "collisions.csv");
    if (f) fprintf(f, "table_size,keys,occupied_cells,colliding_cells,neighbours_ms,density_ms\n");
    lx_block(x, "collisions_table");
    lx_md(x, "| table_size | {{@keys|clés}} | {{@occupied cells|cellules occupées}} | {{@cells sharing a "
             "key|cellules partageant une clé}} | {{@neighbours [ms/step]|voisins [ms/pas]}} "
             "|\n|---|---|---|---|---|\n");
    for (int i = 0; i < nt; i++) {
        char set[64];
        snprintf(set, sizeof set, "search.table_size=%u", ts[i]);
        const char *sets[1] = {set};
        lx_hash_row dummy[1];
        int c = 0, cc = 0;
        uint32_t keys = 0;
        if (lx_hash_example(block, sets, 1, dummy, 1, &c, &cc, &keys) < 0) {
            x->failed++;
            continue;
        }
        lx_run r = {0};
        double nb = -1;
        if (lx_run_sim(x, lx_fmt("run-table-%u", ts[i]), &(lx_run_opts){block, {set}, 20, 1, NULL, NULL}, &r))
            nb = lx_run_pass(&r, "neighbours");
        lx_md(x, "| %u%s | %u | %d | %d | %.3f |\n", ts[i], ts[i] ? "" : " (N)", keys, c, cc, nb);
        if (f) fprintf(f, "%u,%u,%d,%d,%.4f,%.4f\n", ts[i], keys, c, cc, nb, lx_run_pass(&r, "density"));
    }
    lx_block_end(x);
    if (f)
        lx_csv_close(x, f, "collisions.csv",
                     "{{@occupied and colliding cells and the neighbour pass's time per table size|cases occupées et "
                     "en collision et temps de la passe des voisins par taille de table}}");
    sub = "render-collisions";
    if (lx_sphlab(x, sub, NULL, NULL, NULL, "render", block, "--out", lx_work(x, sub), "--steps", "1", "--every", "1",
                  "--threads", "1", "--quiet", "--set", "search.table_size=16", "--color", "key", "--overlay",
                  "grid,keys,collisions,hud,legend", "--size", "1000x640", LX_END) == 0 &&
        lx_take(x, sub, "frame_00001.png", "collisions.png"))
        lx_fig(x, "collisions.png", "{{@the block with a table of 16 keys: cells that share a key are red|le bloc avec "
                                    "une table de 16 clés : les cases qui partagent une clé sont en rouge}}");

    /* 4. the hard cases that check the hash */
    /* a child process: the hard cases are the command's own end-to-end checks,
     * and the report quotes their verdict as printed (nothing is parsed) */
    lx_block(x, "hardcases");
    const char *names[2] = {"table-size-1", "negative-borders"};
    for (int i = 0; i < 2; i++) {
        const char *log;
        if (lx_sphlab(x, lx_fmt("hardcases-%s", names[i]), NULL, NULL, &log, "hardcases", "--only", names[i], LX_END) ==
            0)
            lx_md_file(x, log, 10);
    }
    lx_block_end(x);
    return 0;
}

/* ---- lesson 6: sorting and offsets -------------------------------------------------------- */

typedef struct bitonic_ctx {
    lx *x;
    FILE *csv;
} bitonic_ctx;

static void bitonic_row(void *ctx, int stage, int step, uint32_t w, int flip, const uint32_t *keys,
                        const uint32_t *index, uint32_t n, int swaps)
{
    bitonic_ctx *b = ctx;
    lx_md(b->x, "| %d | %d | %u | %s | %d |", stage + 1, step + 1, w, flip ? "flip" : "disperse", swaps);
    for (uint32_t i = 0; i < n; i++) lx_md(b->x, " %u<sub>%u</sub>", keys[i], index[i]);
    lx_md(b->x, " |\n");
    if (b->csv) {
        fprintf(b->csv, "%d,%d,%u,%s,%d", stage + 1, step + 1, w, flip ? "flip" : "disperse", swaps);
        for (uint32_t i = 0; i < n; i++) fprintf(b->csv, ",%u", keys[i]);
        fprintf(b->csv, "\n");
    }
}

static void offsets_table(lx *x, const uint32_t *keys, uint32_t n, uint32_t T, const char *csv_name)
{
    sph_entry e[64], scratch[64];
    uint32_t count[65], start[64];
    for (uint32_t i = 0; i < n; i++) e[i] = (sph_entry){keys[i], keys[i], i};
    sph_sort_counting(e, scratch, count, n, T);
    sph_offsets_build(e, n, start, T);
    lx_md(x, "{{@Sorted (key<sub>particle</sub>)|Triées (clé<sub>particule</sub>)}}:");
    for (uint32_t i = 0; i < n; i++) lx_md(x, " %u<sub>%u</sub>", e[i].key, e[i].index);
    lx_md(x, "\n\n{{@Start table|Table des départs}} (`sph_offsets_build`, src/passes/offsets.c), {{@key: start|clé : départ}}:");
    for (uint32_t k = 0; k < T; k++)
        lx_md(x, " %u: %s%s", k, start[k] == SPH_EMPTY ? "inf" : lx_fmt("%u", start[k]), k + 1 < T ? "," : "\n\n");
    FILE *f = csv_name ? lx_csv_open(x, csv_name) : NULL;
    if (f) {
        fprintf(f, "key,count,start\n");
        for (uint32_t k = 0; k < T; k++) {
            uint32_t c = 0;
            for (uint32_t i = 0; i < n; i++) c += keys[i] == k;
            if (start[k] == SPH_EMPTY) fprintf(f, "%u,%u,inf\n", k, c);
            else fprintf(f, "%u,%u,%u\n", k, c, start[k]);
        }
        lx_csv_close(x, f, csv_name, "{{@per key: its count and its start in the sorted entries (inf: empty)|par clé : "
                                 "son nombre et son début dans les entrées triées (inf : vide)}}");
    }
}

int lx_lesson6(lx *x)
{
    const char *scene = lx_src(x, "lesson.ini");
    sph_scene_def def;
    if (!lx_load_def(x, scene, &def)) return 1;
    char passes[SPH_PASS_COUNT][24];
    int np = lx_pipeline(x, "lesson.ini", passes, SPH_PASS_COUNT);

    /* 1. the slide's keys through the bitonic network */
    static const uint32_t slide[10] = {9, 0, 6, 7, 1, 1, 4, 2, 2, 2};
    lx_block(x, "bitonic_table");
    lx_md(x, "| {{@stage|étape}} | {{@step|sous-étape}} | w | {{@kind|sens}} | {{@swaps|échanges}} | {{@entries after the "
             "step|entrées après la sous-étape}} |\n|---|---|---|---|---|---|\n");
    bitonic_ctx b = {x, lx_csv_open(x, "bitonic-steps.csv")};
    if (b.csv) fprintf(b.csv, "stage,step,w,kind,swaps,k0,k1,k2,k3,k4,k5,k6,k7,k8,k9\n");
    int steps = lx_bitonic_steps(slide, 10, bitonic_row, &b);
    lx_block_end(x);
    if (b.csv) lx_csv_close(x, b.csv, "bitonic-steps.csv",
                                  "{{@the keys after each step of the bitonic network|les clés "
                                                         "après chaque étape du réseau bitonique}}");
    /* the core's own sorts give the same order */
    sph_entry e1[10], e2[10], sc[10];
    uint32_t cnt[11];
    for (int i = 0; i < 10; i++) e1[i] = e2[i] = (sph_entry){slide[i], slide[i], (uint32_t)i};
    sph_sort_bitonic(e1, 10);
    sph_sort_counting(e2, sc, cnt, 10, 10);
    bool same = memcmp(e1, e2, sizeof e1) == 0;
    lx_val(x, "bitonic_steps", "%d", steps);
    lx_val(x, "sorts_differ", "%s", same ? "" : "DIFFERENT");
    if (!same) x->failed++;

    lx_block(x, "offsets_slide");
    offsets_table(x, slide, 10, 10, "offsets-slide.csv");
    lx_block_end(x);

    lx_hash_row rows[16];
    int cells, coll;
    uint32_t T;
    int n = lx_hash_example(scene, NULL, 0, rows, 16, &cells, &coll, &T);
    if (n > 0 && n <= 16) {
        uint32_t keys[16];
        lx_val(x, "real_last", "%d", n - 1);
        lx_block(x, "real_keys");
        for (int i = 0; i < n; i++) {
            keys[i] = rows[i].key;
            lx_md(x, "%u%s", keys[i], i + 1 < n ? ", " : "");
        }
        lx_block(x, "offsets_real");
        offsets_table(x, keys, (uint32_t)n, T, "offsets.csv");
        lx_block_end(x);
    }

    /* 2. the passes one at a time, in the window's scripted mode */
    lx_val(x, "view_ok", "%s", "");
    if (!lx_has_command(x, "view")) {
        lx_missing(x, "`sphlab view` is not in this build: no pass-by-pass screenshots");
    } else {
        /* the window's own scripted mode (SDL's event loop, keys, screenshots)
         * runs as `sphlab view` in a child process: SDL's video subsystem and
         * the offscreen driver are set up per process, from its environment */
        int upto = 0;
        while (upto < np && strcmp(passes[upto], "neighbours") != 0) upto++;
        if (upto < np) upto++;
        char keys[64] = "";
        for (int i = 0; i < upto; i++) strcat(keys, ".p");
        const char *cwd = lx_work(x, "view");
        sph_mkdir_p(cwd, NULL, 0);
        if (lx_sphlab(x, "view-passes", cwd, "SDL_VIDEODRIVER=offscreen", NULL, "view", lx_abs(scene), "--paused", "--frames",
                      lx_fmt("%d", 2 * upto), "--keys", keys, "--threads", "1", "--color", "key", "--overlay",
                      "grid,keys,index,hud,legend", "--select", "7", "--size", "1100x760", LX_END) == 0) {
            for (int i = 0; i < upto; i++) {
                const char *name = lx_fmt("pass-%d-%s.png", i + 1, passes[i]);
                if (lx_take(x, "view", lx_fmt("sphlab-%04d.png", i), name))
                    lx_fig(x, name, lx_fmt("{{@the window after the %s pass of the first step (index strip: "
                                           "entries and start table as they are in memory then)|la fenêtre après la "
                                           "passe %s du premier pas (bande d'index : les entrées et la table des "
                                           "débuts telles qu'elles sont alors en mémoire)}}",
                                           passes[i], passes[i]));
            }
            lx_val(x, "view_ok", "yes");
        }
    }

    /* 3. what a sort costs */
    const char *big = lx_src(x, "big.ini");
    static const double sq[] = {0.02, 0.01}, sf[] = {0.02, 0.01, 0.005};
    const double *sp = x->quick ? sq : sf;
    const int ns = x->quick ? 2 : 3;
    const char *sorts[3] = {"bitonic", "counting", "qsort"};
    double N[3], ms[3][3];
    FILE *f = lx_csv_open(x, "sort-time.csv");
    if (f) fprintf(f, "particles,bitonic_ms,counting_ms,qsort_ms\n");
    lx_block(x, "sort_table");
    lx_md(x, "| {{@particles|particules}} | {{@bitonic|bitonique}} | {{@counting|comptage}} | qsort "
             "|\n|---|---|---|---|\n");
    int good = 0;
    for (int i = 0; i < ns; i++) {
        bool all = true;
        for (int k = 0; k < 3; k++) {
            lx_run r;
            ms[k][good] = NAN;
            lx_run_opts ro = {big,
                              {lx_fmt("fluid.spacing=%g", sp[i]), lx_fmt("kernels.h=%g", 2 * sp[i]),
                               lx_fmt("search.sort=%s", sorts[k])},
                              x->quick ? 3 : 10, 1, NULL, NULL};
            if (!lx_run_sim(x, lx_fmt("run-%s-%g", sorts[k], sp[i]), &ro, &r)) {
                all = false;
                continue;
            }
            N[good] = (double)r.particles;
            ms[k][good] = lx_run_pass(&r, "sort");
        }
        if (!all) continue;
        lx_md(x, "| %.0f | %.3f | %.3f | %.3f |\n", N[good], ms[0][good], ms[1][good], ms[2][good]);
        if (f) fprintf(f, "%.0f,%.4f,%.4f,%.4f\n", N[good], ms[0][good], ms[1][good], ms[2][good]);
        good++;
    }
    lx_block_end(x);
    if (f)
        lx_csv_close(x, f, "sort-time.csv",
                     "{{@the sort pass's milliseconds per step per sort and particle count|les millisecondes par pas "
                     "de la passe de tri, par tri et par nombre de particules}}");
    if (good >= 2) {
        plot_lines L = {0};
        snprintf(L.title, sizeof L.title, "What the sort costs: bitonic network, counting sort, qsort");
        snprintf(L.subtitle, sizeof L.subtitle, "sphlab run big.ini, one thread; the sort pass only");
        snprintf(L.xlabel, sizeof L.xlabel, "particles [-]");
        L.np = 1;
        snprintf(L.p[0].ylabel, sizeof L.p[0].ylabel, "sort pass [ms/step]");
        for (int k = 0; k < 3; k++)
            L.p[0].s[L.p[0].n++] = (plot_series){"", N, ms[k], (size_t)good, k, false};
        for (int k = 0; k < 3; k++) snprintf(L.p[0].s[k].label, sizeof L.p[0].s[k].label, "%s", sorts[k]);
        lx_chart(x, PLOT_LINES, &L, "sort-time", 1000, 650,
                 "{{@the sort pass's time against the particle count|le temps de la passe de tri en fonction du "
                 "nombre de particules}}");
    }
    return 0;
}
