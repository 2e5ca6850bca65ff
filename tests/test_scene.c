/* Scene files: every error names the file, the line, the key and the accepted
 * range, and is refused with a non-zero exit before anything is simulated;
 * checked both on the library (sph_scene_load_string + sph_scene_validate)
 * and on the sphlab binary. Also: the shipped scenes load, and
 * docs/scene-format.md documents every key of sph_scene_keys.
 * A case that fails here is the specification: fix the code, not the test. */
#define _DEFAULT_SOURCE /* mkstemps, mkdtemp */
#include <criterion/criterion.h>
#include <dirent.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include "test_util.h"

/* A valid 2D scene of 9 lines (10 x 10 = 100 particles); what a test appends starts on line 10. */
#define BASE2                                                                                                   \
    "[scene]\ndimension = 2\n[domain]\nmin = 0 0\nmax = 1 1\n[fluid a]\nmin = 0 0\nmax = 0.2 0.2\n"            \
    "spacing = 0.02\n"
/* The same in 3D (10^3 = 1000 particles), also 9 lines. */
#define BASE3                                                                                                   \
    "[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n[fluid a]\nmin = 0 0 0\nmax = 0.2 0.2 0.2\n"  \
    "spacing = 0.02\n"

/* ---- helpers ------------------------------------------------------------ */

/* Loads text as "x.ini" over the defaults and validates it, as sphlab does. */
static sph_error_code lib_load(const char *text, sph_scene_def *out, sph_error *err)
{
    sph_scene_def def = sph_default_scene_def();
    memset(err, 0, sizeof *err);
    sph_error_code c = sph_scene_load_string(text, "x.ini", &def, err);
    if (c == SPH_ERR_OK) c = sph_scene_validate(&def, err);
    if (out) *out = def;
    return c;
}

static void expect_msg(const char *msg, const char *const *needles, const char *what)
{
    for (int i = 0; needles[i]; i++)
        cr_expect(strstr(msg, needles[i]) != NULL, "%s: message lacks '%s':\n  %s", what, needles[i], msg);
}

/* The scene must be refused with `want`, the message containing each needle. */
static void expect_lib(const char *text, sph_error_code want, const char *const *needles)
{
    sph_error err;
    sph_error_code c = lib_load(text, NULL, &err);
    cr_expect_eq(c, want, "want %s, got %s (%s) for:\n%s", sph_error_name(want), sph_error_name(c),
                 c ? err.msg : "accepted", text);
    if (c) expect_msg(err.msg, needles, text);
}
#define EXPECT_LIB(text, code, ...) expect_lib(text, code, (const char *const[]){__VA_ARGS__, NULL})

/* Refused with either code (a value can fairly be "out of range" or "not a number"). */
static void expect_lib2(const char *text, sph_error_code a, sph_error_code b, const char *const *needles)
{
    sph_error err;
    sph_error_code c = lib_load(text, NULL, &err);
    cr_expect(c == a || c == b, "want %s or %s, got %s (%s) for:\n%s", sph_error_name(a), sph_error_name(b),
              sph_error_name(c), c ? err.msg : "accepted", text);
    if (c) expect_msg(err.msg, needles, text);
}
#define EXPECT_LIB2(text, a, b, ...) expect_lib2(text, a, b, (const char *const[]){__VA_ARGS__, NULL})

static void expect_ok(const char *text)
{
    sph_error err;
    sph_error_code c = lib_load(text, NULL, &err);
    cr_expect_eq(c, SPH_ERR_OK, "scene refused: %s\n%s", err.msg, text);
}

static bool exists(const char *path)
{
    struct stat st;
    return stat(path, &st) == 0;
}

/* Runs "$SPHLAB args" under `timeout`, so a hang fails the test (exit 124) instead of the suite. */
static int sphlab_timed(int seconds, char *out, size_t cap, const char *fmt, ...)
{
    char args[2048];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(args, sizeof args, fmt, ap);
    va_end(ap);
    const char *bin = getenv("SPHLAB");
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "timeout -s KILL %d %s %s 2>&1", seconds, bin && *bin ? bin : "./sphlab", args);
    FILE *p = popen(cmd, "r");
    cr_assert(p != NULL, "cannot run %s", cmd);
    size_t n = fread(out, 1, cap - 1, p);
    out[n] = '\0';
    char sink[4096];
    while (fread(sink, 1, sizeof sink, p) > 0) {}
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

/* The binary refuses the scene at `path` with exit 1, naming the path, "path:line:" (line > 0) and the key,
 * in `run` and in `check`; nothing is simulated (the --stats file is never made). */
static void expect_cli_path(const char *path, int line, const char *key, const char *what)
{
    char out[8192], stats[320], tmp[340], loc[320];
    snprintf(stats, sizeof stats, "%s.stats.csv", path);
    snprintf(tmp, sizeof tmp, "%s.tmp", stats);
    snprintf(loc, sizeof loc, "%s:%d:", path, line);
    int rc = sphlab_timed(30, out, sizeof out, "run '%s' --steps 1 --quiet --stats '%s'", path, stats);
    cr_expect_eq(rc, 1, "%s: run exit %d, want 1; output:\n%s", what, rc, out);
    cr_expect(strstr(out, path) != NULL, "%s: run output lacks the path %s:\n%s", what, path, out);
    if (line > 0) cr_expect(strstr(out, loc) != NULL, "%s: run output lacks '%s':\n%s", what, loc, out);
    if (key) cr_expect(strstr(out, key) != NULL, "%s: run output lacks the key '%s':\n%s", what, key, out);
    cr_expect(!exists(stats) && !exists(tmp), "%s: a refused scene left %s", what, stats);
    remove(stats);
    remove(tmp);

    rc = sphlab_timed(30, out, sizeof out, "check '%s'", path);
    cr_expect_eq(rc, 1, "%s: check exit %d, want 1; output:\n%s", what, rc, out);
    cr_expect(strstr(out, path) != NULL, "%s: check output lacks the path %s:\n%s", what, path, out);
    if (line > 0) cr_expect(strstr(out, loc) != NULL, "%s: check output lacks '%s':\n%s", what, loc, out);
    if (key) cr_expect(strstr(out, key) != NULL, "%s: check output lacks the key '%s':\n%s", what, key, out);
    cr_expect(strstr(out, "\nok\n") == NULL && strncmp(out, "ok\n", 3) != 0, "%s: check said ok:\n%s", what, out);
}

static void expect_cli(const char *text, int line, const char *key)
{
    char path[256];
    snprintf(path, sizeof path, "%s", test_write_temp(text, ".ini"));
    expect_cli_path(path, line, key, text);
    remove(path);
}

/* Writes n raw bytes (NULs included) to a fresh file under /tmp. */
static void write_binary(char *path, size_t cap, const void *bytes, size_t n)
{
    snprintf(path, cap, "/tmp/sphlab-test-XXXXXX.ini");
    int fd = mkstemps(path, 4);
    cr_assert(fd >= 0, "cannot make a temporary file");
    cr_assert_eq(write(fd, bytes, n), (ssize_t)n);
    close(fd);
}

/* ---- library: one case per kind of error ---------------------------------- */

