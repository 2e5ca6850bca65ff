/* A scene written back as a scene file (sph_scene_write, the window's "Save
 * scene as…", `sphlab check --save-scene`) loads into the same definition:
 * every key of the table, each fluid block, the shipped scenes. */
#define _DEFAULT_SOURCE /* open_memstream */
#include <criterion/criterion.h>
#include <glob.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "test_util.h"

/* Bytes a key's value takes in the definition. */
static size_t key_size(const sph_key *k)
{
    switch (k->type) {
    case SPH_KEY_STRING: return 64;
    case SPH_KEY_VEC: return 3 * sizeof(float);
    case SPH_KEY_POINT: return 3 * sizeof(double);
    default: return 4;
    }
}

/* Compares the values of every key (raw bytes, so -0 and 0 or two NaNs would
 * differ), the blocks' count and names; names the first difference. */
static void expect_same_def(const sph_scene_def *a, const sph_scene_def *b, const char *what)
{
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        if (strcmp(k->section, "fluid") == 0 || strcmp(k->section, "obstacle") == 0) continue;
        cr_expect(memcmp((const char *)a + k->offset, (const char *)b + k->offset, key_size(k)) == 0,
                  "%s: [%s] %s differs after the round trip", what, k->section, k->name);
    }
    cr_assert_eq(a->n_blocks, b->n_blocks, "%s: %d blocks, then %d", what, a->n_blocks, b->n_blocks);
    for (int bl = 0; bl < a->n_blocks; bl++) {
        cr_expect_str_eq(a->blocks[bl].name, b->blocks[bl].name, "%s: block %d's name", what, bl);
        for (int i = 0; i < sph_scene_key_count; i++) {
            const sph_key *k = &sph_scene_keys[i];
            if (strcmp(k->section, "fluid") != 0) continue;
            cr_expect(memcmp((const char *)&a->blocks[bl] + k->offset, (const char *)&b->blocks[bl] + k->offset,
                             key_size(k)) == 0,
                      "%s: [fluid %s] %s differs after the round trip", what, a->blocks[bl].name, k->name);
        }
    }
    cr_assert_eq(a->n_obstacles, b->n_obstacles, "%s: %d obstacles, then %d", what, a->n_obstacles, b->n_obstacles);
    for (int o = 0; o < a->n_obstacles; o++) {
        cr_expect_str_eq(a->obstacles[o].name, b->obstacles[o].name, "%s: obstacle %d's name", what, o);
        for (int i = 0; i < sph_scene_key_count; i++) {
            const sph_key *k = &sph_scene_keys[i];
            if (strcmp(k->section, "obstacle") != 0) continue;
            cr_expect(memcmp((const char *)&a->obstacles[o] + k->offset, (const char *)&b->obstacles[o] + k->offset,
                             key_size(k)) == 0,
                      "%s: [obstacle %s] %s differs after the round trip", what, a->obstacles[o].name, k->name);
        }
    }
}

/* def written to text, which the caller frees. */
static char *write_text(const sph_scene_def *def)
{
    char *text = NULL;
    size_t len = 0;
    FILE *f = open_memstream(&text, &len);
    cr_assert_not_null(f);
    sph_error err = {0};
    cr_assert_eq(sph_scene_write(def, f, &err), SPH_ERR_OK, "%s", err.msg);
    fclose(f);
    return text;
}

/* Writes def, loads the text over the defaults, validates, compares. */
static void round_trip(const sph_scene_def *def, const char *what)
{
    char *text = write_text(def);
    sph_scene_def back = sph_default_scene_def();
    sph_error err = {0};
    cr_assert_eq(sph_scene_load_string(text, "saved.ini", &back, &err), SPH_ERR_OK, "%s: %s\n%s", what, err.msg, text);
    cr_assert_eq(sph_scene_validate(&back, &err), SPH_ERR_OK, "%s: %s\n%s", what, err.msg, text);
    expect_same_def(def, &back, what);
    free(text);
}

