/* The memory a run needs, against the memory the process may use. Each
 * figure follows the allocation it stands for in sph_sim_create and the
 * neighbours pass, so when one changes, so must the other. */
#include "sph_memory.h"
#include "sph_pass.h"
#include "sph_fields.h"
#include "sph_walls.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>
#include <unistd.h>

const char *sph_memory_text(double bytes, char *buf, size_t n)
{
    static const char *const units[] = {"bytes", "KiB", "MiB", "GiB", "TiB", "PiB"};
    int u = 0;
    while (bytes >= 1024 && u < 5) {
        bytes /= 1024;
        u++;
    }
    snprintf(buf, n, u ? "%.3g %s" : "%.0f %s", bytes, units[u]);
    return buf;
}

static void add(sph_mem_estimate *e, const char *name, double bytes, const char *fmt, double a, double b)
{
    if (!(bytes > 0) || e->n == SPH_MEM_ITEMS) return;
    sph_mem_item *it = &e->item[e->n];
    it->name = name;
    it->bytes = bytes;
    snprintf(it->detail, sizeof it->detail, fmt, a, b);
    if (!e->n || bytes > e->item[e->largest].bytes) e->largest = e->n;
    e->n++;
    e->total += bytes;
}

/* Cells of the dense grid, as sph_sim_create counts them (a double: it can
 * be absurd before validation refuses it). */
double sph_memory_grid_cells(const sph_scene_def *def)
{
    const double size = (double)def->h * (1.0 + 1.0 / 1024);
    double cells = 1;
    for (int d = 0; d < def->dim; d++) {
        double len = (double)def->domain_max[d] - def->domain_min[d];
        cells *= (def->periodic & (1u << d)) ? floor(len / size) : ceil(len / size) + 1;
    }
    return cells;
}

void sph_memory_estimate(const sph_scene_def *def, sph_mem_estimate *out)
{
    memset(out, 0, sizeof *out);
    bool in[SPH_PASS_COUNT];
    for (int p = 0; p < SPH_PASS_COUNT; p++) in[p] = sph_passes[p]->skip_reason(def) == NULL;
    const double n = sph_scene_particle_count(def) + sph_wall_particle_count(def), f = sizeof(float);

    /* particle fields: those always there and those whose pass runs, plus the ids */
    double comps = 1; /* P.id */
    for (int k = 0; k < SPH_FIELD_COUNT; k++) {
        const sph_field_info *info = &sph_field_infos[k];
        if (!sph_field_allocated(k, def, in)) continue;
        comps += info->vector ? def->dim : 1;
    }
    add(out, "particle fields", n * comps * f, "%.3g particles x %.0f floats", n, comps);

    double index = 0, table = 0;
    if (in[SPH_PASS_HASH]) {
        const double entry = 3 * sizeof(uint32_t);
        index = n * entry;
        if (!in[SPH_PASS_REORDER]) index += n * 4 * f; /* predicted positions in sorted order */
        if (def->sort == SPH_SORT_NONE) index += n * sizeof(uint32_t);
        /* the counting sort's scratch, unless it borrows the lists' buffer (sort.c) */
        if (def->sort == SPH_SORT_COUNTING && !in[SPH_PASS_NEIGHBOURS]) index += n * entry;
        if (in[SPH_PASS_REORDER]) index += n * (2 * sizeof(uint32_t) + f);
        add(out, "search index", index, "%.3g entries", n, 0);
        /* the start table, and the counting sort's histogram of the same size */
        double per_key = sizeof(uint32_t) * (def->sort == SPH_SORT_COUNTING ? 2 : 1);
        if (def->search == SPH_SEARCH_GRID) {
            double cells = sph_memory_grid_cells(def);
            table = cells * per_key;
            add(out, "grid cells", table, "%.3g cells of the dense grid", cells, 0);
        } else {
            double keys = def->table_size ? (double)def->table_size : fmax(n, 1);
            table = keys * per_key;
            add(out, "hash table", table, def->table_size ? "table_size = %.0f" : "table_size = %.0f (the particle count)",
                keys, 0);
        }
    }
    if (in[SPH_PASS_NEIGHBOURS] && def->backend != SPH_BACKEND_GL) { /* the GL backend builds no lists */
        /* each row once in its thread's buffer and once in the merged lists */
        double nb = sph_scene_neighbour_estimate(def);
        if (def->skin > 0) nb *= pow(1.0 + def->skin, def->dim); /* Verlet lists reach h (1 + skin) */
        nb = fmin(nb, n); /* no particle has more neighbours than particles */
        add(out, "neighbour lists", n * nb * 2 * sizeof(uint32_t), "%.3g particles x %.3g neighbours", n, nb);
    }
    if (def->backend == SPH_BACKEND_GL) /* the device's copy (in host memory with llvmpipe) */
        add(out, "GL buffers", n * comps * f + index + table, "the device's copy of the above", 0, 0);
}