Test(scene, control_scenes_load)
{
    expect_ok(BASE2);
    expect_ok(BASE3);
    expect_ok(BASE2 "; a comment\n# another comment\n[kernels]\nh = 0.04 ; inline comment\n");
    char out[8192];
    const char *path = test_write_temp(BASE2, ".ini");
    char cmd[512];
    snprintf(cmd, sizeof cmd, "run %s --steps 1 --quiet", path);
    int rc = test_sphlab(cmd, out, sizeof out);
    cr_expect_eq(rc, 0, "a valid scene: run exit %d:\n%s", rc, out);
    snprintf(cmd, sizeof cmd, "check %s", path);
    int rc2 = test_sphlab(cmd, out, sizeof out);
    cr_expect_eq(rc2, 0, "a valid scene: check exit %d:\n%s", rc2, out);
    cr_expect(strstr(out, "\nok\n") != NULL, "check prints ok:\n%s", out);
    remove(path);
}

Test(scene, unknown_section)
{
    EXPECT_LIB(BASE2 "[foo]\nx = 1\n", SPH_ERR_UNKNOWN_SECTION, "x.ini:10", "[foo]", "accepted:", "fluid NAME");
    /* an unknown section without keys: inih alone would pass over it */
    EXPECT_LIB(BASE2 "[foo]\n", SPH_ERR_UNKNOWN_SECTION, "x.ini:10", "[foo]", "accepted:");
    EXPECT_LIB("[Scene]\ndimension = 2\n", SPH_ERR_UNKNOWN_SECTION, "x.ini:1", "Scene", "accepted:");
}

/* A key above every header: the message says so and names the section the
 * key belongs to, not "unknown section []". */
Test(scene, key_before_any_section)
{
    EXPECT_LIB("h = 0.04\n" BASE2, SPH_ERR_UNKNOWN_SECTION, "x.ini:1", "'h' comes before any [section] header",
               "[kernels]");
    EXPECT_LIB("stiffness = 100\n" BASE2, SPH_ERR_UNKNOWN_SECTION, "x.ini:1", "[physics]");
}

Test(scene, unknown_key)
{
    EXPECT_LIB(BASE2 "[physics]\nbogus = 1\n", SPH_ERR_UNKNOWN_KEY, "x.ini:11", "bogus", "[physics]",
               "accepted:", "stiffness");
    EXPECT_LIB(BASE2 "[fluid b]\nsize = 1\n", SPH_ERR_UNKNOWN_KEY, "x.ini:11", "size", "accepted:", "spacing");
}

Test(scene, values_that_do_not_parse)
{
    EXPECT_LIB(BASE2 "[kernels]\nh = abc\n", SPH_ERR_PARSE, "x.ini:11", "h = 'abc'", "not a number",
               "accepted: from 0.0001");
    EXPECT_LIB(BASE2 "[kernels]\nh = 0.04x\n", SPH_ERR_PARSE, "x.ini:11", "h", "accepted:");
    EXPECT_LIB(BASE2 "[kernels]\nh =\n", SPH_ERR_PARSE, "x.ini:11", "h", "accepted:");
    EXPECT_LIB(BASE2 "[kernels]\nh = 0,04\n", SPH_ERR_PARSE, "x.ini:11", "h", "accepted:");
    EXPECT_LIB("[scene]\ndimension = 2.5\n", SPH_ERR_PARSE, "x.ini:2", "dimension", "whole number",
               "accepted: from 2 and up to 3");
    EXPECT_LIB(BASE2 "[physics]\ngravity = 0 -9.8a\n", SPH_ERR_PARSE, "x.ini:11", "gravity",
               "accepted: 2 or 3 numbers");
    EXPECT_LIB(BASE2 "[physics]\ngravity = x y\n", SPH_ERR_PARSE, "x.ini:11", "gravity", "accepted: 2 or 3 numbers");
    EXPECT_LIB(BASE2 "[physics]\ngravity = -9.81\n", SPH_ERR_PARSE, "x.ini:11", "gravity",
               "accepted: 2 or 3 numbers");
    EXPECT_LIB(BASE2 "[physics]\ngravity = 0 -9.81 0 1\n", SPH_ERR_PARSE, "x.ini:11", "gravity",
               "accepted: 2 or 3 numbers");
    EXPECT_LIB(BASE2 "[physics]\neos = Tait\n", SPH_ERR_PARSE, "x.ini:11", "eos", "accepted: one of: linear, tait");
    EXPECT_LIB(BASE2 "[scene]\neffects = gravity bogus\n", SPH_ERR_PARSE, "x.ini:11", "effects", "accepted:",
               "viscosity");
    EXPECT_LIB(BASE2 "[kernels]\ndensity = gauss\n", SPH_ERR_PARSE, "x.ini:11", "density", "accepted:", "poly6");
}

Test(scene, values_out_of_range)
{
    EXPECT_LIB(BASE2 "[kernels]\nh = 0\n", SPH_ERR_RANGE, "x.ini:11", "h = '0'", "accepted: from 0.0001");
    EXPECT_LIB(BASE2 "[kernels]\nh = -1\n", SPH_ERR_RANGE, "x.ini:11", "h = '-1'", "accepted: from 0.0001");
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\nspacing = 0\n", SPH_ERR_RANGE, "x.ini:13",
               "spacing", "accepted: above 0");
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\nspacing = -0.01\n", SPH_ERR_RANGE, "x.ini:13",
               "spacing", "accepted: above 0");
    EXPECT_LIB("[scene]\ndimension = 4\n", SPH_ERR_RANGE, "x.ini:2", "dimension", "accepted: from 2 and up to 3");
    EXPECT_LIB("[scene]\ndimension = 1\n", SPH_ERR_RANGE, "x.ini:2", "dimension", "accepted: from 2 and up to 3");
    EXPECT_LIB(BASE2 "[physics]\nstiffness = -5\n", SPH_ERR_RANGE, "x.ini:11", "stiffness", "accepted: above 0");
    EXPECT_LIB(BASE2 "[physics]\nstiffness = 0\n", SPH_ERR_RANGE, "x.ini:11", "stiffness", "accepted: above 0");
    EXPECT_LIB(BASE2 "[domain]\nwall_damping = 2\n", SPH_ERR_RANGE, "x.ini:11", "wall_damping",
               "accepted: from 0 and up to 1");
    EXPECT_LIB(BASE2 "[domain]\nwall_damping = -0.1\n", SPH_ERR_RANGE, "x.ini:11", "wall_damping",
               "accepted: from 0 and up to 1");
    EXPECT_LIB(BASE2 "[scene]\njitter = 0.6\n", SPH_ERR_RANGE, "x.ini:11", "jitter", "accepted:");
    EXPECT_LIB(BASE2 "[scene]\nsteps = 0\n", SPH_ERR_RANGE, "x.ini:11", "steps", "accepted:");
    EXPECT_LIB(BASE2 "[physics]\ngravity = 0 -1e5\n", SPH_ERR_RANGE, "x.ini:11", "gravity", "accepted:");
    EXPECT_LIB(BASE2 "[time]\ncfl = 1.5\n", SPH_ERR_RANGE, "x.ini:11", "cfl", "accepted:");
}

/* NaN, infinities and overflowing numbers are never accepted, whatever the key's type. */
Test(scene, non_finite_values_are_refused)
{
    const char *bad[] = {"nan", "NaN", "-nan", "inf", "-inf", "infinity", "1e400", "-1e400"};
    const struct {
        const char *section, *key, *fmt;
    } keys[] = {
        {"kernels", "h", "%s"},           {"physics", "stiffness", "%s"}, {"physics", "viscosity", "%s"},
        {"domain", "wall_damping", "%s"}, {"time", "dt", "%s"},           {"scene", "steps", "%s"},
        {"scene", "seed", "%s"},          {"physics", "gravity", "0 %s"}, {"fluid c", "min", "%s 0"},
    };
    for (size_t k = 0; k < sizeof keys / sizeof keys[0]; k++)
        for (size_t b = 0; b < sizeof bad / sizeof bad[0]; b++) {
            char value[64], text[512];
            snprintf(value, sizeof value, keys[k].fmt, bad[b]);
            snprintf(text, sizeof text, BASE2 "[%s]\n%s = %s\n", keys[k].section, keys[k].key, value);
            EXPECT_LIB2(text, SPH_ERR_RANGE, SPH_ERR_PARSE, "x.ini:11", keys[k].key, "accepted:");
        }
    /* the same in a fluid block */
    EXPECT_LIB2(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\nspacing = nan\n", SPH_ERR_RANGE, SPH_ERR_PARSE,
                "x.ini:13", "spacing", "accepted:");
    EXPECT_LIB2(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\nvelocity = 0 inf\n", SPH_ERR_RANGE, SPH_ERR_PARSE,
                "x.ini:13", "velocity", "accepted:");
}