#define BASE2                                                                                                 \
    "[scene]\nname = two blocks\ndimension = 2\n[domain]\nmin = 0 0\nmax = 1 1\n[fluid a]\nmin = 0 0\n"      \
    "max = 0.2 0.2\nspacing = 0.02\n[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\nspacing = 0.025\n"              \
    "velocity = 0.1 -0.3\n"

Test(scene_write, a_scene_with_two_blocks_reads_back_the_same)
{
    sph_scene_def def = test_scene(BASE2 "[physics]\nviscosity = 0.0123\ngravity = 0.1 -3.3\n[kernels]\nh = 0.043\n"
                                         "density = cubic\n[scene]\neffects = gravity pressure walls\n");
    round_trip(&def, "two blocks");
}

Test(scene_write, obstacles_read_back_the_same)
{
    sph_scene_def def = test_scene(BASE2 "[domain]\nwall_model = particles\nwall_slip_xmin = free\n"
                                         "[obstacle box]\nshape = box\nmin = 0.3 0\nmax = 0.4 0.1\n"
                                         "[obstacle ball]\nshape = circle\ncentre = 0.8 0.2\nradius = 0.05\n"
                                         "slip = free\n");
    cr_assert_eq(def.n_obstacles, 2);
    round_trip(&def, "two obstacles");
}

/* A value other than the default, inside the key's range, as a file would write it. */
static void other_value(const sph_key *k, char *out, size_t n)
{
    double lo = k->min, hi = fmin(k->max, k->min + 10.0);
    switch (k->type) {
    case SPH_KEY_FLOAT: snprintf(out, n, "%.9g", (double)(float)(lo + 0.37 * (hi - lo)) + (k->min_open ? 1e-3 : 0)); return;
    case SPH_KEY_INT:
    case SPH_KEY_UINT: snprintf(out, n, "%.0f", floor(lo + 0.5 * (hi - lo)) + 1.0); return;
    case SPH_KEY_VEC: snprintf(out, n, "0.125 -0.25 0.5"); return;
    case SPH_KEY_POINT: snprintf(out, n, "0.1 -0.3 0.7"); return; /* not exact in binary: 17 digits needed */
    case SPH_KEY_CHOICE:
    case SPH_KEY_KERNEL:
        for (int c = 0; c < k->n_choices; c++)
            if (strcmp(k->choices[c], k->def) != 0) {
                snprintf(out, n, "%s", k->choices[c]);
                return;
            }
        snprintf(out, n, "%s", k->def);
        return;
    case SPH_KEY_FLAGS: snprintf(out, n, "%s %s", k->choices[0], k->choices[k->n_choices - 1]); return;
    case SPH_KEY_STRING: snprintf(out, n, "a name with spaces"); return;
    }
}

/* Each key of the table set to a value other than its default (one at a
 * time: together they would not make a valid scene), written, read back. */
Test(scene_write, every_key_reads_back_the_value_it_was_given)
{
    const sph_scene_def base = test_scene(BASE2);
    int tried = 0;
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        if (strcmp(k->section, "scene") == 0 && strcmp(k->name, "dimension") == 0) continue; /* the blocks are 2D */
        if (strcmp(k->section, "obstacle") == 0) continue; /* the base has none: obstacles_read_back_the_same */
        char value[128], assignment[256];
        other_value(k, value, sizeof value);
        snprintf(assignment, sizeof assignment, "%s.%s=%s", k->section, k->name, value);
        sph_scene_def def = base;
        sph_error err = {0};
        cr_assert_eq(sph_scene_set(&def, assignment, &err), SPH_ERR_OK, "%s: %s", assignment, err.msg);
        char *text = write_text(&def);
        sph_scene_def back = sph_default_scene_def();
        cr_assert_eq(sph_scene_load_string(text, "saved.ini", &back, &err), SPH_ERR_OK, "%s: %s\n%s", assignment,
                     err.msg, text);
        expect_same_def(&def, &back, assignment);
        free(text);
        tried++;
    }
    cr_expect_geq(tried, 40, "only %d keys tried", tried);
}

