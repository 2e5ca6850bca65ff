/* The memory estimate (every large allocation of a run) against the limits
 * of the process: physical memory, ulimit and the cgroup. */
#define _DEFAULT_SOURCE /* mkdtemp */
#include <criterion/criterion.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#include "sph_memory.h"
#include "test_util.h"

#define BOX "[scene]\neffects = gravity pressure viscosity walls\n[domain]\nmin = 0 0\nmax = 1 1\n"
#define BLOCK "[fluid a]\nmin = 0 0\nmax = 0.2 0.2\nspacing = 0.02\n[kernels]\nh = 0.04\n"

static double item(const sph_mem_estimate *e, const char *name)
{
    for (int i = 0; i < e->n; i++)
        if (strcmp(e->item[i].name, name) == 0) return e->item[i].bytes;
    return 0;
}

/* The estimate follows what sph_sim_create allocates: the fields the
 * pipeline has (counted from the sim's own arrays) and the start table. */
Test(memory, estimate_matches_the_simulation_allocations)
{
#define CUBE "[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n[fluid a]\nmin = 0 0 0\n" \
             "max = 0.2 0.2 0.2\nspacing = 0.04\n[kernels]\nh = 0.08\n"
    const char *inis[] = {BOX BLOCK, BOX BLOCK "[search]\nmethod = grid\n", BOX BLOCK "[search]\ntable_size = 1000\n",
                          CUBE};
    for (size_t k = 0; k < sizeof inis / sizeof inis[0]; k++) {
        sph_sim *sim = test_sim(inis[k], 1);
        sph_mem_estimate e;
        sph_memory_estimate(&sim->def, &e);
        double arrays = 1; /* P.id */
        for (int f = 0; f < SPH_FIELD_COUNT; f++)
            for (int d = 0; d < 3; d++) arrays += sim->P.field[f][d] != NULL;
        cr_expect_float_eq(item(&e, "particle fields"), arrays * 4 * sim->n, 1e-9, "scene %zu", k);
        /* counting sort (the default): the start table and its histogram, 8 bytes a key */
        double table = item(&e, sim->def.search == SPH_SEARCH_GRID ? "grid cells" : "hash table");
        cr_expect_float_eq(table, 8.0 * sim->S.table_size, 1e-9, "scene %zu: %g bytes for %u keys", k, table,
                           sim->S.table_size);
        cr_expect(item(&e, "neighbour lists") > 0, "scene %zu", k);
        sph_sim_destroy(sim);
    }
}

/* The GL backend builds no neighbour lists (its pair passes walk the cells): the estimate counted the CPU's
 * beside the GL buffers (865 MiB of them at 9 million particles). No GL context is needed for the estimate. */
Test(memory, gl_backend_counts_no_neighbour_lists)
{
    sph_scene_def def = test_scene(BOX BLOCK);
    sph_mem_estimate cpu, gl;
    sph_memory_estimate(&def, &cpu);
    def.backend = SPH_BACKEND_GL;
    sph_memory_estimate(&def, &gl);
    cr_expect(item(&cpu, "neighbour lists") > 0, "the CPU's lists are counted");
    cr_expect_eq(item(&gl, "neighbour lists"), 0, "GL: %g bytes of lists counted", item(&gl, "neighbour lists"));
    cr_expect(item(&gl, "GL buffers") > 0, "GL: its buffers are counted");
}

/* The hash table is counted: 2^20 keys on 100 particles is 8 MiB of it. */
Test(memory, hash_table_is_counted)
{
    sph_scene_def def = test_scene(BOX BLOCK "[search]\ntable_size = 1048576\n");
    sph_mem_estimate e;
    sph_memory_estimate(&def, &e);
    cr_expect_float_eq(item(&e, "hash table"), 8.0 * 1048576, 1e-9);
    cr_expect_str_eq(e.item[e.largest].name, "hash table");
}

/* The neighbour lists grow with n times the neighbour count: h = 8
 * spacings (201 neighbours in 2D) needs 4 times the lists of h = 4
 * (900 particles: more than either count, which caps the estimate). */
Test(memory, neighbour_lists_follow_the_neighbour_count)
{
#define BLOCK_ "[fluid a]\nmin = 0 0\nmax = 0.6 0.6\nspacing = 0.02\n"
    sph_scene_def a = test_scene(BOX BLOCK_ "[kernels]\nh = 0.08\n");
    sph_scene_def b = test_scene(BOX BLOCK_ "[kernels]\nh = 0.16\n");
    sph_mem_estimate ea, eb;
    sph_memory_estimate(&a, &ea);
    sph_memory_estimate(&b, &eb);
    double la = item(&ea, "neighbour lists"), lb = item(&eb, "neighbour lists");
    cr_expect_float_eq(lb / la, 4.0, 1e-6, "%g and %g bytes", la, lb);
    cr_expect_float_eq(la, 900 * sph_scene_neighbour_estimate(&a) * 8, 1e-6);
}

/* A scene over the limit: refused with the largest item, both figures and
 * the limit's source. */
Test(memory, check_names_the_largest_item_and_the_limit)
{
    sph_scene_def def = test_scene(BOX BLOCK "[search]\ntable_size = 1048576\n");
    sph_mem_limit lim = {1024.0 * 1024, "cgroup memory.max"};
    sph_error err;
    cr_assert_eq(sph_memory_check(&def, &lim, &err), SPH_ERR_MEMORY);
    cr_expect(strstr(err.msg, "hash table (table_size = 1048576) needs 8 MiB") && strstr(err.msg, "limit 1 MiB") &&
                  strstr(err.msg, "cgroup memory.max"),
              "%s", err.msg);
    lim.bytes = 1e12;
    cr_expect_eq(sph_memory_check(&def, &lim, &err), SPH_ERR_OK);
}