/* A number that is above 0 as a double but 0 as the float it is stored in
 * (h = 1e-310, dt = 1e-50) breaks the range the message promises: h = 0
 * makes NaN positions, dt = 0 never reaches the scene's duration. */
Test(scene, values_that_underflow_the_stored_float_are_refused)
{
    EXPECT_LIB(BASE2 "[kernels]\nh = 1e-310\n", SPH_ERR_RANGE, "x.ini:11", "h", "accepted: from 0.0001");
    EXPECT_LIB(BASE2 "[physics]\nstiffness = 1e-50\n", SPH_ERR_RANGE, "x.ini:11", "stiffness", "accepted: above 0");
    EXPECT_LIB(BASE2 "[time]\ndt = 1e-50\n", SPH_ERR_RANGE, "x.ini:11", "dt", "accepted: above 0");
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\nspacing = 1e-60\n", SPH_ERR_RANGE, "x.ini:13",
               "spacing", "accepted: above 0");
}

Test(scene, block_outside_the_domain)
{
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 1.5 0.8\n", SPH_ERR_SCENE, "x.ini:10", "fluid b",
               "outside the domain", "0 to 1");
    EXPECT_LIB(BASE2 "[fluid b]\nmin = -0.1 0.5\nmax = 0.5 0.8\n", SPH_ERR_SCENE, "x.ini:10", "fluid b",
               "outside the domain");
    EXPECT_LIB(BASE3 "[fluid b]\nmin = 0.5 0.5 0.5\nmax = 0.7 0.7 1.2\n", SPH_ERR_SCENE, "x.ini:10", "fluid b",
               "outside the domain");
}

Test(scene, initial_pressure_hydrostatic_needs_gravity_without_a_ramp)
{
    sph_scene_def def;
    sph_error err;
    cr_assert_eq(lib_load(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\ninitial_pressure = hydrostatic\n", &def, &err),
                 SPH_ERR_OK, "%s", err.msg);
    cr_assert_eq(def.blocks[1].initial_pressure, SPH_INITP_HYDROSTATIC);
    cr_assert_eq(def.blocks[0].initial_pressure, SPH_INITP_NONE, "the default");
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\ninitial_pressure = hydrostatic\n[physics]\n"
                     "gravity_ramp = 0.3\n",
               SPH_ERR_SCENE, "x.ini:13", "fluid b", "initial_pressure = hydrostatic", "gravity_ramp = 0.3 (at x.ini:15)");
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\ninitial_pressure = hydrostatic\n[physics]\n"
                     "gravity = 0 0\n",
               SPH_ERR_SCENE, "x.ini:13", "fluid b", "no gravity");
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\ninitial_pressure = lithostatic\n", SPH_ERR_PARSE,
               "x.ini:13", "initial_pressure", "hydrostatic");
}

Test(scene, block_thinner_than_one_spacing_has_no_particles)
{
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.51 0.8\n", SPH_ERR_SCENE, "x.ini:10", "fluid b",
               "no particles", "spacing");
    EXPECT_LIB(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.5 0.8\n", SPH_ERR_SCENE, "x.ini:10", "fluid b");
}

Test(scene, no_fluid_block_means_no_particles)
{
    EXPECT_LIB("[scene]\ndimension = 2\n[domain]\nmax = 1 1\n", SPH_ERR_SCENE, "x.ini", "no particles",
               "[fluid NAME]");
    EXPECT_LIB("; only a comment\n", SPH_ERR_SCENE, "x.ini", "no particles");
}

Test(scene, more_particles_than_memory_allows)
{
    const char *text = "[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n"
                       "[fluid a]\nmin = 0 0 0\nmax = 1 1 1\nspacing = 1e-6\n";
    EXPECT_LIB(text, SPH_ERR_MEMORY, "x.ini:9: [fluid a] spacing = 1e-06 m", "memory");
    /* the binary refuses it at once, before allocating anything */
    char path[256], out[4096];
    snprintf(path, sizeof path, "%s", test_write_temp(text, ".ini"));
    /* a refusal, not an attempt: killed (exit 137) only if it hangs, a bound no busy machine comes near */
    int rc = sphlab_timed(120, out, sizeof out, "run %s --steps 1 --quiet", path);
    cr_expect_eq(rc, 5, "exit %d (5: does not fit in memory):\n%s", rc, out);
    cr_expect(strstr(out, path) && strstr(out, "memory"), "message: %s", out);
    remove(path);
}

Test(scene, two_component_vector_in_a_3d_scene)
{
    EXPECT_LIB("[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n[fluid a]\nmin = 0 0\n"
               "max = 0.2 0.2 0.2\n",
               SPH_ERR_RANGE, "x.ini:7", "min", "3D", "accepted: 3 numbers");
    EXPECT_LIB(BASE3 "[physics]\ngravity = 0 -9.81\n", SPH_ERR_RANGE, "x.ini:11", "gravity", "accepted: 3 numbers");
    EXPECT_LIB("[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 1 1\n[fluid a]\nmax = 0.2 0.2 0.2\n",
               SPH_ERR_RANGE, "x.ini:5", "max", "accepted: 3 numbers");
    /* a 2D scene takes 3 numbers and ignores z */
    expect_ok(BASE2 "[physics]\ngravity = 0 -9.81 5\n");
}

Test(scene, duplicate_key_names_both_lines)
{
    EXPECT_LIB(BASE2 "[kernels]\nh = 0.04\nh = 0.05\n", SPH_ERR_DUPLICATE_KEY, "x.ini:12", "line 11", "'h'");
    /* the same section twice counts as one */
    EXPECT_LIB(BASE2 "[kernels]\nh = 0.04\n[kernels]\nh = 0.05\n", SPH_ERR_DUPLICATE_KEY, "x.ini:13", "line 11",
               "'h'");
    /* in a fluid block */
    EXPECT_LIB(BASE2 "spacing = 0.01\n", SPH_ERR_DUPLICATE_KEY, "x.ini:10", "line 9", "spacing");
}

/* Two [fluid a] sections are one mistake however their keys fall: the second
 * header must be refused, naming both headers' lines (6 and 10). */
Test(scene, two_fluid_sections_with_the_same_name)
{
    sph_error err;
    /* same keys: caught at the first repeated key at least */
    sph_error_code c = lib_load(BASE2 "[fluid a]\nmin = 0.3 0.3\nmax = 0.5 0.5\n", NULL, &err);
    cr_expect_neq(c, SPH_ERR_OK, "two [fluid a] sections accepted");
    if (c) cr_expect(strstr(err.msg, "fluid a") != NULL, "message: %s", err.msg);
    /* different keys: the second section would silently merge into the first */
    c = lib_load(BASE2 "[fluid a]\nvelocity = 1 0\n", NULL, &err);
    cr_expect(c == SPH_ERR_DUPLICATE_KEY || c == SPH_ERR_SCENE,
              "[fluid a] twice (disjoint keys): got %s (%s)", sph_error_name(c), c ? err.msg : "accepted");
    if (c) {
        cr_expect(strstr(err.msg, "x.ini:10") != NULL, "should name the second header, line 10: %s", err.msg);
        cr_expect(strstr(err.msg, "line 6") != NULL, "should name the first header, line 6: %s", err.msg);
        cr_expect(strstr(err.msg, "fluid a") != NULL, "message: %s", err.msg);
    }
}

