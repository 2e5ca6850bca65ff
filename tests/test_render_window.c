#define _DEFAULT_SOURCE /* setenv */
/* The window's ladder (sphlab view, src/render/view_ladder.c): levels and
 * ingredients switched live by scripted keys through SDL's offscreen driver,
 * validate mode, N changed live, the passes numbered as `sphlab check`
 * numbers them; and the first frame of every lesson: the inspector reads
 * the selected particle's own cell. */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_overlay.h"
#include "sph_search.h"
#include "test_util.h"
#include "view_ladder.h"

static char out[65536];

static const char *const scene_2d =
    "[scene]\nname = ladder\ndimension = 2\neffects = gravity pressure viscosity walls\njitter = 0.1\n"
    "[domain]\nmin = 0 0\nmax = 1 0.6\n"
    "[fluid block]\nmin = 0 0\nmax = 0.4 0.3\nspacing = 0.02\n"
    "[kernels]\nh = 0.04\n[time]\ndt = 0.0005\n";

static int window(const char *args)
{
    setenv("SDL_VIDEODRIVER", "offscreen", 1);
    return test_sphlab(args, out, sizeof out);
}

/* The strings in this order in the window's messages. */
static void expect_in_order(const char *const *want, size_t n)
{
    const char *at = out;
    for (size_t k = 0; k < n; k++) {
        const char *p = strstr(at, want[k]);
        cr_expect_not_null(p, "no '%s' (in order) in:\n%s", want[k], out);
        if (p) at = p + strlen(want[k]);
    }
}

/* l walks the ladder L0..L7 while the scene runs (then G0..: a GL device or
 * a refusal with the reason); a validates against L0. */
Test(render_window, keys_walk_the_ladder_and_validate, .timeout = 300)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    char args[1024];
    snprintf(args, sizeof args, "view %s --threads 1 --frames 12 --keys 'llllllllaeut' --size 480x320", scene);
    int rc = window(args);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    const char *want[] = {"level: at level L0 (brute force", "level: at level L1", "level: at level L2",
                          "level: at level L3", "level: at level L4", "level: at level L5 (OpenMP",
                          "level: at level L6", "level: at level L7 (dense grid",
                          "validate vs L0, 5 steps: 0 sets differ (0 pairs",
                          "search.reorder=off", "search.vector=off", "threads: at level"};
    expect_in_order(want, sizeof want / sizeof *want);
    cr_expect_null(strstr(out, "WRONG"), "%s", out);
    remove(scene);
}

/* ] doubles the particles (spacing and h / 2^(1/2)), [ halves them; the level is kept. */
Test(render_window, keys_change_n_live, .timeout = 120)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    char args[1024];
    snprintf(args, sizeof args, "view %s --threads 1 --frames 4 --keys 'lll]' --size 320x240", scene);
    int rc = window(args);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    unsigned n = 0;
    const char *p = strstr(out, " particles: spacing and h x 0.707");
    cr_assert_not_null(p, "%s", out);
    while (p > out && p[-1] >= '0' && p[-1] <= '9') p--;
    cr_assert_eq(sscanf(p, "%u", &n), 1, "%s", out);
    sph_sim *sim = test_sim(scene_2d, 1);
    cr_expect(n > 1.8 * sim->n && n < 2.2 * sim->n, "%u particles after ], %u before", n, sim->n);
    sph_sim_destroy(sim);
    remove(scene);
}

/* Through the library: N x 2 or / 2, h / spacing kept; a scene too large is refused with the reason. */
Test(render_window, rescaled_scene_keeps_h_over_spacing)
{
    sph_scene_def def = test_scene(scene_2d), more, fewer;
    char why[256];
    cr_assert(view_scene_rescaled(&def, powf(2.0f, -0.5f), &more, why, sizeof why), "%s", why);
    cr_assert(view_scene_rescaled(&def, powf(2.0f, 0.5f), &fewer, why, sizeof why), "%s", why);
    const double n = sph_scene_particle_count(&def);
    cr_expect(sph_scene_particle_count(&more) > 1.8 * n && sph_scene_particle_count(&more) < 2.2 * n);
    cr_expect(sph_scene_particle_count(&fewer) > 0.4 * n && sph_scene_particle_count(&fewer) < 0.6 * n);
    cr_expect_float_eq(more.h / more.blocks[0].spacing, def.h / def.blocks[0].spacing, 1e-5);
    cr_expect_float_eq(more.dt, def.cfl > 0 ? def.dt : def.dt * powf(2.0f, -0.5f), 1e-9, "a fixed dt goes with h");
    def.cfl = 0;
    cr_assert(view_scene_rescaled(&def, 0.5f, &more, why, sizeof why), "%s", why);
    cr_expect_float_eq(more.dt, 0.5f * def.dt, 1e-9, "a fixed dt goes with h");
    cr_expect_not(view_scene_rescaled(&def, 1e-3f, &more, why, sizeof why), "a billion particles accepted");
    cr_expect_gt(strlen(why), 10);
}

