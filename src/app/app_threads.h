/* How the core's worker threads wait between parallel regions.
 *
 * A step is some twenty short parallel regions. By default the OpenMP
 * runtime (libgomp) keeps its idle workers spinning between them; when
 * another process shares a core, a spinning or preempted worker holds every
 * region's barrier for a scheduler time slice, and two threads run 10 to 30
 * times slower than one. Waiting passively (sleeping on a futex) lets the
 * scheduler wake a worker at once instead. The runtime reads its settings
 * from the environment once, while the program loads, before main() (a
 * setenv from an ELF pre-initialiser is undone by the C library before
 * libgomp reads it), so the way in is to set OMP_WAIT_POLICY=passive and run
 * the program again. */
#ifndef APP_THREADS_H
#define APP_THREADS_H

/* The wait policy to set given the environment's values (NULL: unset):
 * "passive" when none of the runtimes' wait settings (OMP_WAIT_POLICY,
 * GOMP_SPINCOUNT, KMP_BLOCKTIME) is set, NULL when the user chose one. */
const char *sph_threads_wait_choose(const char *omp_wait_policy, const char *gomp_spincount,
                                    const char *kmp_blocktime);

/* First thing in main(), before any thread starts: when the environment sets
 * no wait policy, sets OMP_WAIT_POLICY=passive and runs this program again
 * (/proc/self/exe) with the same arguments; the second run finds it set and
 * goes on. Returns only if there was nothing to do or the program could not
 * run again (then the threads keep the runtime's default, spinning). */
void sph_threads_wait_passive(char **argv);

#endif