Test(scene, empty_file)
{
    EXPECT_LIB("", SPH_ERR_SCENE, "x.ini", "empty");
    EXPECT_LIB("\n  \n\t\n", SPH_ERR_SCENE, "x.ini", "empty");
}

Test(scene, binary_garbage)
{
    /* bytes without a NUL are still not a scene */
    EXPECT_LIB2("\xff\xfe\x01\x02garbage\x80\n", SPH_ERR_SYNTAX, SPH_ERR_UNKNOWN_SECTION, "x.ini:1");
    EXPECT_LIB2(BASE2 "\xff\xfe\x01\x02\n", SPH_ERR_SYNTAX, SPH_ERR_UNKNOWN_SECTION, "x.ini:10");
    /* a NUL byte: only a file can hold one */
    const unsigned char bytes[] = {'[', 's', 'c', 'e', 'n', 'e', ']', '\n', 0x00, 0xff, 0xfe, 'x', 0x00, '\n', 0xff};
    char path[256];
    write_binary(path, sizeof path, bytes, sizeof bytes);
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    sph_error_code c = sph_scene_load(path, &def, &err);
    cr_expect_eq(c, SPH_ERR_SYNTAX, "got %s: %s", sph_error_name(c), err.msg);
    char loc[300];
    snprintf(loc, sizeof loc, "%s:2:", path);
    cr_expect(strstr(err.msg, loc) != NULL, "should name %s: %s", loc, err.msg);
    expect_cli_path(path, 2, NULL, "NUL and 0xff bytes");
    remove(path);
}

Test(scene, line_too_long)
{
    char text[1024], comment[251], value[251];
    memset(comment, 'x', 250);
    comment[250] = '\0';
    memset(value, 'n', 250);
    value[250] = '\0';
    snprintf(text, sizeof text, BASE2 ";%s\n", comment);
    EXPECT_LIB(text, SPH_ERR_SYNTAX, "x.ini:10", "longer than");
    snprintf(text, sizeof text, BASE2 ";%s", comment); /* at the end, without a newline */
    EXPECT_LIB(text, SPH_ERR_SYNTAX, "x.ini:10", "longer than");
    snprintf(text, sizeof text, BASE2 "[scene]\nname = %s\n", value);
    EXPECT_LIB(text, SPH_ERR_SYNTAX, "x.ini:11", "longer than");
    snprintf(text, sizeof text, BASE2 "[scene]\nname = %s\n", value);
    expect_cli(text, 11, "longer than");
}

Test(scene, missing_file_and_directory)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    sph_error_code c = sph_scene_load("/nonexistent-dir/none.ini", &def, &err);
    cr_expect_eq(c, SPH_ERR_IO, "got %s", sph_error_name(c));
    cr_expect(strstr(err.msg, "/nonexistent-dir/none.ini") != NULL, "message: %s", err.msg);
    c = sph_scene_load("/tmp", &def, &err);
    cr_expect_eq(c, SPH_ERR_IO, "got %s", sph_error_name(c));
    cr_expect(strstr(err.msg, "/tmp") != NULL, "message: %s", err.msg);
    expect_cli_path("/nonexistent-dir/none.ini", 0, NULL, "missing file");
    expect_cli_path("/tmp", 0, NULL, "a directory");
}

Test(scene, syntax_errors)
{
    EXPECT_LIB(BASE2 "this is not ini\n", SPH_ERR_SYNTAX, "x.ini:10", "syntax");
    EXPECT_LIB(BASE2 "[kernels]\nh 0.04\n", SPH_ERR_SYNTAX, "x.ini:11");
}

/* An unclosed section header is the error, not the key after it (which
 * inih goes on to apply to the previous section). */
Test(scene, unclosed_section_header)
{
    EXPECT_LIB(BASE2 "[kernels\nh = 0.04\n", SPH_ERR_SYNTAX, "x.ini:10");
}

/* inih goes on after a syntax error: the first error in the file must be the one reported. */
Test(scene, first_error_in_the_file_is_reported)
{
    EXPECT_LIB(BASE2 "this is not ini\n[kernels]\nh = abc\n", SPH_ERR_SYNTAX, "x.ini:10");
}

/* Indented keys are common in INI files. libinih takes an indented line after
 * a key as a continuation of that key's value, which here reads as
 * "duplicate key 'min'": the scene must load as if it were not indented. */
Test(scene, indented_keys_load)
{
    expect_ok("[scene]\n  dimension = 2\n[domain]\n  max = 1 1\n[fluid a]\n  min = 0 0\n  max = 0.2 0.2\n"
              "  spacing = 0.02\n");
}

/* ---- --set overrides ----------------------------------------------------- */

static sph_error_code lib_set(const char *text, const char *assignment, sph_scene_def *def, sph_error *err)
{
    *def = sph_default_scene_def();
    memset(err, 0, sizeof *err);
    sph_error_code c = sph_scene_load_string(text, "x.ini", def, err);
    cr_assert_eq(c, SPH_ERR_OK, "base scene: %s", err->msg);
    c = sph_scene_set(def, assignment, err);
    if (c == SPH_ERR_OK) c = sph_scene_validate(def, err);
    return c;
}

static void expect_set(const char *text, const char *assignment, sph_error_code want, const char *const *needles)
{
    sph_scene_def def;
    sph_error err;
    sph_error_code c = lib_set(text, assignment, &def, &err);
    cr_expect_eq(c, want, "--set %s: want %s, got %s (%s)", assignment, sph_error_name(want), sph_error_name(c),
                 c ? err.msg : "accepted");
    if (c) expect_msg(err.msg, needles, assignment);
}
#define EXPECT_SET(text, assignment, code, ...) \
    expect_set(text, assignment, code, (const char *const[]){__VA_ARGS__, NULL})

Test(scene, set_errors)
{
    EXPECT_SET(BASE2, "kernels.h=-1", SPH_ERR_RANGE, "--set", "h", "'-1'", "accepted: from 0.0001");
    EXPECT_SET(BASE2, "kernels.h=nan", SPH_ERR_RANGE, "--set", "h", "accepted: from 0.0001");
    EXPECT_SET(BASE2, "nosuch.key=1", SPH_ERR_UNKNOWN_SECTION, "--set", "nosuch", "accepted:");
    EXPECT_SET(BASE2, "physics.nosuch=1", SPH_ERR_UNKNOWN_KEY, "--set", "nosuch", "accepted:", "stiffness");
    EXPECT_SET(BASE2, "garbage", SPH_ERR_USAGE, "garbage", "section.key=value");
    EXPECT_SET(BASE2, "kernels=1", SPH_ERR_USAGE, "section.key=value");
    EXPECT_SET(BASE2, "fluid.a.spacing=0", SPH_ERR_RANGE, "--set", "spacing", "accepted: above 0");
}

/* The block is wrong, but the message should still say which key was being set. */
Test(scene, set_unknown_fluid_block_names_block_and_key)
{
    EXPECT_SET(BASE2, "fluid.nosuchblock.spacing=0.1", SPH_ERR_SCENE, "--set", "nosuchblock", "spacing");
}

