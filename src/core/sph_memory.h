/* What a run of a scene needs in memory, and what this process may use.
 * sph_scene_validate compares the two, so `sphlab check` refuses a scene
 * that cannot fit, naming its largest allocation, before anything is made. */
#ifndef SPH_MEMORY_H
#define SPH_MEMORY_H

#include "sph_scene.h"

/* The exit status of a command whose scene does not fit in memory, or whose
 * run failed to allocate (docs/scene-format.md, "Errors"). */
#define SPH_EXIT_MEMORY 5

#define SPH_MEM_ITEMS 10

typedef struct sph_mem_item {
    const char *name;  /* "particle fields", "hash table", ... */
    double bytes;      /* [B] */
    char detail[120];  /* what it is made of, e.g. "table_size = 2147483648" */
} sph_mem_item;

typedef struct sph_mem_estimate {
    int n;
    sph_mem_item item[SPH_MEM_ITEMS];
    double total; /* [B] */
    int largest;  /* index of the largest item */
} sph_mem_estimate;

typedef struct sph_mem_limit {
    double bytes;       /* [B] what the process may still allocate; INFINITY if nothing is known */
    const char *source; /* which limit binds: "physical memory", "ulimit -v", "ulimit -d", "cgroup" */
} sph_mem_limit;

/* Every large allocation a run of def makes: particle fields (per the field
 * registry and the pipeline), the search index and its hash table or grid,
 * the neighbour lists at the expected neighbour count, GL buffers. */
void sph_memory_estimate(const sph_scene_def *def, sph_mem_estimate *out);

/* The smallest of: physical memory, RLIMIT_AS and RLIMIT_DATA (less what the
 * process already maps), the cgroup's memory.max (v2) or
 * memory.limit_in_bytes (v1). */
void sph_memory_limit(sph_mem_limit *out);
/* The same with the cgroup files read under root ("" for the real ones):
 * root/proc/self/cgroup and root/sys/fs/cgroup/... (for tests). */
void sph_memory_limit_at(const char *root, sph_mem_limit *out);

/* SPH_ERR_MEMORY, naming the largest item and both figures, if the estimate
 * does not fit in the limit. */
sph_error_code sph_memory_check(const sph_scene_def *def, const sph_mem_limit *limit, sph_error *err);

/* Prints "N.N GiB" (or MiB, KiB, bytes) into buf. */
const char *sph_memory_text(double bytes, char *buf, size_t n);

/* A run-time allocation failed inside a pass, where no error can be returned:
 * prints what (and how much) and exits with SPH_EXIT_MEMORY. */
_Noreturn void sph_memory_fail(const char *what, double bytes);

#endif