Test(scene_write, only_the_keys_that_differ_are_written)
{
    sph_scene_def def = test_scene(BASE2 "[physics]\nviscosity = 0.01\nstiffness = 1000\n");
    char *text = write_text(&def);
    cr_expect(strstr(text, "name = two blocks\n") && strstr(text, "dimension = 2\n"), "%s", text);
    cr_expect(strstr(text, "[physics]\nviscosity = 0.01\n"), "the change, shortest form: %s", text);
    cr_expect(!strstr(text, "stiffness"), "stiffness = 1000 is the default: %s", text);
    cr_expect(!strstr(text, "[time]"), "no section without a change: %s", text);
    cr_expect(strstr(text, "[fluid b]\nmin = 0.5 0.5 0\nmax = 0.7 0.7 0\nspacing = 0.025\nvelocity = 0.1 -0.3 0\n"),
              "%s", text);
    free(text);
}

/* An unnamed scene gets no empty "name = " line (check --save-scene wrote one); its dimension is written always. */
Test(scene_write, an_unnamed_scene_writes_no_name)
{
    sph_scene_def def = test_scene("[scene]\ndimension = 2\n[domain]\nmax = 1 1\n[fluid a]\nmax = 0.5 0.5\nspacing = 0.05\n");
    char *text = write_text(&def);
    cr_expect(!strstr(text, "name ="), "%s", text);
    cr_expect(strstr(text, "[scene]\ndimension = 2\n"), "%s", text);
    free(text);
}

Test(scene_write, a_name_a_file_could_not_hold_is_refused)
{
    sph_scene_def def = test_scene(BASE2);
    snprintf(def.name, sizeof def.name, "two\nlines");
    char buf[256];
    FILE *f = fmemopen(buf, sizeof buf, "w");
    sph_error err = {0};
    cr_expect_eq(sph_scene_write(&def, f, &err), SPH_ERR_RANGE);
    cr_expect(strstr(err.msg, "newline"), "%s", err.msg);
    fclose(f);
}

Test(scene_write, the_shipped_scenes_read_back_the_same)
{
    glob_t g;
    cr_assert_eq(glob("lessons/scenes/*.ini", 0, NULL, &g), 0, "no scenes found (run from the repository root)");
    for (size_t s = 0; s < g.gl_pathc; s++) {
        sph_scene_def def = sph_default_scene_def();
        sph_error err = {0};
        if (sph_scene_load(g.gl_pathv[s], &def, &err) != SPH_ERR_OK) continue; /* test_scene checks them */
        round_trip(&def, g.gl_pathv[s]);
    }
    cr_expect_gt(g.gl_pathc, 3);
    globfree(&g);
}

/* The command line: the file appears, reproduces the run's scene, and never
 * replaces the scene it was read from. */
Test(scene_write, check_save_scene_writes_a_file_check_accepts)
{
    const char *scene = test_write_temp(BASE2, ".ini");
    char out_path[] = "/tmp/sphlab-saved-XXXXXX.ini", args[1024], out[8192];
    int fd = mkstemps(out_path, 4);
    cr_assert_geq(fd, 0);
    close(fd);
    snprintf(args, sizeof args, "check %s --set physics.viscosity=0.02 --save-scene %s", scene, out_path);
    cr_assert_eq(test_sphlab(args, out, sizeof out), 0, "%s", out);
    cr_expect(strstr(out, "saved "), "%s", out);
    sph_scene_def saved = sph_default_scene_def(), want = test_scene(BASE2 "[physics]\nviscosity = 0.02\n");
    sph_error err = {0};
    cr_assert_eq(sph_scene_load(out_path, &saved, &err), SPH_ERR_OK, "%s", err.msg);
    expect_same_def(&want, &saved, "check --save-scene");
    snprintf(args, sizeof args, "check %s --save-scene %s", scene, scene);
    cr_expect_eq(test_sphlab(args, out, sizeof out), 1, "%s", out);
    cr_expect(strstr(out, "sphlab check:"), "%s", out);
    remove(out_path);
    remove(scene);
}
