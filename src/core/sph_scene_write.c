/* A scene definition written back as a scene file: the name and dimension,
 * then every key whose value differs from its default, section by section in
 * the order of the key table, then one [fluid NAME] section per block. Read
 * again with sph_scene_load over the defaults, it gives the same values (the
 * window's "Save scene as…", `sphlab check --save-scene`). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "sph_scene.h"

/* The shortest of %.6g .. %.9g that reads back to the same float (9 digits
 * always do): 0.3, not 0.300000012. */
static void float_text(float v, char *out, size_t n)
{
    for (int digits = 6; digits <= 9; digits++) {
        snprintf(out, n, "%.*g", digits, (double)v);
        if (strtof(out, NULL) == v) return;
    }
}

/* The same for a double (SPH_KEY_POINT): 17 digits always read back. */
static void double_text(double v, char *out, size_t n)
{
    for (int digits = 6; digits <= 17; digits++) {
        snprintf(out, n, "%.*g", digits, v);
        if (strtod(out, NULL) == v) return;
    }
}

/* The value of key k stored at base, as a scene file writes it; floats read
 * back to the same bits. */
void sph_scene_value_text(const sph_key *k, const void *base, char *out, size_t n)
{
    const char *field = (const char *)base + k->offset;
    switch (k->type) {
    case SPH_KEY_STRING: snprintf(out, n, "%s", field); return;
    case SPH_KEY_FLOAT: {
        float v;
        memcpy(&v, field, sizeof v);
        float_text(v, out, n);
        return;
    }
    case SPH_KEY_INT: {
        int v;
        memcpy(&v, field, sizeof v);
        snprintf(out, n, "%d", v);
        return;
    }
    case SPH_KEY_UINT: {
        uint32_t v;
        memcpy(&v, field, sizeof v);
        snprintf(out, n, "%u", (unsigned)v);
        return;
    }
    case SPH_KEY_VEC: { /* all three components: a 2D file's two would set z to 0 */
        float v[3];
        char c[3][32];
        memcpy(v, field, sizeof v);
        for (int d = 0; d < 3; d++) float_text(v[d], c[d], sizeof c[d]);
        snprintf(out, n, "%s %s %s", c[0], c[1], c[2]);
        return;
    }
    case SPH_KEY_POINT: { /* a position kept in double (far from 0) */
        double v[3];
        char c[3][32];
        memcpy(v, field, sizeof v);
        for (int d = 0; d < 3; d++) double_text(v[d], c[d], sizeof c[d]);
        snprintf(out, n, "%s %s %s", c[0], c[1], c[2]);
        return;
    }
    case SPH_KEY_CHOICE:
    case SPH_KEY_KERNEL: {
        int v;
        memcpy(&v, field, sizeof v);
        snprintf(out, n, "%s", v >= 0 && v < k->n_choices ? k->choices[v] : "?");
        return;
    }
    case SPH_KEY_FLAGS: {
        unsigned v;
        memcpy(&v, field, sizeof v);
        size_t used = 0;
        out[0] = '\0';
        for (int c = 0; c < k->n_choices && used < n; c++)
            if (v & (1u << c)) used += (size_t)snprintf(out + used, n - used, "%s%s", used ? " " : "", k->choices[c]);
        if (!used) snprintf(out, n, "none");
        return;
    }
    }
}

/* [fluid NAME] and [obstacle NAME]: sections that repeat, one per block, their keys stored per block. */
static bool is_block_key(const sph_key *k)
{
    return strcmp(k->section, "fluid") == 0 || strcmp(k->section, "obstacle") == 0;
}

/* One block's keys that differ from a default block of its kind; `always` keys are written anyway. */
static void write_block(FILE *f, const char *kind, const char *name, const void *blk, const void *ref,
                        const char *const always[2])
{
    char have[256], want[256];
    fprintf(f, *name ? "\n[%s %s]\n" : "\n[%s]\n", kind, name);
    for (int j = 0; j < sph_scene_key_count; j++) {
        const sph_key *k = &sph_scene_keys[j];
        if (strcmp(k->section, kind) != 0) continue;
        sph_scene_value_text(k, blk, have, sizeof have);
        sph_scene_value_text(k, ref, want, sizeof want);
        bool forced = strcmp(k->name, always[0]) == 0 || strcmp(k->name, always[1]) == 0;
        if (forced || strcmp(have, want) != 0) fprintf(f, "%s = %s\n", k->name, have);
    }
}

/* The first key of each section, in table order (a section may appear in several runs of the table). */
static bool first_of_section(int i)
{
    for (int j = 0; j < i; j++)
        if (strcmp(sph_scene_keys[j].section, sph_scene_keys[i].section) == 0) return false;
    return true;
}

sph_error_code sph_scene_write(const sph_scene_def *def, FILE *f, sph_error *err)
{
    if (strpbrk(def->name, "\n\r;#")) /* a scene file could not read it back */
        return sph_fail(err, SPH_ERR_RANGE, "scene name '%.60s' has a newline, ';' or '#': it cannot be written", def->name);
    sph_scene_def ref = sph_default_scene_def();
    sph_block_def ref_block;
    sph_obstacle_def ref_obstacle;
    memset(&ref_block, 0, sizeof ref_block);
    memset(&ref_obstacle, 0, sizeof ref_obstacle);
    sph_scene_block_defaults(&ref_block, "fluid");
    sph_scene_block_defaults(&ref_obstacle, "obstacle");
    char have[256], want[256];
    fprintf(f, "# written by sphlab: the keys that differ from their defaults (sphlab keys lists them all), and\n"
               "# those a scene states anyway: its dimension (and its name, if any), a block's min and max, an\n"
               "# obstacle's shape and slip\n");
    for (int i = 0; i < sph_scene_key_count; i++) {
        if (!first_of_section(i) || is_block_key(&sph_scene_keys[i])) continue;
        const char *section = sph_scene_keys[i].section;
        bool opened = false;
        for (int j = i; j < sph_scene_key_count; j++) {
            const sph_key *k = &sph_scene_keys[j];
            if (strcmp(k->section, section) != 0) continue;
            sph_scene_value_text(k, def, have, sizeof have);
            sph_scene_value_text(k, &ref, want, sizeof want);
            /* the dimension always (the defaults of a 2D and a 3D scene differ); the name when there is one */
            bool always = strcmp(section, "scene") == 0 &&
                          ((strcmp(k->name, "name") == 0 && def->name[0]) || strcmp(k->name, "dimension") == 0);
            if (!always && strcmp(have, want) == 0) continue;
            if (!opened) fprintf(f, "\n[%s]\n", section);
            opened = true;
            fprintf(f, "%s = %s\n", k->name, have);
        }
    }
    static const char *const fluid_always[2] = {"min", "max"};
    for (int b = 0; b < def->n_blocks; b++)
        write_block(f, "fluid", def->blocks[b].name, &def->blocks[b], &ref_block, fluid_always);
    static const char *const obstacle_always[2] = {"shape", "slip"};
    for (int o = 0; o < def->n_obstacles; o++)
        write_block(f, "obstacle", def->obstacles[o].name, &def->obstacles[o], &ref_obstacle, obstacle_always);
    if (fflush(f) != 0 || ferror(f)) return sph_fail(err, SPH_ERR_IO, "cannot write the scene");
    return SPH_ERR_OK;
}
