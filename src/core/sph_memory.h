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

/* Cells of the dense grid ([search] method = grid) as sph_sim_create counts
 * them, in double: before validation the count can be absurd. */
double sph_memory_grid_cells(const sph_scene_def *def);

/* ---- limits of a scene (sph_scene_limits.c) ---- */

/* [m] The simulation's frame along axis d: the domain's point nearest 0 (0
 * for a domain that contains 0, its min corner for one beyond 0). Positions
 * are floats relative to it (sph_sim_create). */
double sph_scene_origin(const sph_scene_def *def, int d);
/* A float's step at the largest |coordinate| of the domain in that frame
 * must be at most this share of h (why: sph_scene_limits.c). */
#define SPH_POSITION_STEP (1.0 / 2048)
/* The dense grid's cells at most (its start table is 4 bytes a cell). */
#define SPH_GRID_CELLS_MAX (1 << 28)
/* [search] table_size at most max(64 n, 2^20) keys (why: sph_scene_limits.c). */
#define SPH_TABLE_PER_PARTICLE 64
#define SPH_TABLE_FLOOR (1 << 20)
/* [m] the largest float step of a position the scene accepts: h / 2048. */
double sph_scene_position_step_bound(const sph_scene_def *def);
/* Float precision over the domain, the search's cell counts, and memory
 * against sph_memory_limit(): the checks sph_scene_validate makes last. */
sph_error_code sph_scene_check_limits(const sph_scene_def *def, sph_error *err);

/* "particle fields 1.2 GiB, hash table 4 MiB, ..., total 2 GiB" into buf. */
const char *sph_memory_list(const sph_mem_estimate *e, char *buf, size_t n);

/* Prints "N.N GiB" (or MiB, KiB, bytes) into buf. */
const char *sph_memory_text(double bytes, char *buf, size_t n);

/* A run-time allocation failed inside a pass, where no error can be returned:
 * prints "out of memory: " and the message (what, how much) and exits with
 * SPH_EXIT_MEMORY. */
_Noreturn void sph_memory_fail(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

#endif