/* The passes as `sphlab check` numbers them: every one reachable (also past
 * 12), the numbers those check prints, when a pass is left out too. */
Test(render_window, pass_numbers_are_checks)
{
    const char *ini[] = {scene_2d,
                         "[scene]\ndimension = 2\neffects = gravity pressure viscosity cohesion walls interaction\n"
                         "[domain]\nmin = 0 0\nmax = 1 0.6\nwall_model = particles\n"
                         "[fluid block]\nmin = 0.1 0.1\nmax = 0.4 0.3\nspacing = 0.02\n"
                         "[kernels]\nh = 0.04\n[physics]\ndensity_method = continuity\nshifting = lind\n"};
    for (size_t s = 0; s < sizeof ini / sizeof *ini; s++) {
        const char *scene = test_write_temp(ini[s], ".ini");
        char args[512];
        snprintf(args, sizeof args, "check %s", scene);
        cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
        sph_sim *sim = test_sim(ini[s], 1);
        int in = 0, seen = 0;
        for (int p = 0; p < SPH_PASS_COUNT; p++) in += sim->in_pipeline[p];
        /* n from "no pass" walks every pass once and comes back */
        for (int p = view_pass_next(sim, -1, 1), k = 1; k <= in; p = view_pass_next(sim, p, 1), k++) {
            char line[96];
            snprintf(line, sizeof line, "  %2d. %-15s", k, sph_passes[p]->name);
            cr_expect_not_null(strstr(out, line), "'%s' not in check's output:\n%s", line, out);
            cr_expect_eq(view_pass_number(sim, p), k);
            cr_expect_eq(view_pass_of_number(sim, k), p);
            seen++;
        }
        cr_expect_eq(seen, in);
        cr_expect_eq(view_pass_next(sim, view_pass_of_number(sim, in), 1), view_pass_of_number(sim, 1), "wraps");
        cr_expect_eq(view_pass_next(sim, view_pass_of_number(sim, 1), -1), view_pass_of_number(sim, in));
        if (s == 1) cr_expect_gt(in, 12, "the second scene has passes past F12 (%d)", in);
        sph_sim_destroy(sim);
        remove(scene);
    }
}

/* n chooses a pass, d switches it (numbers as check's). */
Test(render_window, keys_choose_and_switch_passes, .timeout = 120)
{
    const char *scene = test_write_temp(scene_2d, ".ini");
    char args[1024];
    snprintf(args, sizeof args, "view %s --threads 1 --frames 5 --keys 'nnNdd' --size 320x240", scene);
    int rc = window(args);
    cr_assert_eq(rc, 0, "view exit %d: %s", rc, out);
    const char *want[] = {"pass 1 external chosen", "pass 2 hash chosen", "pass 1 external chosen",
                          "pass 1 external off", "pass 1 external on"};
    expect_in_order(want, sizeof want / sizeof *want);
    remove(scene);
}

/* The first frame of every lesson that selects a particle: the inspector
 * reads the particle's own cell (the cell of its position: at step 0 the
 * search sees it there), never cell (0,0) with hash 0 key 0. */
