#define _DEFAULT_SOURCE /* mkstemps */
#include "test_util.h"

#include <criterion/criterion.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/wait.h>
#include <unistd.h>

sph_scene_def test_scene(const char *ini)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    if (sph_scene_load_string(ini, "test.ini", &def, &err) != SPH_ERR_OK ||
        sph_scene_validate(&def, &err) != SPH_ERR_OK)
        cr_assert_fail("scene does not load: %s", err.msg);
    return def;
}

sph_sim *test_sim(const char *ini, int threads)
{
    sph_scene_def def = test_scene(ini);
    sph_sim *sim;
    sph_error err;
    if (sph_sim_create(&def, threads, &sim, &err) != SPH_ERR_OK) cr_assert_fail("sim not created: %s", err.msg);
    return sim;
}

void test_run_pass(sph_sim *sim, sph_pass_id id)
{
    sph_passes[id]->run(sim);
}

int test_sphlab(const char *args, char *out, size_t cap)
{
    return test_sphlab_env(NULL, args, out, cap);
}

int test_sphlab_env(const char *env, const char *args, char *out, size_t cap)
{
    const char *bin = getenv("SPHLAB");
    char cmd[4096];
    snprintf(cmd, sizeof cmd, "%s%s%s%s %s 2>&1", env ? "env " : "", env ? env : "", env ? " " : "",
             bin && *bin ? bin : "./sphlab", args);
    FILE *p = popen(cmd, "r");
    if (!p) cr_assert_fail("cannot run %s", cmd);
    size_t n = 0;
    if (out && cap) {
        n = fread(out, 1, cap - 1, p);
        out[n] = '\0';
    }
    char sink[4096];
    while (fread(sink, 1, sizeof sink, p) > 0) {}
    int st = pclose(p);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

const char *test_write_temp(const char *text, const char *suffix)
{
    static char paths[8][256];
    static int slot;
    char *path = paths[slot++ % 8];
    snprintf(path, 256, "/tmp/sphlab-test-XXXXXX%s", suffix);
    int fd = mkstemps(path, (int)strlen(suffix));
    if (fd < 0) cr_assert_fail("cannot make a temporary file");
    size_t len = strlen(text);
    if (write(fd, text, len) != (ssize_t)len) cr_assert_fail("cannot write %s", path);
    close(fd);
    return path;
}

const char *test_temp_dir(const char *what)
{
    static char paths[8][96];
    static int slot;
    char *p = paths[slot++ % 8];
    snprintf(p, sizeof paths[0], "/tmp/sphlab-%s-XXXXXX", what);
    if (!mkdtemp(p)) cr_assert_fail("cannot make a temporary directory %s", p);
    return p;
}

void test_remove_dir(const char *dir)
{
    char cmd[256];
    snprintf(cmd, sizeof cmd, "rm -rf '%s'", dir);
    cr_expect_eq(system(cmd), 0, "cannot remove %s", dir);
}