/* table_size = 2^31 on 100 particles (16 GiB of keys): refused whatever the
 * machine, naming table_size (it was accepted, and the run's allocation
 * failure blamed the particles). */
Test(memory, huge_table_is_refused_naming_table_size)
{
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    cr_assert_eq(sph_scene_load_string(BOX BLOCK "[search]\ntable_size = 2147483648\n", "t.ini", &def, &err), 0);
    cr_assert_eq(sph_scene_validate(&def, &err), SPH_ERR_RANGE);
    cr_expect(strstr(err.msg, "t.ini:13: [search] table_size = 2147483648") && strstr(err.msg, "16 GiB"), "%s", err.msg);
    /* the largest table the rule allows is accepted */
    def = sph_default_scene_def();
    cr_assert_eq(sph_scene_load_string(BOX BLOCK "[search]\ntable_size = 1048576\n", "t.ini", &def, &err), 0);
    cr_expect_eq(sph_scene_validate(&def, &err), SPH_ERR_OK, "%s", err.msg);
}

static void put(const char *root, const char *path, const char *text)
{
    char full[512];
    snprintf(full, sizeof full, "%s/%s", root, path);
    for (char *p = full + strlen(root) + 1; *p; p++)
        if (*p == '/') {
            *p = '\0';
            mkdir(full, 0700);
            *p = '/';
        }
    FILE *f = fopen(full, "w");
    cr_assert(f, "%s", full);
    fputs(text, f);
    fclose(f);
}

/* cgroup v2: the process's own cgroup says max, its parent 1 GiB: 1 GiB
 * binds. v1: memory.limit_in_bytes under the memory controller. */
Test(memory, limit_reads_the_cgroup)
{
    char root[] = "/tmp/sphlab-cgroup-XXXXXX";
    cr_assert(mkdtemp(root));
    put(root, "proc/self/cgroup", "0::/a/b\n");
    put(root, "sys/fs/cgroup/a/b/memory.max", "max\n");
    put(root, "sys/fs/cgroup/a/memory.max", "1073741824\n");
    sph_mem_limit lim;
    sph_memory_limit_at(root, &lim);
    cr_expect_float_eq(lim.bytes, 1073741824.0, 1, "%g (%s)", lim.bytes, lim.source);
    cr_expect_str_eq(lim.source, "cgroup memory.max");

    put(root, "proc/self/cgroup", "4:memory:/job\n1:cpu:/\n");
    put(root, "sys/fs/cgroup/memory/job/memory.limit_in_bytes", "536870912\n");
    sph_memory_limit_at(root, &lim);
    cr_expect_float_eq(lim.bytes, 536870912.0, 1, "%g (%s)", lim.bytes, lim.source);
    cr_expect_str_eq(lim.source, "cgroup memory.limit_in_bytes");

    /* no cgroup limit: physical memory (or a ulimit) binds */
    put(root, "proc/self/cgroup", "0::/\n");
    put(root, "sys/fs/cgroup/memory.max", "max\n");
    sph_memory_limit_at(root, &lim);
    cr_expect(lim.bytes > 1e6 && isfinite(lim.bytes), "%g (%s)", lim.bytes, lim.source);
    char cmd[600];
    snprintf(cmd, sizeof cmd, "rm -rf %s", root);
    cr_expect_eq(system(cmd), 0);
}

/* `sphlab check` under ulimit -v: a scene of 8 million 3D particles (3 GiB)
 * is refused with exit status 5, naming the neighbour lists and the ulimit. */
#if defined(__SANITIZE_ADDRESS__)
#define SPH_TEST_ASAN 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define SPH_TEST_ASAN 1
#endif
#endif

Test(memory, check_honours_ulimit, .timeout = 120)
{
#ifdef SPH_TEST_ASAN
    cr_skip_test("AddressSanitizer reserves terabytes of shadow address space at start, which ulimit -v forbids");
#endif
    const char *scene = test_write_temp("[scene]\ndimension = 3\n[domain]\nmin = 0 0 0\nmax = 1 1 1\n"
                                        "[fluid a]\nmin = 0 0 0\nmax = 1 1 1\nspacing = 0.005\n[kernels]\nh = 0.01\n",
                                        ".ini");
    char args[600], out[4096];
    const char *bin = getenv("SPHLAB");
    snprintf(args, sizeof args, "-c 'ulimit -v 1000000; exec %s check %s' sh", bin && *bin ? bin : "./sphlab", scene);
    char cmd[800];
    snprintf(cmd, sizeof cmd, "sh %s 2>&1", args);
    FILE *p = popen(cmd, "r");
    cr_assert(p);
    size_t n = fread(out, 1, sizeof out - 1, p);
    out[n] = '\0';
    int st = pclose(p);
    cr_expect(WIFEXITED(st) && WEXITSTATUS(st) == SPH_EXIT_MEMORY, "status %d: %s", st, out);
    cr_expect(strstr(out, "neighbour lists") && strstr(out, "ulimit -v") && strstr(out, scene), "%s", out);
    remove(scene);
}