Test(render_window, lessons_first_frame_inspects_the_selected_cell, .timeout = 300)
{
    int with_select = 0;
    for (int n = 1; n <= 9; n++) {
        char args[256];
        snprintf(args, sizeof args, "lesson %d --frames 1 --threads 1 --size 480x320", n);
        int rc = window(args);
        cr_assert_eq(rc, 0, "lesson %d exit %d: %s", n, rc, out);
        const char *p = strstr(out, "inspector: particle ");
        if (!p) continue;
        with_select++;
        unsigned id = 0, index = 0;
        cr_assert_eq(sscanf(p, "inspector: particle %u (index %u)", &id, &index), 2, "%s", p);
        const char *c = strstr(out, "inspector: cell (");
        cr_assert_not_null(c, "lesson %d: no cell row:\n%s", n, out);
        int cell[3] = {0, 0, 0};
        int got = sscanf(c, "inspector: cell (%d, %d, %d)", &cell[0], &cell[1], &cell[2]);
        cr_assert(got >= 2, "%s", c);
        /* the lesson's scene, made as the window makes it: the cell of the particle's position */
        char path[256 + 16]; /* room for the folder's name and "/lesson.ini" */
        snprintf(path, sizeof path, "lessons/0%d-", n);
        char cmd[300], dir[256] = "";
        snprintf(cmd, sizeof cmd, "ls -d %s* 2>/dev/null", path);
        FILE *ls = popen(cmd, "r");
        cr_assert_not_null(ls);
        cr_assert_not_null(fgets(dir, sizeof dir, ls));
        pclose(ls);
        dir[strcspn(dir, "\n")] = '\0';
        snprintf(path, sizeof path, "%s/lesson.ini", dir);
        sph_scene_def def = sph_default_scene_def();
        sph_error err;
        cr_assert_eq(sph_scene_load(path, &def, &err), SPH_ERR_OK, "%s", err.msg);
        sph_sim *sim = NULL;
        cr_assert_eq(sph_sim_create(&def, 1, &sim, &err), SPH_ERR_OK, "%s", err.msg);
        int32_t i = -1;
        for (uint32_t k = 0; k < sim->n; k++)
            if (sim->P.id[k] == id) i = (int32_t)k;
        cr_assert_geq(i, 0);
        for (int d = 0; d < sim->dim; d++) {
            int32_t want = sph_cells_coord(&sim->S.cells, d, sim->P.pos[d][i]);
            cr_expect_eq(cell[d], want, "lesson %d, particle %u: cell[%d] = %d in the inspector, %d at its position",
                         n, id, d, cell[d], want);
        }
        sph_sim_destroy(sim);
    }
    cr_expect_geq(with_select, 4, "lessons 1, 2, 5 and 6 select a particle");
}

/* The key labels carry their cell's size, which the renderer holds a 3D
 * label to (a label wider than its cell, as drawn, is left out). */
Test(render_window, key_labels_carry_their_cells_size)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    sph_sim_step(sim);
    sph_overlay ov;
    memset(&ov, 0, sizeof ov);
    sph_overlay_opts o = {.layers = SPH_OV_BIT(KEYS) | SPH_OV_BIT(NEIGHBOURS), .selected = 10};
    cr_assert(sph_overlay_build(sim, &o, &ov));
    int keys = 0;
    for (int k = 0; k < ov.n_labels; k++) {
        if (ov.labels[k].fit[0] > 0) {
            keys++;
            cr_expect_float_eq(ov.labels[k].fit[0], sim->S.cells.size[0], 1e-6);
            cr_expect_float_eq(ov.labels[k].fit[1], sim->S.cells.size[1], 1e-6);
        }
    }
    cr_expect_eq(keys, ov.n_cells, "one sized label per occupied cell");
    cr_expect_gt(ov.n_labels, keys, "the neighbours' labels are not held to a cell");
    sph_overlay_free(&ov);
    sph_sim_destroy(sim);
}

/* Speed-ups of levels not visited here come from the last bench ladder CSV,
 * said as such; a level measured live wins over it. */
/* The ingredients row says what runs: brute force has no reorder pass (it read "reorder on") and L0 runs on one
 * thread of the CPU. */
Test(render_window, ingredients_say_what_runs)
{
    sph_scene_def def = test_scene(scene_2d);
    sph_error err;
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L0")], &def, &err), SPH_ERR_OK);
    def.reorder = SPH_ON; /* the key as a scene may leave it: brute force leaves the pass out anyway */
    sph_sim *sim = NULL;
    cr_assert_eq(sph_sim_create(&def, 1, &sim, &err), SPH_ERR_OK);
    cr_assert(!sim->in_pipeline[SPH_PASS_REORDER]);
    view_ladder l;
    memset(&l, 0, sizeof l);
    char lines[8][128];
    int n = view_ladder_lines(&l, sim, lines, 8);
    cr_assert_geq(n, 2);
    cr_expect(strstr(lines[1], "reorder -, ") && strstr(lines[1], "1 thread, cpu"), "%s", lines[1]);
    sph_sim_destroy(sim);
}

