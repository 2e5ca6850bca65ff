/* libFuzzer target for the scene parser: any bytes must give either a scene
 * or an error message, never a crash, a hang or undefined behaviour. A scene
 * that validates and is small is also simulated for two steps, so fuzzed
 * parameters reach the passes. Built and run by `make fuzz` (clang). */
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "sph_sim.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size > 1 << 16) return 0;
    char *text = malloc(size + 1);
    if (!text) return 0;
    memcpy(text, data, size);
    text[size] = '\0';
    sph_scene_def def = sph_default_scene_def();
    sph_error err;
    if (sph_scene_load_string(text, "fuzz.ini", &def, &err) == SPH_ERR_OK &&
        sph_scene_validate(&def, &err) == SPH_ERR_OK) {
        /* the error path must always produce a message; the success path a usable scene */
        /* simulate only what stays fast: a scene may legitimately ask for N^2 pairs */
        double pairs = sph_scene_particle_count(&def) * sph_scene_neighbour_estimate(&def);
        if (sph_scene_particle_count(&def) <= 2000 && pairs <= 2e5) {
            sph_scene_def small = def;
            small.search = def.search == SPH_SEARCH_GRID ? SPH_SEARCH_HASH : def.search; /* grid memory follows the domain */
            sph_sim *sim;
            if (sph_sim_create(&small, 1, &sim, &err) == SPH_ERR_OK) {
                for (int s = 0; s < 2 && !sim->alarm.raised; s++) sph_sim_step(sim);
                sph_sim_destroy(sim);
            }
        }
    } else if (err.msg[0] == '\0') {
        abort(); /* every failure must explain itself */
    }
    free(text);
    return 0;
}
