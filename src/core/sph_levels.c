/* The ladder's levels (sph_levels.h): the table `sphlab bench` measures and
 * the window switches between. */
#include "sph_levels.h"

#include <stdio.h>
#include <string.h>

/* The ladder, one line per level. Each line names every search key it
 * relies on, so a level does not change when a default does. To add a
 * level, add a line (any scene key, `sphlab keys` lists them). */
const sph_level sph_levels[] = {
    {"L0", "brute force O(N^2) on 1 thread", "search.method=brute search.reorder=off search.vector=off", 1,
     "force brute O(N^2) sur 1 fil"},
    {"L1", "spatial hash unsorted (linked lists)",
     "search.method=hash search.sort=none search.reorder=off search.vector=off", 1,
     "hachage spatial non trié (listes chaînées)"},
    {"L2", "hash + bitonic sort + offsets (the seed)",
     "search.method=hash search.sort=bitonic search.reorder=off search.vector=off", 1,
     "hachage + tri bitonique + décalages (le projet d'origine)"},
    {"L3", "counting sort", "search.method=hash search.sort=counting search.reorder=off search.vector=off", 1,
     "tri par comptage"},
    {"L4", "particle data reordered by cell", "search.method=hash search.sort=counting search.reorder=on search.vector=off",
     1, "données des particules réordonnées par cellule"},
    {"L5", "OpenMP on all cores", "search.method=hash search.sort=counting search.reorder=on search.vector=off", 0,
     "OpenMP sur tous les cœurs"},
    {"L6", "vectorised inner loops (AVX-512)",
     "search.method=hash search.sort=counting search.reorder=on search.vector=on", 0,
     "boucles internes vectorisées (AVX-512)"},
    {"L7", "dense grid: a stencil row is one run",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on", 0,
     "grille dense : une ligne du pochoir est une plage"},
    /* Past L7 (docs/performance.md, "Past L7"): fewer gathers per neighbour. */
    {"L8", "L7 + pressure and viscosity in one walk",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on", 0,
     "L7 + pression et viscosité en un seul parcours"},
    {"L9", "L8 + lists built in place (one copy less)",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on",
     0, "L8 + listes construites sur place (une copie de moins)"},
    {"L10", "L9 + Verlet lists (skin 0.05 h)",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05",
     0, "L9 + listes de Verlet (peau 0.05 h)"},
    {"L11", "L10 + compact lists (16-bit offsets)",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05 search.compact_lists=on",
     0, "L10 + listes compactes (décalages sur 16 bits)"},
    {"L12", "L11 + AVX2 vector loops (8 lanes)",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05 search.compact_lists=on search.vector_avx2=on",
     0, "L11 + boucles vectorielles AVX2 (8 voies)"},
    {"L13", "L12 + packed records (loads, not gathers)",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05 search.compact_lists=on search.vector_avx2=on "
     "compute.packed_records=on",
     0, "L12 + enregistrements groupés (chargements, pas de collectes)"},
    {"L14", "L13 + one mass for all (no mass gather)",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05 search.compact_lists=on search.vector_avx2=on "
     "compute.packed_records=on compute.uniform_mass=on",
     0, "L13 + une masse pour toutes (pas de collecte des masses)"},
    {"L15", "L14 + search a cell's particles together",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05 search.compact_lists=on search.vector_avx2=on "
     "compute.packed_records=on compute.uniform_mass=on search.cell_batch=on",
     0, "L14 + recherche des particules d'une cellule ensemble"},
    {"L16", "L15 + density's walk on 16 lanes",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05 search.compact_lists=on search.vector_avx2=on "
     "compute.packed_records=on compute.uniform_mass=on search.cell_batch=on compute.wide_density=on",
     0, "L15 + parcours de la densité sur 16 voies (AVX-512)"},
    {"L17", "L16 + the search's batch on 16 lanes",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05 search.compact_lists=on search.vector_avx2=on "
     "compute.packed_records=on compute.uniform_mass=on search.cell_batch=on compute.wide_density=on "
     "search.wide_batch=on",
     0, "L16 + lot de la recherche sur 16 voies (AVX-512)"},
    {"L18", "L17 + list pages kept (no faults)",
     "search.method=grid search.sort=counting search.reorder=on search.vector=on compute.fuse_forces=on "
     "search.lists_in_place=on search.skin=0.05 search.compact_lists=on search.vector_avx2=on "
     "compute.packed_records=on compute.uniform_mass=on search.cell_batch=on compute.wide_density=on "
     "search.wide_batch=on search.lists_resident=on",
     0, "L17 + pages des listes gardées (sans défauts de page)"},
    /* The seed's GPU steps: the passes as GLSL compute shaders (src/gpu/), on
     * whatever OpenGL 4.3 device EGL gives (llvmpipe without a GPU). */
    {"G0", "GLSL: brute force", "compute.backend=gl search.method=brute search.reorder=off", 0, "GLSL : force brute"},
    {"G1", "GLSL: hash + bitonic sort (the seed)",
     "compute.backend=gl search.method=hash search.sort=bitonic search.reorder=off", 0,
     "GLSL : hachage + tri bitonique (le projet d'origine)"},
    /* From G2 on the pressure force and viscosity share one walk
     * (docs/performance.md, "The GL levels": the forces in half the time on
     * llvmpipe, the same result to the bit). */
    {"G2", "GLSL: counting sort, reorder, fused forces",
     "compute.backend=gl search.method=hash search.sort=counting search.reorder=on compute.fuse_forces=on", 0,
     "GLSL : tri par comptage + réordonnancement + forces fusionnées"},
    {"G3", "GLSL: dense grid: stencil rows",
     "compute.backend=gl search.method=grid search.sort=counting search.reorder=on compute.fuse_forces=on", 0,
     "GLSL : grille dense : lignes du pochoir"},
};
const int sph_level_count = (int)(sizeof sph_levels / sizeof sph_levels[0]);