Test(render_window, speedups_from_the_bench_csv_when_not_visited)
{
    const char *csv = test_write_temp(
        "level,description,backend,threads,max_n,capped,steps_per_s_at_max,speedup,n_at,ms_per_step,pairs_per_step\n"
        "L0,brute,cpu,1,,0,,,5000,40,1\n"
        "L2,seed,cpu,1,20000,0,61,,5000,4,1\n"
        "L3,counting sort,cpu,1,25000,0,60,1.2,5000,2,1\n",
        ".csv");
    view_ladder l;
    memset(&l, 0, sizeof l);
    cr_assert(view_ladder_load_csv(&l, csv));
    const int l0 = sph_level_find("L0"), l2 = sph_level_find("L2"), l3 = sph_level_find("L3");
    cr_expect_eq(l.csv_ms[l0], 40.0, "an empty max_n does not shift the columns");
    cr_expect_eq(l.csv_ms[l3], 2.0);
    cr_expect_eq(l.csv_n[l3], 5000.0);
    sph_scene_def def = test_scene(scene_2d);
    sph_error err;
    cr_assert_eq(sph_level_apply(&sph_levels[l3], &def, &err), SPH_ERR_OK);
    sph_sim *sim = NULL;
    cr_assert_eq(sph_sim_create(&def, 1, &sim, &err), SPH_ERR_OK);
    for (int s = 0; s < 3; s++) sph_sim_step(sim);
    char lines[8][128];
    int n = view_ladder_lines(&l, sim, lines, 8);
    bool found = false;
    for (int k = 0; k < n; k++)
        if (strstr(lines[k], "x2 vs L2 (bench CSV, N=5000)") && strstr(lines[k], "x20 vs L0 (bench CSV")) found = true;
    cr_expect(found, "no CSV speed-ups in: %s | %s | %s", lines[0], n > 2 ? lines[2] : "", n > 3 ? lines[3] : "");
    /* L2 measured live: that one is live, L0 still from the CSV */
    l.ms[l2] = 1000.0;
    n = view_ladder_lines(&l, sim, lines, 8);
    found = false;
    for (int k = 0; k < n; k++)
        if (strstr(lines[k], "vs L2,") && !strstr(lines[k], "vs L2 (bench") && strstr(lines[k], "vs L0 (bench CSV"))
            found = true;
    cr_expect(found, "live L2 not preferred: %s", n > 2 ? lines[2] : "");
    cr_expect_not(view_ladder_load_csv(&l, "/nonexistent/ladder-2d.csv"));
    sph_sim_destroy(sim);
    remove(csv);
}

/* A switch carries the state into a new simulation (sph_sim_reconfigure,
 * sph_sim_clone) whose start-up predicted the placement's positions: the
 * selection is drawn where the particle is now, not where it was placed. */
Test(render_window, selection_follows_a_carried_state)
{
    sph_sim *sim = test_sim(scene_2d, 1);
    for (int s = 0; s < 200; s++) sph_sim_step(sim); /* the block has fallen and spread */
    sph_scene_def def = sim->def;
    sph_error err;
    cr_assert_eq(sph_scene_set(&def, "search.sort=qsort", &err), SPH_ERR_OK);
    cr_assert_eq(sph_sim_reconfigure(sim, &def, &err), SPH_ERR_OK, "%s", err.msg);
    int moved = 0;
    for (uint32_t i = 0; i < sim->n; i += 7) {
        sph_overlay ov;
        memset(&ov, 0, sizeof ov);
        sph_overlay_opts o = {.layers = SPH_OV_BIT(NEIGHBOURS), .selected = (int32_t)i};
        cr_assert(sph_overlay_build(sim, &o, &ov));
        for (int d = 0; d < 2; d++) {
            int32_t want = sph_cells_coord(&sim->S.cells, d, sim->P.pos[d][i]);
            cr_expect_eq(ov.sel_cell[d], want, "particle %u: cell[%d] %d drawn, %d where it is", i, d, ov.sel_cell[d],
                         want);
        }
        sph_overlay_free(&ov);
        moved++;
    }
    cr_expect_gt(moved, 10);
    sph_sim_destroy(sim);
}

/* Validate refuses brute force where it would freeze the window, and says what to use. */
Test(render_window, validate_refuses_brute_force_at_large_n)
{
    sph_sim *sim = test_sim("[scene]\ndimension = 2\neffects = density\n[domain]\nmin = 0 0\nmax = 3.2 3.2\n"
                            "[fluid a]\nmin = 0 0\nmax = 3 3\nspacing = 0.02\n[kernels]\nh = 0.04\n",
                            1);
    cr_assert_gt(sim->n, VIEW_VALIDATE_BRUTE_MAX);
    view_ladder l;
    memset(&l, 0, sizeof l);
    char msg[300];
    cr_expect_not(view_validate(&l, sim, "L0", msg, sizeof msg));
    cr_expect(strstr(msg, "shift+a") && strstr(msg, "brute force"), "%s", msg);
    cr_expect_not(l.validated);
    cr_expect_not(view_validate(&l, sim, "L99", msg, sizeof msg));
    cr_expect(strstr(msg, "no such reference level"), "%s", msg);
    sph_sim_destroy(sim);
}
