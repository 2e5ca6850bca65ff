/* The ladder's levels (src/core/sph_levels.c) and validate mode
 * (src/core/sph_compare.c): every CPU level finds the same neighbour sets as
 * brute force from the same state, and a perturbed state is caught. */
#include <criterion/criterion.h>
#include <math.h>
#include <string.h>

#include "sph_compare.h"
#include "sph_levels.h"
#include "test_util.h"

/* A dam break of about 600 particles off their lattice (jitter), with
 * periodic x so the nearest-image paths are compared too. */
static const char *const scene_2d =
    "[scene]\ndimension = 2\neffects = gravity pressure viscosity walls\njitter = 0.2\n"
    "[domain]\nmin = 0 0\nmax = 1.2 0.8\nperiodic = x\n"
    "[fluid block]\nmin = 0.02 0.02\nmax = 0.62 0.42\nspacing = 0.02\n"
    "[kernels]\nh = 0.04\n[time]\ndt = 0.0005\n";
static const char *const scene_3d =
    "[scene]\ndimension = 3\neffects = gravity pressure viscosity walls\njitter = 0.2\n"
    "[domain]\nmin = 0 0 0\nmax = 0.4 0.4 0.4\n"
    "[fluid block]\nmin = 0.02 0.02 0.02\nmax = 0.2 0.24 0.2\nspacing = 0.02\n"
    "[kernels]\nh = 0.04\n[time]\ndt = 0.0005\n";

static sph_sim *sim_at(const char *ini, const sph_level *L)
{
    sph_scene_def def = test_scene(ini);
    sph_error err;
    cr_assert_eq(sph_level_apply(L, &def, &err), SPH_ERR_OK, "%s: %s", L->name, err.msg);
    sph_sim *sim = NULL;
    cr_assert_eq(sph_sim_create(&def, L->threads, &sim, &err), SPH_ERR_OK, "%s: %s", L->name, err.msg);
    return sim;
}

static void every_level_matches(const char *ini)
{
    const sph_level *ref = &sph_levels[sph_level_find("L0")];
    int checked = 0;
    for (int l = 0; l < sph_level_count; l++) {
        const sph_level *L = &sph_levels[l];
        if (sph_level_gl(L)) continue; /* the GL levels: tests/test_gl_backend.c's device */
        sph_sim *sim = sim_at(ini, L);
        for (int s = 0; s < 5; s++) sph_sim_step(sim); /* a state that has moved */
        sph_compare_result r;
        sph_error err;
        cr_assert_eq(sph_sim_validate(sim, ref, 4, &r, &err), SPH_ERR_OK, "%s: %s", L->name, err.msg);
        cr_expect_eq(r.n, sim->n);
        cr_expect_eq(r.steps, 4);
        cr_expect(r.pairs_a > 5.0 * sim->n, "%s: %.0f pairs for %u particles", L->name, r.pairs_a, sim->n);
        cr_expect_eq(r.sets_differ, 0, "%s: %u neighbour sets differ from L0's", L->name, r.sets_differ);
        cr_expect_eq(r.pairs_a, r.pairs_b, "%s: %.0f pairs, L0 %.0f", L->name, r.pairs_a, r.pairs_b);
        /* sums in another order only: far below a spacing after 4 steps */
        cr_expect(r.dx < 1e-5, "%s: positions differ from L0's by %g m", L->name, r.dx);
        cr_expect(!r.stopped);
        /* the level is the one its keys name */
        cr_expect_eq(sph_level_of(&sim->def, L->threads, 64), l,
                     "%s is named %d", L->name, sph_level_of(&sim->def, L->threads, 64));
        sph_sim_destroy(sim);
        checked++;
    }
    cr_expect_eq(checked, 19, "levels L0..L18");
}

Test(levels, every_cpu_level_finds_brute_forces_sets_2d) { every_level_matches(scene_2d); }
Test(levels, every_cpu_level_finds_brute_forces_sets_3d) { every_level_matches(scene_3d); }

/* A wrong comparison is seen: the same state with one particle moved by
 * 0.6 h gives other neighbour sets (and positions) at once. */
