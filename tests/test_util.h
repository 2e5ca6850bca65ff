/* Helpers shared by the Criterion tests. */
#ifndef SPH_TEST_UTIL_H
#define SPH_TEST_UTIL_H

#include "sph_sim.h"

/* A scene from INI text over the defaults, validated; the test fails with the message if not. */
sph_scene_def test_scene(const char *ini);
/* A simulation of that scene; the test fails if it cannot be made. */
sph_sim *test_sim(const char *ini, int threads);
/* Runs one pass by id, timed, as the pipeline would. */
void test_run_pass(sph_sim *sim, sph_pass_id id);
/* Runs the whole `sphlab` binary (path from $SPHLAB, default ./sphlab) with
 * args through the shell; returns its exit status and fills out (stdout and
 * stderr together, up to cap bytes). */
int test_sphlab(const char *args, char *out, size_t cap);
/* The same with environment assignments ("A=1 B=2") before the binary; NULL: none. */
int test_sphlab_env(const char *env, const char *args, char *out, size_t cap);
/* A fresh directory /tmp/sphlab-WHAT-XXXXXX (8 static slots) / removed with all it holds. */
const char *test_temp_dir(const char *what);
void test_remove_dir(const char *dir);
/* Writes text to a fresh temporary file and returns its path (static buffer per call slot). */
const char *test_write_temp(const char *text, const char *suffix);

#endif
