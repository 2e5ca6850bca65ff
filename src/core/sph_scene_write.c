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

static bool is_fluid_key(const sph_key *k)
{
    return strcmp(k->section, "fluid") == 0;
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
    sph_error lerr = {0};
    /* a block of default values: a [fluid] section that sets one key to its default */
    char block[128] = "";
    for (int i = 0; i < sph_scene_key_count && !*block; i++)
        if (is_fluid_key(&sph_scene_keys[i]))
            snprintf(block, sizeof block, "[fluid]\n%s = %s\n", sph_scene_keys[i].name, sph_scene_keys[i].def);
    if (sph_scene_load_string(block, "defaults", &ref, &lerr) != SPH_ERR_OK || ref.n_blocks != 1)
        return sph_fail(err, SPH_ERR_SCENE, "cannot make the default fluid block: %s", lerr.msg);
    char have[256], want[256];
    fprintf(f, "# written by sphlab: the keys that differ from their defaults (sphlab keys lists them all)\n");
    for (int i = 0; i < sph_scene_key_count; i++) {
        if (!first_of_section(i) || is_fluid_key(&sph_scene_keys[i])) continue;
        const char *section = sph_scene_keys[i].section;
        bool opened = false;
        for (int j = i; j < sph_scene_key_count; j++) {
            const sph_key *k = &sph_scene_keys[j];
            if (strcmp(k->section, section) != 0) continue;
            sph_scene_value_text(k, def, have, sizeof have);
            sph_scene_value_text(k, &ref, want, sizeof want);
            bool always = strcmp(section, "scene") == 0 && (strcmp(k->name, "name") == 0 || strcmp(k->name, "dimension") == 0);
            if (!always && strcmp(have, want) == 0) continue;
            if (!opened) fprintf(f, "\n[%s]\n", section);
            opened = true;
            fprintf(f, "%s = %s\n", k->name, have);
        }
    }
    for (int b = 0; b < def->n_blocks; b++) {
        const sph_block_def *blk = &def->blocks[b];
        fprintf(f, *blk->name ? "\n[fluid %s]\n" : "\n[fluid]\n", blk->name);
        for (int j = 0; j < sph_scene_key_count; j++) {
            const sph_key *k = &sph_scene_keys[j];
            if (!is_fluid_key(k)) continue;
            sph_scene_value_text(k, blk, have, sizeof have);
            sph_scene_value_text(k, &ref.blocks[0], want, sizeof want);
            bool always = strcmp(k->name, "min") == 0 || strcmp(k->name, "max") == 0;
            if (always || strcmp(have, want) != 0) fprintf(f, "%s = %s\n", k->name, have);
        }
    }
    if (fflush(f) != 0 || ferror(f)) return sph_fail(err, SPH_ERR_IO, "cannot write the scene");
    return SPH_ERR_OK;
}