/* A 2-component vector from --set in a 3D scene comes from the command line,
 * not from line -1 of the file. */
Test(scene, set_two_component_vector_in_3d_names_the_option)
{
    sph_scene_def def;
    sph_error err;
    sph_error_code c = lib_set(BASE3, "physics.gravity=0 -9.81", &def, &err);
    cr_expect_eq(c, SPH_ERR_RANGE, "got %s (%s)", sph_error_name(c), err.msg);
    cr_expect(strstr(err.msg, "--set") != NULL && strstr(err.msg, ":-1:") == NULL,
              "should name --set, not line -1: %s", err.msg);
    cr_expect(strstr(err.msg, "gravity") != NULL, "message: %s", err.msg);
}

Test(scene, set_applies_to_every_block_or_one)
{
    const char *two = BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\n";
    sph_scene_def def;
    sph_error err;
    cr_assert_eq(lib_set(two, "fluid.spacing=0.05", &def, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_float_eq(def.blocks[0].spacing, 0.05f, 1e-7f);
    cr_expect_float_eq(def.blocks[1].spacing, 0.05f, 1e-7f);
    cr_assert_eq(lib_set(two, "fluid.b.spacing=0.05", &def, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_float_eq(def.blocks[0].spacing, 0.02f, 1e-7f);
    cr_expect_float_eq(def.blocks[1].spacing, 0.05f, 1e-7f);
    /* --set may override a key the file set */
    cr_assert_eq(lib_set(BASE2 "[kernels]\nh = 0.04\n", "kernels.h=0.05", &def, &err), SPH_ERR_OK, "%s", err.msg);
    cr_expect_float_eq(def.h, 0.05f, 1e-7f);
}

/* A --set that breaks a cross-check (domain) is refused by validation. */
Test(scene, set_that_moves_a_block_out_is_refused)
{
    EXPECT_SET(BASE2, "domain.max=0.1 1", SPH_ERR_SCENE, "fluid a", "outside the domain");
}

/* The domain check names the line of the key that is wrong when the other is a default. */
Test(scene, domain_min_above_default_max_names_a_real_line)
{
    sph_error err;
    sph_error_code c = lib_load("[scene]\ndimension = 2\n[domain]\nmin = 2 2\n[fluid a]\nmin = 2.1 2.1\n"
                                "max = 2.3 2.3\n",
                                NULL, &err);
    cr_expect_neq(c, SPH_ERR_OK);
    cr_expect(strstr(err.msg, "x.ini:0:") == NULL, "line 0 does not exist: %s", err.msg);
    cr_expect(strstr(err.msg, "x.ini:4") != NULL, "should name [domain] min, line 4: %s", err.msg);
}

/* ---- the binary ---------------------------------------------------------- */

Test(scene, cli_scene_errors)
{
    expect_cli(BASE2 "[foo]\nx = 1\n", 10, "foo");
    expect_cli(BASE2 "[physics]\nbogus = 1\n", 11, "bogus");
    expect_cli(BASE2 "[kernels]\nh = abc\n", 11, "h = 'abc'");
    expect_cli("[scene]\ndimension = 2.5\n", 2, "dimension");
    expect_cli(BASE2 "[physics]\ngravity = 0 -9.8a\n", 11, "gravity");
    expect_cli(BASE2 "[physics]\ngravity = 1\n", 11, "gravity");
    expect_cli(BASE2 "[physics]\ngravity = 1 2 3 4\n", 11, "gravity");
    expect_cli(BASE2 "[kernels]\nh = 0\n", 11, "accepted: from 0.0001");
    expect_cli(BASE2 "[kernels]\nh = -1\n", 11, "h = '-1'");
    expect_cli(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.7 0.7\nspacing = 0\n", 13, "spacing");
    expect_cli("[scene]\ndimension = 4\n", 2, "dimension");
    expect_cli("[scene]\ndimension = 1\n", 2, "dimension");
    expect_cli(BASE2 "[physics]\nstiffness = -1\n", 11, "stiffness");
    expect_cli(BASE2 "[domain]\nwall_damping = 2\n", 11, "wall_damping");
    expect_cli(BASE2 "[kernels]\nh = nan\n", 11, "h = 'nan'");
    expect_cli(BASE2 "[kernels]\nh = NaN\n", 11, "h = 'NaN'");
    expect_cli(BASE2 "[kernels]\nh = inf\n", 11, "h = 'inf'");
    expect_cli(BASE2 "[kernels]\nh = 1e400\n", 11, "h = '1e400'");
    expect_cli(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 1.5 0.8\n", 10, "fluid b");
    expect_cli(BASE2 "[fluid b]\nmin = 0.5 0.5\nmax = 0.51 0.8\n", 10, "no particles");
    expect_cli("[scene]\ndimension = 2\n", 0, "no particles");
    expect_cli("[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n[fluid a]\nmin = 0 0\n"
               "max = 0.2 0.2 0.2\n",
               7, "min");
    expect_cli(BASE2 "[kernels]\nh = 0.04\nh = 0.05\n", 12, "line 11");
    expect_cli("", 0, "empty");
    expect_cli(BASE2 "this is not ini\n", 10, "syntax");
}

/* dt = 1e-50 is stored as 0: a run to the scene's duration would never end. */
Test(scene, cli_underflowing_dt_is_refused_not_run_forever)
{
    char path[256], out[4096];
    snprintf(path, sizeof path, "%s", test_write_temp(BASE2 "[time]\ndt = 1e-50\n[scene]\nduration = 0.01\n", ".ini"));
    int rc = sphlab_timed(10, out, sizeof out, "run %s --quiet", path);
    cr_expect_eq(rc, 1, "exit %d (137: killed after 10 s):\n%s", rc, out);
    cr_expect(strstr(out, "dt") != NULL, "message: %s", out);
    remove(path);
}

/* A --set whose key or value is refused is a bad command line: exit 2, as `bench` and `--backend vulkan` have
 * it (run and check said 1, the bench 2, for the same --set). A --set that parses but breaks a cross-check of the
 * scene (a block moved out of the domain) is refused by validation, exit 1. */
Test(scene, cli_set_errors)
{
    char path[256], out[4096];
    snprintf(path, sizeof path, "%s", test_write_temp(BASE2, ".ini"));
    const struct {
        const char *set, *needle;
    } cases[] = {
        {"kernels.h=-1", "accepted: from 0.0001"},
        {"nosuch.key=1", "nosuch"},
        {"physics.bogus=1", "bogus"},
        {"fluid.nosuchblock.spacing=0.1", "nosuchblock"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++)
        for (int cmd = 0; cmd < 2; cmd++) {
            int rc = sphlab_timed(30, out, sizeof out, "%s %s --set '%s'%s", cmd ? "check" : "run", path,
                                  cases[i].set, cmd ? "" : " --steps 1 --quiet");
            cr_expect_eq(rc, 2, "%s --set %s: exit %d:\n%s", cmd ? "check" : "run", cases[i].set, rc, out);
            cr_expect(strstr(out, "--set") && strstr(out, cases[i].needle), "--set %s: message: %s", cases[i].set,
                      out);
        }
    remove(path);
}

/* A --set that is not section.key=value at all is a command-line usage error: exit 2, like --steps abc. */
Test(scene, cli_set_without_equals_is_a_usage_error)
{
    char path[256], out[4096];
    snprintf(path, sizeof path, "%s", test_write_temp(BASE2, ".ini"));
    int rc = sphlab_timed(30, out, sizeof out, "run %s --steps 1 --quiet --set garbage", path);
    cr_expect_eq(rc, 2, "run --set garbage: exit %d:\n%s", rc, out);
    cr_expect(strstr(out, "garbage") && strstr(out, "section.key=value"), "message: %s", out);
    rc = sphlab_timed(30, out, sizeof out, "check %s --set garbage", path);
    cr_expect_eq(rc, 2, "check --set garbage: exit %d:\n%s", rc, out);
    remove(path);
}

Test(scene, cli_command_line_errors)
{
    char path[256], out[4096];
    snprintf(path, sizeof path, "%s", test_write_temp(BASE2, ".ini"));
    const struct {
        const char *args, *needle;
    } cases[] = {
        {"run %s --bogus", "--bogus"},          {"run %s --steps abc", "--steps"},
        {"run %s --steps -1", "--steps"},       {"run %s --steps 1.5", "--steps"},
        {"run %s --threads 0", "--threads"},    {"run %s --threads abc", "--threads"},
        {"run %s --time nan", "--time"},        {"run %s --time inf", "--time"},
        {"run %s --time -1", "--time"},         {"run %s --steps 1 --time 1", "--time"},
        {"run %s --steps", "--steps"},          {"run %s %s", "more than one"},
        {"check %s --bogus", "--bogus"},        {"check %s --set", "--set"},
        {"bogus %s", "bogus"},
    };
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        char args[512];
        snprintf(args, sizeof args, cases[i].args, path, path);
        int rc = sphlab_timed(30, out, sizeof out, "%s", args);
        cr_expect_eq(rc, 2, "%s: exit %d, want 2:\n%s", args, rc, out);
        cr_expect(strstr(out, cases[i].needle) != NULL, "%s: message lacks '%s': %s", args, cases[i].needle, out);
    }
    remove(path);
}

static bool dir_has_tmp(const char *dir, char *found, size_t cap)
{
    DIR *d = opendir(dir);
    if (!d) return false;
    bool any = false;
    for (struct dirent *e; (e = readdir(d));) {
        size_t n = strlen(e->d_name);
        if (n >= 4 && strcmp(e->d_name + n - 4, ".tmp") == 0) {
            snprintf(found, cap, "%s", e->d_name);
            any = true;
        }
    }
    closedir(d);
    return any;
}

static int count_lines(const char *path)
{
    FILE *f = fopen(path, "r");
    if (!f) return -1;
    int n = 0;
    for (int ch; (ch = fgetc(f)) != EOF;) n += ch == '\n';
    fclose(f);
    return n;
}

static void remove_dir(const char *dir)
{
    DIR *d = opendir(dir);
    if (!d) return;
    char p[512];
    for (struct dirent *e; (e = readdir(d));) {
        if (strcmp(e->d_name, ".") == 0 || strcmp(e->d_name, "..") == 0) continue;
        snprintf(p, sizeof p, "%s/%s", dir, e->d_name);
        remove(p);
    }
    closedir(d);
    rmdir(dir);
}

Test(scene, cli_unwritable_output_fails_before_simulating)
{
    char dir[] = "/tmp/sphlab-test-out-XXXXXX", scene[300], stats[300], out[4096], found[256], bad[320];
    cr_assert(mkdtemp(dir) != NULL);
    snprintf(scene, sizeof scene, "%s/s.ini", dir);
    FILE *f = fopen(scene, "w");
    cr_assert(f);
    fputs(BASE2, f);
    fclose(f);
    snprintf(stats, sizeof stats, "%s/stats.csv", dir);
    /* a folder that cannot be made, even as root (a missing one is made: the output folders' rule): below a file */
    snprintf(bad, sizeof bad, "%s/afile/x.csv", dir);
    char afile[310];
    snprintf(afile, sizeof afile, "%s/afile", dir);
    f = fopen(afile, "w");
    cr_assert(f);
    fclose(f);
    /* 2e9 steps: only a refusal before the run ends in time */
    int rc = sphlab_timed(20, out, sizeof out, "run %s --steps 2000000000 --quiet --stats %s", scene, bad);
    cr_expect_eq(rc, 1, "--stats %s: exit %d:\n%s", bad, rc, out);
    cr_expect(strstr(out, "afile") != NULL, "message: %s", out);
    cr_expect(!exists(bad));
    rc = sphlab_timed(20, out, sizeof out, "run %s --steps 2000000000 --quiet --stats %s --dump %s", scene, stats, bad);
    cr_expect_eq(rc, 1, "--dump %s: exit %d:\n%s", bad, rc, out);
    cr_expect(!exists(stats), "the --stats file of a refused run was left behind");
    cr_expect(!dir_has_tmp(dir, found, sizeof found), "left %s", found);
    /* a folder made for an output of a refused run is taken back */
    char made[330];
    snprintf(made, sizeof made, "%s/new/stats.csv", dir);
    rc = sphlab_timed(20, out, sizeof out, "run %s --steps 2000000000 --quiet --stats %s --dump %s", scene, made, bad);
    snprintf(made, sizeof made, "%s/new", dir);
    cr_expect(rc == 1 && !exists(made), "exit %d; the folder made for --stats of a refused run was left: %s", rc, out);
    remove(afile);
    remove_dir(dir);
}

/* A directory given as the output cannot be written either: refused before the run, not after it. */
Test(scene, cli_directory_as_output_fails_before_simulating)
{
    char dir[] = "/tmp/sphlab-test-out-XXXXXX", scene[300], out[4096], found[256];
    cr_assert(mkdtemp(dir) != NULL);
    snprintf(scene, sizeof scene, "%s/s.ini", dir);
    FILE *f = fopen(scene, "w");
    cr_assert(f);
    fputs(BASE2, f);
    fclose(f);
    int rc = sphlab_timed(10, out, sizeof out, "run %s --steps 2000000000 --quiet --stats %s", scene, dir);
    cr_expect_eq(rc, 1, "--stats DIRECTORY: exit %d (137: it simulated until killed):\n%s", rc, out);
    char parent_tmp[320];
    snprintf(parent_tmp, sizeof parent_tmp, "%s.tmp", dir);
    cr_expect(!exists(parent_tmp), "left %s", parent_tmp);
    remove(parent_tmp);
    cr_expect(!dir_has_tmp(dir, found, sizeof found), "left %s", found);
    remove_dir(dir);
}

Test(scene, cli_outputs_on_success)
{
    char dir[] = "/tmp/sphlab-test-out-XXXXXX", scene[300], stats[300], dump[300], out[8192], found[256];
    cr_assert(mkdtemp(dir) != NULL);
    snprintf(scene, sizeof scene, "%s/s.ini", dir);
    snprintf(stats, sizeof stats, "%s/stats.csv", dir);
    snprintf(dump, sizeof dump, "%s/dump.csv", dir);
    FILE *f = fopen(scene, "w");
    cr_assert(f);
    fputs(BASE2, f);
    fclose(f);
    int rc = sphlab_timed(30, out, sizeof out, "run %s --steps 3 --quiet --stats %s --dump %s", scene, stats, dump);
    cr_expect_eq(rc, 0, "exit %d:\n%s", rc, out);
    cr_expect_eq(count_lines(stats), 4, "stats: header + 3 rows, got %d lines", count_lines(stats));
    cr_expect_eq(count_lines(dump), 101, "dump: header + 100 particles, got %d lines", count_lines(dump));
    cr_expect(!dir_has_tmp(dir, found, sizeof found), "left %s", found);
    remove_dir(dir);
}

/* ---- shipped scenes and the documentation --------------------------------- */

static char *read_all(const char *path)
{
    FILE *f = fopen(path, "rb");
    if (!f) return NULL;
    fseek(f, 0, SEEK_END);
    long n = ftell(f);
    fseek(f, 0, SEEK_SET);
    char *s = malloc((size_t)n + 1);
    cr_assert(s);
    size_t got = fread(s, 1, (size_t)n, f);
    s[got] = '\0';
    fclose(f);
    return s;
}

Test(scene, shipped_scenes_load_and_stay_small)
{
    const char *want[] = {"dam-break-2d.ini", "dam-break-3d.ini", "drop-2d.ini",
                          "drop-3d.ini",      "rest-2d.ini",      "rest-3d.ini"};
    for (size_t i = 0; i < sizeof want / sizeof want[0]; i++) {
        char path[256];
        snprintf(path, sizeof path, "lessons/scenes/%s", want[i]);
        cr_expect(exists(path), "%s is missing (run the suite from the repository root)", path);
    }
    DIR *d = opendir("lessons/scenes");
    cr_assert(d, "lessons/scenes: run the suite from the repository root");
    int n = 0;
    for (struct dirent *e; (e = readdir(d));) {
        size_t len = strlen(e->d_name);
        if (len < 5 || strcmp(e->d_name + len - 4, ".ini") != 0) continue;
        char path[512];
        snprintf(path, sizeof path, "lessons/scenes/%s", e->d_name);
        n++;
        char *text = read_all(path);
        cr_assert(text, "cannot read %s", path);
        cr_expect(text[0] == ';' || text[0] == '#', "%s: should open with a comment saying what it shows", path);
        free(text);
        sph_scene_def def = sph_default_scene_def();
        sph_error err;
        sph_error_code c = sph_scene_load(path, &def, &err);
        if (c == SPH_ERR_OK) c = sph_scene_validate(&def, &err);
        cr_expect_eq(c, SPH_ERR_OK, "%s: %s", path, err.msg);
        if (c) continue;
        double count = sph_scene_particle_count(&def);
        cr_expect(count <= (def.dim == 2 ? 10000 : 8000), "%s: %.0f particles, too many for a quick lesson", path,
                  count);
    }
    closedir(d);
    cr_expect_geq(n, 6);
}

/* The section heading of `section` in the doc, e.g. "### [physics]" or "### [fluid NAME]". */
static const char *doc_section(const char *doc, const char *section)
{
    char heading[64];
    snprintf(heading, sizeof heading, "\n### [%s", section);
    const char *p = strstr(doc, heading);
    if (!p) return NULL;
    char after = p[strlen(heading)];
    return after == ']' || after == ' ' ? p + 1 : NULL;
}

Test(scene, every_key_is_documented)
{
    char *doc = read_all("docs/scene-format.md");
    cr_assert(doc, "docs/scene-format.md: cannot read it (run the suite from the repository root)");
    for (int i = 0; i < sph_scene_key_count; i++) {
        const sph_key *k = &sph_scene_keys[i];
        const char *sec = doc_section(doc, k->section);
        cr_expect(sec, "docs/scene-format.md has no '### [%s]' heading", k->section);
        if (!sec) continue;
        const char *end = strstr(sec, "\n#");
        size_t len = end ? (size_t)(end - sec) : strlen(sec);
        char row[96];
        snprintf(row, sizeof row, "\n| `%s` |", k->name);
        const char *r = NULL;
        for (const char *p = sec; (p = strstr(p, row)) && p < sec + len; p++) {
            r = p;
            break;
        }
        cr_expect(r, "docs/scene-format.md: no row '| `%s` |' under [%s]", k->name, k->section);
        if (!r) continue;
        /* the row states the table's default and unit */
        const char *eol = strchr(r + 1, '\n');
        size_t rl = eol ? (size_t)(eol - r) : strlen(r);
        char line[1024];
        snprintf(line, sizeof line, "%.*s", (int)(rl < sizeof line ? rl : sizeof line - 1), r);
        if (*k->def) cr_expect(strstr(line, k->def), "[%s] %s: the row lacks the default '%s':%s", k->section, k->name,
                               k->def, line);
        if (k->unit && *k->unit)
            cr_expect(strstr(line, k->unit), "[%s] %s: the row lacks the unit '%s':%s", k->section, k->name, k->unit,
                      line);
    }
    for (int e = 0; e < SPH_EFFECT_COUNT; e++) {
        char name[64];
        snprintf(name, sizeof name, "`%s`", sph_effect_names[e]);
        cr_expect(strstr(doc, name), "docs/scene-format.md does not describe the effect %s", name);
    }
    free(doc);
}

/* Every key of a [fluid NAME] or [obstacle NAME] section has an origin slot
 * in its block (sph_block_def.origin, sph_obstacle_def.origin): a key added to
 * the table past SPH_GROUP_KEYS_MAX would be written out of the array. */
Test(scene, group_keys_fit_their_origin_slots)
{
    const char *groups[] = {"fluid", "obstacle"};
    for (int g = 0; g < 2; g++) {
        int n = 0;
        for (int i = 0; i < sph_scene_key_count; i++)
            if (strcmp(sph_scene_keys[i].section, groups[g]) == 0) n++;
        cr_expect_gt(n, 0, "no [%s] key in the table", groups[g]);
        cr_expect_leq(n, SPH_GROUP_KEYS_MAX, "[%s] has %d keys, %d origin slots", groups[g], n, SPH_GROUP_KEYS_MAX);
    }
}

/* A misspelt effect is named with the nearest one; a key under the wrong header names its own section; a misspelt
 * choice gets the nearest choice (a user's review: "gravity presure" named no word, [time] solver_tolerance no
 * section). */
Test(scene, typos_name_the_word_and_the_home)
{
    const struct {
        const char *ini, *want;
    } cases[] = {
        {"[scene]\neffects = gravity presure\n", "unknown effect 'presure' (did you mean 'pressure'?)"},
        {"[time]\nsolver_tolerance = 0.01\n", "unknown key 'solver_tolerance' in [time] (it is a key of [physics])"},
        {"[domain]\nspacing = 0.01\n", "unknown key 'spacing' in [domain] (it is a key of [fluid NAME])"},
        {"[physics]\neos = tate\n",
         "eos = 'tate': unknown choice (did you mean 'tait'?) (accepted: one of: linear, tait)"},
        {"[physics]\neos = zzzz\n", "eos = 'zzzz': unknown choice (accepted: one of: linear, tait)"},
    };
    for (size_t c = 0; c < sizeof cases / sizeof cases[0]; c++) {
        sph_scene_def def = sph_default_scene_def();
        sph_error err;
        cr_assert_neq(sph_scene_load_string(cases[c].ini, "t.ini", &def, &err), SPH_ERR_OK, "%s", cases[c].ini);
        cr_assert(strstr(err.msg, cases[c].want), "want \"%s\" in \"%s\"", cases[c].want, err.msg);
    }
}

/* A key given twice under one block header is a plain duplicate; the hint to name the blocks apart is for a key
 * set again under a second header of the same name (a user's review: the hint came with both). */
Test(scene, duplicate_key_in_a_block_names_the_right_cause)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    cr_assert_neq(sph_scene_load_string("[fluid a]\nspacing = 0.02\nspacing = 0.03\n", "t.ini", &def, &err),
                  SPH_ERR_OK);
    cr_assert(strstr(err.msg, "t.ini:3: duplicate key 'spacing' in [fluid a] (first set on line 2)"), "%s", err.msg);
    cr_assert_null(strstr(err.msg, "its own name"), "%s", err.msg);
}

/* --set obstacle.rock.KEY and fluid.pool.KEY name their blocks as the file does, [obstacle rock] and [fluid pool]
 * (a user's review: "[obstacle.rock]"). */
Test(scene, set_names_blocks_as_the_file_does)
{
    sph_scene_def def = test_scene("[domain]\nmin = 0 0\nmax = 1 1\nwall_model = particles\n[fluid pool]\nmin = 0 0\n"
                                   "max = 0.2 0.2\n[obstacle rock]\nshape = circle\ncentre = 0.5 0.5\nradius = 0.1\n");
    sph_error err;
    cr_assert_neq(sph_scene_set(&def, "obstacle.rock.centre=nan", &err), SPH_ERR_OK);
    cr_assert(strstr(err.msg, "--set: [obstacle rock] centre = 'nan'"), "%s", err.msg);
    cr_assert_neq(sph_scene_set(&def, "fluid.pool.spacing=zz", &err), SPH_ERR_OK);
    cr_assert(strstr(err.msg, "--set: [fluid pool] spacing = 'zz'"), "%s", err.msg);
    cr_assert_eq(sph_scene_set(&def, "fluid.pool.spacing=0.01", &err), SPH_ERR_OK, "%s", err.msg);
    cr_assert_float_eq(def.blocks[0].spacing, 0.01, 1e-9);
}

/* A path that is not a file is named for what it is: /dev/null is no directory (a user's review). */
Test(scene, load_names_what_a_non_file_is)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    cr_assert_neq(sph_scene_load("/tmp", &def, &err), SPH_ERR_OK);
    cr_expect(strstr(err.msg, "/tmp: a directory, not a scene file") != NULL, "%s", err.msg);
    cr_assert_neq(sph_scene_load("/dev/null", &def, &err), SPH_ERR_OK);
    cr_expect(strstr(err.msg, "/dev/null: a device, not a scene file") != NULL, "%s", err.msg);
}

/* --set KEY=VALUE without its section names the sections that have KEY (a user's review). */
Test(scene, set_without_a_section_names_where_the_key_is)
{
    sph_scene_def def = test_scene("[fluid a]\nmin=0 0\nmax=0.2 0.2\nspacing=0.02\n[domain]\nmin=0 0\nmax=1 1\n");
    sph_error err;
    cr_assert_eq(sph_scene_set(&def, "stiffness=400", &err), SPH_ERR_USAGE);
    cr_expect(strstr(err.msg, "did you mean physics.stiffness=400?") != NULL, "%s", err.msg);
    cr_assert_eq(sph_scene_set(&def, "viscosity=0.1", &err), SPH_ERR_USAGE); /* a physics and a kernels key */
    cr_expect(strstr(err.msg, "did you mean physics.viscosity=0.1 or kernels.viscosity=0.1?") != NULL, "%s", err.msg);
    cr_assert_eq(sph_scene_set(&def, "radius=0.1", &err), SPH_ERR_USAGE);
    cr_expect(strstr(err.msg, "did you mean interaction.radius=0.1 or obstacle.radius=0.1?") != NULL, "%s", err.msg);
    cr_assert_eq(sph_scene_set(&def, "nosuch=1", &err), SPH_ERR_USAGE);
    cr_expect(strstr(err.msg, "expected section.key=value") != NULL && strstr(err.msg, "did you mean") == NULL, "%s",
              err.msg);
}

/* The equation of state's keys under a pressure solver: pcisph and dfsph hold
 * rho_rest without an equation of state, so eos, tait_gamma and eos_rest set
 * there are unread and said so, with their line; stiffness is read (the
 * artificial viscosity's speed of sound), and a velocity field's initial
 * pressure (field_pressure = on) reads the equation of state under a solver
 * too. */
Test(scene, eos_keys_unread_under_a_solver)
{
    const char *base = "[domain]\nmin = 0 0\nmax = 1 1\n[fluid a]\nmin = 0 0\nmax = 0.2 0.2\n[physics]\n"
                       "pressure_solver = %s\n%s = %s\nstiffness = 400\n";
    const struct {
        const char *key, *value;
    } keys[] = {{"eos", "tait"}, {"tait_gamma", "7"}, {"eos_rest", "lattice"}};
    char ini[512], buf[512];
    for (size_t k = 0; k < 3; k++)
        for (int s = 0; s < 3; s++) {
            const char *solver = s == 0 ? "eos" : s == 1 ? "pcisph" : "dfsph";
            /* tait_gamma is read by eos = tait only */
            snprintf(ini, sizeof ini, base, solver, keys[k].key, keys[k].value);
            if (k == 1) strcat(ini, "eos = tait\n");
            sph_scene_def def = test_scene(ini);
            const char *w = sph_scene_warning(&def, buf, sizeof buf);
            char want[128];
            snprintf(want, sizeof want, "test.ini:9: [physics] %s is set but this scene does not use it", keys[k].key);
            if (s == 0)
                cr_expect(!w || !strstr(w, "does not use it"), "eos with %s: %s", keys[k].key, w);
            else
                cr_expect(w && strstr(w, want) && strstr(w, "pressure_solver = eos"), "%s with %s: %s", solver,
                          keys[k].key, w ? w : "(no warning)");
        }
    /* stiffness stays unsaid under a solver */
    snprintf(ini, sizeof ini, base, "pcisph", "viscosity_form", "artificial");
    sph_scene_def def = test_scene(ini);
    const char *w = sph_scene_warning(&def, buf, sizeof buf);
    cr_expect(!w || !strstr(w, "does not use it"), "pcisph with stiffness: %s", w);
}

/* h not larger than the spacing: a lattice particle has no neighbour within h (the warning read "about 1.8
 * neighbours per particle", pi (h/s)^2, while check's hash health counted 0) */
Test(scene, h_below_the_spacing_is_said_as_no_neighbour)
{
    sph_scene_def def = test_scene("[scene]\neffects = gravity pressure walls\n[domain]\nmin = 0 0\nmax = 1 1\n"
                                   "[fluid a]\nmin = 0 0\nmax = 0.2 0.2\nspacing = 0.02\n[kernels]\nh = 0.015\n");
    char buf[4096];
    const char *w = sph_scene_warning(&def, buf, sizeof buf);
    cr_assert(w, "no warning");
    cr_expect(strstr(w, "is not larger than the spacing 0.02 m") && !strstr(w, "neighbours per particle"), "%s", w);
}

/* Every key the scene's choices leave unread is said, each on its own line, not only the first: a user fixing one
 * warning at a time found the next only on the following run (a review: delta, delta_form, solver_tolerance and
 * divergence_tolerance in an equation-of-state scene gave one warning, for delta). */
Test(scene, every_unread_key_is_said)
{
    sph_scene_def def = test_scene("[domain]\nmin = 0 0\nmax = 1 1\n[fluid a]\nmin = 0 0\nmax = 0.2 0.2\n[physics]\n"
                                   "delta = 0.1\ndelta_form = antuono\nsolver_tolerance = 0.01\n"
                                   "divergence_tolerance = 0.01\n");
    char buf[4096];
    const char *w = sph_scene_warning(&def, buf, sizeof buf);
    cr_assert(w, "no warning");
    const char *keys[] = {"delta", "delta_form", "solver_tolerance", "divergence_tolerance"};
    for (int k = 0; k < 4; k++) {
        char want[128];
        snprintf(want, sizeof want, "test.ini:%d: [physics] %s is set but this scene does not use it", 8 + k, keys[k]);
        cr_expect(strstr(w, want), "%s not said in:\n%s", keys[k], w);
    }
    int lines = 1;
    for (const char *c = w; *c; c++) lines += *c == '\n';
    cr_expect_eq(lines, 4, "one line per key:\n%s", w);
}
