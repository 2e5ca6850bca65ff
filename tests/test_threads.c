/* The threads' wait policy (src/app/app_threads.c, issue 17 "Threads on a
 * busy machine"): sphlab's OpenMP runtime starts with passive waits unless
 * the user chose a policy. Checked through what the runtime itself reports
 * (OMP_DISPLAY_ENV=verbose, printed as libgomp starts), never through speed. */
#define _DEFAULT_SOURCE /* setenv, unsetenv */
#include <criterion/criterion.h>
#include <stdlib.h>
#include <string.h>

#include "app_threads.h"
#include "test_util.h"

static char g_out[1 << 16];

Test(threads, passive_unless_the_user_chose)
{
    cr_assert_str_eq(sph_threads_wait_choose(NULL, NULL, NULL), "passive");
    cr_assert_null(sph_threads_wait_choose("active", NULL, NULL));
    cr_assert_null(sph_threads_wait_choose("passive", NULL, NULL));
    cr_assert_null(sph_threads_wait_choose(NULL, "10000", NULL));
    cr_assert_null(sph_threads_wait_choose(NULL, NULL, "0"));
}

/* The spin count libgomp reported last (the run the program ended in; the
 * first run reports too when sphlab runs itself again), or NULL if the
 * runtime printed none (not libgomp). */
static const char *spin_count_reported(const char *args, char *value, size_t cap)
{
    setenv("OMP_DISPLAY_ENV", "verbose", 1);
    int rc = test_sphlab(args, g_out, sizeof g_out);
    cr_assert_eq(rc, 0, "sphlab %s: exit %d\n%s", args, rc, g_out);
    const char *key = "GOMP_SPINCOUNT = '", *last = NULL;
    for (const char *p = strstr(g_out, key); p; p = strstr(p + 1, key)) last = p + strlen(key);
    if (!last) return NULL;
    size_t n = strcspn(last, "'");
    if (n >= cap) n = cap - 1;
    memcpy(value, last, n);
    value[n] = '\0';
    return value;
}

Test(threads, runtime_starts_with_passive_waits)
{
    unsetenv("OMP_WAIT_POLICY");
    unsetenv("GOMP_SPINCOUNT");
    unsetenv("KMP_BLOCKTIME");
    char spin[64];
    if (!spin_count_reported("keys", spin, sizeof spin)) cr_skip_test("the OpenMP runtime is not libgomp");
    /* libgomp's default without a policy is 300000 spins: the slow case */
    cr_assert_str_eq(spin, "0", "GOMP_SPINCOUNT '%s' (passive waits spin 0 times)\n%s", spin, g_out);
}

Test(threads, user_policy_kept)
{
    unsetenv("GOMP_SPINCOUNT");
    unsetenv("KMP_BLOCKTIME");
    setenv("OMP_WAIT_POLICY", "active", 1);
    char spin[64];
    if (!spin_count_reported("keys", spin, sizeof spin)) cr_skip_test("the OpenMP runtime is not libgomp");
    cr_assert_str_neq(spin, "0", "OMP_WAIT_POLICY=active was overridden\n%s", g_out);
    /* only one run: with the user's policy set, sphlab does not run itself again */
    cr_assert_null(strstr(strstr(g_out, "GOMP_SPINCOUNT") + 1, "GOMP_SPINCOUNT"), "%s", g_out);
}
