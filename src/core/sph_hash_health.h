/* Hash health: how well the spatial hash spreads the particles over its keys,
 * measured from the particles' positions with the same cells, hash and key as
 * the hash pass (src/passes/hash.c). Shown in the HUD, by `sphlab check` and
 * as --stats columns; docs/performance.md defines the figures the same way. */
#ifndef SPH_HASH_HEALTH_H
#define SPH_HASH_HEALTH_H

#include <stdbool.h>
#include <stdint.h>

#include "sph_sim.h"

typedef struct sph_hash_health {
    /* false: the scene has no hash table (search = grid or brute, or no
     * effect needs neighbours); `why` says which and every figure is 0. */
    bool has_table;
    const char *why;
    uint32_t table_size;  /* number of keys (the start table's length) */
    uint32_t particles;   /* entries in the table: one per particle */
    double load_factor;   /* particles / table_size */
    uint32_t occupied;    /* keys that hold at least one particle */
    /* Collision: an occupied key whose particles come from more than one
     * grid cell (two cells whose hashes are equal modulo table_size). */
    uint32_t colliding;
    uint32_t longest_run; /* most particles holding one key (the longest run of the sorted entries) */
    /* Candidates visited: the entries the neighbour search examines for one
     * particle in its 3^dim cell walk, i.e. the sum over the stencil's cells
     * of the particles holding that cell's key (a key's whole run is read,
     * whatever cell its entries come from; the particle itself counts).
     * Mean over the particles. */
    double candidates;
    /* True neighbours: the candidates within h of the particle (r^2 < h^2,
     * itself excluded), the pairs of the neighbour lists. share =
     * true neighbours / candidates over all particles; NaN when not counted
     * (the lists not built on the host and count_neighbours false). */
    double neighbours;    /* mean true neighbours per particle, NaN if not counted */
    double share;         /* true neighbours / candidates, in [0, 1], NaN if not counted */
} sph_hash_health;

/* The figures for the particles' predicted positions (what the last hash
 * pass saw; the current positions before the first step). Costs O(N + keys):
 * one pass over the particles, one over the keys, and a stencil of 3^dim
 * keys each time the particle order enters a new cell (about 1.5 ms at
 * 62,500 particles, docs/performance.md). The true neighbours
 * come from the neighbour lists when the CPU built them, else, with
 * count_neighbours, from a distance test over every candidate (the cost of a
 * neighbour search). Returns false only when out of memory (out says why). */
bool sph_sim_hash_health(const sph_sim *sim, bool count_neighbours, sph_hash_health *out);

#endif
