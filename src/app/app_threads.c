/* The threads' wait policy, set before the OpenMP runtime starts (see app_threads.h). */
#include <stdlib.h>
#include <unistd.h>

#include "app_threads.h"

const char *sph_threads_wait_choose(const char *omp_wait_policy, const char *gomp_spincount,
                                    const char *kmp_blocktime)
{
    if (omp_wait_policy || gomp_spincount || kmp_blocktime) return NULL; /* the user's choice */
    return "passive";
}

void sph_threads_wait_passive(char **argv)
{
    const char *w = sph_threads_wait_choose(getenv("OMP_WAIT_POLICY"), getenv("GOMP_SPINCOUNT"), getenv("KMP_BLOCKTIME"));
    if (!w || !argv || !argv[0] || setenv("OMP_WAIT_POLICY", w, 0) != 0) return;
    /* Set, the policy stops the next run from coming back here: no loop. */
    execv("/proc/self/exe", argv);
}