/* A number from the first line of a file; false if absent or "max". */
static bool read_bytes(const char *path, double *out)
{
    FILE *fp = fopen(path, "r");
    if (!fp) return false;
    char line[64] = "";
    bool ok = fgets(line, sizeof line, fp) != NULL;
    fclose(fp);
    if (!ok) return false;
    char *end;
    double v = strtod(line, &end);
    if (end == line || !(v > 0)) return false;
    *out = v;
    return true;
}

/* Kilobytes of a "Name:  N kB" line of /proc/self/status. */
static double proc_status_kb(const char *name)
{
    FILE *fp = fopen("/proc/self/status", "r");
    if (!fp) return 0;
    char line[256];
    double kb = 0;
    size_t len = strlen(name);
    while (fgets(line, sizeof line, fp))
        if (strncmp(line, name, len) == 0 && line[len] == ':') {
            kb = atof(line + len + 1);
            break;
        }
    fclose(fp);
    return kb;
}

static void lower(sph_mem_limit *out, double bytes, const char *source)
{
    if (bytes < out->bytes) {
        out->bytes = bytes > 0 ? bytes : 0;
        out->source = source;
    }
}

void sph_memory_limit_at(const char *root, sph_mem_limit *out)
{
    out->bytes = INFINITY;
    out->source = "nothing known";
    double phys = (double)sysconf(_SC_PHYS_PAGES) * (double)sysconf(_SC_PAGE_SIZE);
    if (phys > 0) lower(out, phys, "physical memory");
    /* ulimit -v counts address space already mapped (libraries, GL drivers); ulimit -d the data segment */
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
        lower(out, (double)rl.rlim_cur - 1024 * proc_status_kb("VmSize"), "ulimit -v");
    if (getrlimit(RLIMIT_DATA, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY)
        lower(out, (double)rl.rlim_cur - 1024 * proc_status_kb("VmData"), "ulimit -d");
    /* the cgroup: v2 names one path ("0::/PATH"), v1 a line per controller ("N:memory:/PATH") */
    char path[512], line[512];
    snprintf(path, sizeof path, "%s/proc/self/cgroup", root);
    FILE *fp = fopen(path, "r");
    if (!fp) return;
    while (fgets(line, sizeof line, fp)) {
        line[strcspn(line, "\n")] = '\0';
        char *rest = strchr(line, ':');
        char *cg = rest ? strchr(rest + 1, ':') : NULL;
        if (!cg) continue;
        *cg++ = '\0';
        const char *ctl = rest + 1;
        double v;
        /* a nested cgroup's own file may say max while a parent's binds: walk up to the root */
        for (;;) {
            if (!*ctl) {
                snprintf(path, sizeof path, "%s/sys/fs/cgroup%s/memory.max", root, cg);
                if (read_bytes(path, &v)) lower(out, v, "cgroup memory.max");
            } else if (strstr(ctl, "memory")) {
                snprintf(path, sizeof path, "%s/sys/fs/cgroup/memory%s/memory.limit_in_bytes", root, cg);
                if (read_bytes(path, &v) && v < 1e18) lower(out, v, "cgroup memory.limit_in_bytes");
            }
            char *slash = strrchr(cg, '/');
            if (!slash || slash == cg) break;
            *slash = '\0';
        }
    }
    fclose(fp);
}

void sph_memory_limit(sph_mem_limit *out)
{
    sph_memory_limit_at("", out);
}

const char *sph_memory_list(const sph_mem_estimate *e, char *buf, size_t n)
{
    size_t used = 0;
    buf[0] = '\0';
    for (int i = 0; i < e->n && used < n; i++) {
        char b[32];
        used += (size_t)snprintf(buf + used, n - used, "%s %s, ", e->item[i].name,
                                 sph_memory_text(e->item[i].bytes, b, sizeof b));
    }
    if (used < n) {
        char b[32];
        snprintf(buf + used, n - used, "total %s", sph_memory_text(e->total, b, sizeof b));
    }
    return buf;
}

sph_error_code sph_memory_check(const sph_scene_def *def, const sph_mem_limit *limit, sph_error *err)
{
    sph_mem_estimate e;
    sph_memory_estimate(def, &e);
    if (!(e.total > limit->bytes)) return SPH_ERR_OK;
    const sph_mem_item *big = &e.item[e.largest];
    char need[32], lim[32], all[400];
    sph_memory_list(&e, all, sizeof all);
    return sph_fail(err, SPH_ERR_MEMORY, "%s: does not fit in memory: %s (%s) needs %s; limit %s (%s). In all: %s",
                    def->file, big->name, big->detail, sph_memory_text(big->bytes, need, sizeof need),
                    sph_memory_text(limit->bytes, lim, sizeof lim), limit->source, all);
}

void sph_memory_fail(const char *fmt, ...)
{
    char msg[400];
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(msg, sizeof msg, fmt, ap);
    va_end(ap);
    fprintf(stderr, "sphlab: out of memory: %s; the run stops (exit status %d)\n", msg, SPH_EXIT_MEMORY);
    exit(SPH_EXIT_MEMORY);
}
