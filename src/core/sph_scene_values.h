/* Shared by the scene's parser (sph_scene.c) and its values and defaults
 * (sph_scene_values.c): the table of named-section groups and the setting of
 * one key's value from its text. Only the scene's own files include it. */
#ifndef SPH_SCENE_VALUES_H
#define SPH_SCENE_VALUES_H

#include <stddef.h>

#include "sph_scene.h"

/* Sections that name a record of a list: [fluid NAME] blocks and
 * [obstacle NAME]s. Both are parsed by the same code through this table. */
typedef struct sph_scene_group {
    const char *kind, *noun, *example; /* "fluid", "fluid block", "[fluid pool]" */
    size_t size, name_off, line_off, origin_off, items_off, count_off;
    int max, name_max;
} sph_scene_group;
extern const sph_scene_group sph_scene_groups[]; /* [0]: fluid, [1]: obstacle */

/* The group a section header names ("fluid", "fluid pool", "obstacle.rock"), or NULL. */
const sph_scene_group *sph_scene_section_group(const char *section);

/* Where a value was given, for the messages. */
typedef struct sph_scene_where {
    const char *file;
    int line; /* > 0: a file line; -1: --set */
    const char *section;
} sph_scene_where;

/* "file:line", or "--set". */
void sph_scene_where_text(const sph_scene_where *w, char *out, size_t n);

/* Parses one value into the field at `base + k->offset`; sets *ncomp for vectors. */
sph_error_code sph_scene_value_set(const sph_key *k, void *base, const char *value, const sph_scene_where *w,
                                   int *ncomp, sph_error *err);

#endif