int sph_level_find(const char *name)
{
    for (int i = 0; i < sph_level_count; i++)
        if (strcmp(sph_levels[i].name, name) == 0) return i;
    return -1;
}

bool sph_level_gl(const sph_level *L) { return strstr(L->sets, "compute.backend=gl") != NULL; }

sph_error_code sph_level_apply(const sph_level *L, sph_scene_def *def, sph_error *err)
{
    /* the ingredients past L7 are off unless the level names them, so going
     * from L8 down to L7 (in the window) leaves no fused walk behind */
    def->fuse_forces = SPH_OFF;
    def->lists_in_place = SPH_OFF;
    def->compact_lists = SPH_OFF;
    def->vector_avx2 = SPH_OFF;
    def->packed_records = SPH_OFF;
    def->uniform_mass = SPH_OFF;
    def->cell_batch = SPH_OFF;
    def->wide_density = SPH_OFF;
    def->wide_batch = SPH_OFF;
    def->lists_resident = SPH_OFF;
    def->skin = 0.0f;
    char buf[512];
    snprintf(buf, sizeof buf, "%s", L->sets);
    char *save = NULL;
    for (char *tok = strtok_r(buf, " \t", &save); tok; tok = strtok_r(NULL, " \t", &save)) {
        sph_error_code c = sph_scene_set(def, tok, err);
        if (c != SPH_ERR_OK) return c;
    }
    /* a CPU level runs on the CPU whatever the scene said */
    if (!sph_level_gl(L)) def->backend = SPH_BACKEND_CPU;
    return SPH_ERR_OK;
}

int sph_level_of(const sph_scene_def *def, int threads, int cores)
{
    const bool one = threads == 1 || (threads <= 0 && cores == 1);
    for (int i = 0; i < sph_level_count; i++) {
        const sph_level *L = &sph_levels[i];
        if ((L->threads == 1) != one) continue;
        sph_scene_def at = *def;
        sph_error err;
        if (sph_level_apply(L, &at, &err) != SPH_ERR_OK) continue;
        if (at.search == def->search && at.sort == def->sort && at.reorder == def->reorder &&
            at.vector == def->vector && at.backend == def->backend && at.fuse_forces == def->fuse_forces &&
            at.lists_in_place == def->lists_in_place && at.skin == def->skin &&
            at.compact_lists == def->compact_lists && at.vector_avx2 == def->vector_avx2 &&
            at.packed_records == def->packed_records && at.uniform_mass == def->uniform_mass &&
            at.cell_batch == def->cell_batch && at.wide_density == def->wide_density &&
            at.wide_batch == def->wide_batch && at.lists_resident == def->lists_resident)
            return i;
    }
    return -1;
}