Test(levels, perturbed_state_is_detected)
{
    sph_sim *a = sim_at(scene_2d, &sph_levels[sph_level_find("L3")]);
    sph_sim_step(a);
    sph_sim *b = NULL;
    sph_error err;
    cr_assert_eq(sph_sim_clone(a, &a->def, a->threads, &b, &err), SPH_ERR_OK, "%s", err.msg);
    sph_compare_result r;
    cr_assert_eq(sph_sim_compare(a, b, 2, &r, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(r.sets_differ, 0, "a copy of the same state: %u sets differ", r.sets_differ);
    cr_expect_eq(r.dx, 0.0, "a copy of the same state at the same level: dx %g", r.dx);
    const uint32_t i = b->n / 2;
    b->P.pos[0][i] += 0.6f * b->def.h;
    cr_assert_eq(sph_sim_compare(a, b, 2, &r, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_gt(r.sets_differ, 1, "a particle moved by 0.6 h: only %u sets differ", r.sets_differ);
    cr_expect_eq(r.worst_id, b->P.id[i], "the moved particle (id %u) differs most, not %u", b->P.id[i], r.worst_id);
    cr_expect_gt(r.dx, 0.5 * b->def.h, "dx %g", r.dx);
    char text[256];
    sph_compare_text(&r, "L3", text, sizeof text);
    cr_expect(strstr(text, "WRONG") != NULL, "%s", text);
    sph_sim_destroy(a);
    sph_sim_destroy(b);
}

/* A comparison leaves the compared simulations as they were. */
Test(levels, validate_leaves_the_simulation_alone)
{
    sph_sim *a = sim_at(scene_2d, &sph_levels[sph_level_find("L7")]);
    sph_sim_step(a);
    const uint64_t step = a->step;
    const float x = a->P.pos[1][10];
    sph_compare_result r;
    sph_error err;
    cr_assert_eq(sph_sim_validate(a, &sph_levels[0], 3, &r, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_eq(a->step, step);
    cr_expect_eq(a->P.pos[1][10], x);
    sph_sim_destroy(a);
}

/* Levels name themselves; a mix of ingredients is no level. */
Test(levels, level_of_the_ingredients)
{
    sph_scene_def def = test_scene(scene_2d);
    sph_error err;
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L4")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(sph_level_of(&def, 1, 8), sph_level_find("L4"));
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L5"), "all cores: L5");
    cr_expect_eq(sph_level_of(&def, 0, 1), sph_level_find("L4"), "one core: all cores is one thread");
    def.sort = SPH_SORT_BITONIC; /* reorder with bitonic: no level has it */
    cr_expect_eq(sph_level_of(&def, 1, 8), -1);
    cr_expect_eq(sph_level_find("G2") >= 0 && sph_level_gl(&sph_levels[sph_level_find("G2")]), true);
    cr_expect_eq(sph_level_find("L99"), -1);
    /* down from L9 to L7 (the window's shift+l): nothing of L8 or L9 stays on */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L9")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L9"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L7")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.fuse_forces, SPH_OFF);
    cr_expect_eq(def.lists_in_place, SPH_OFF);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L7"));
    /* L10 is L9 with a skin; down from L10 to L9 the lists are built every step again */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L10")], &def, &err), SPH_ERR_OK);
    cr_expect_gt(def.skin, 0.0f);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L10"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L9")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.skin, 0.0f);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L9"));
    /* L12 is L11 with the AVX2 loops; down to L11 they are off again */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L12")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.vector_avx2, SPH_ON);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L12"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L11")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.vector_avx2, SPH_OFF);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L11"));
    /* L13 is L12 reading packed records; down to L12 they are off again */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L13")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.packed_records, SPH_ON);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L13"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L12")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.packed_records, SPH_OFF);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L12"));
    /* L14 is L13 with one mass for all; down to L13 it is off again */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L14")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.uniform_mass, SPH_ON);
    cr_expect_eq(def.packed_records, SPH_ON);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L14"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L13")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.uniform_mass, SPH_OFF);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L13"));
    /* L15 is L14 searching a cell's particles together; down to L14 it is off again */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L15")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.cell_batch, SPH_ON);
    cr_expect_eq(def.uniform_mass, SPH_ON);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L15"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L14")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.cell_batch, SPH_OFF);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L14"));
    /* L16 is L15 with density's walk 16 lanes wide; down to L15 it is off again */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L16")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.wide_density, SPH_ON);
    cr_expect_eq(def.cell_batch, SPH_ON);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L16"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L15")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.wide_density, SPH_OFF);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L15"));
    /* L17 is L16 with the search's batch 16 wide; down to L16 it is off again */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L17")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.wide_batch, SPH_ON);
    cr_expect_eq(def.wide_density, SPH_ON);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L17"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L16")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.wide_batch, SPH_OFF);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L16"));
    /* L18 is L17 keeping the lists' pages; down to L17 it is off again */
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L18")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.lists_resident, SPH_ON);
    cr_expect_eq(def.wide_batch, SPH_ON);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L18"));
    cr_assert_eq(sph_level_apply(&sph_levels[sph_level_find("L17")], &def, &err), SPH_ERR_OK);
    cr_expect_eq(def.lists_resident, SPH_OFF);
    cr_expect_eq(sph_level_of(&def, 0, 8), sph_level_find("L17"));
}
