/* The registry of particle fields (sph_fields.h) as a table, and the names of
 * field masks. */
#include "sph_fields.h"

#include <stdio.h>
#include <string.h>

#define SPH_PASS_NONE SPH_PASS_COUNT
#define SPH_COMPS_1 false
#define SPH_COMPS_V true

const sph_field_info sph_field_infos[SPH_FIELD_COUNT] = {
#define SPH_FIELD_ROW(ID, name_, comps, unit_, unit2_, kind_, made_by_, check_, colour_, label_, about_)                        \
    [SPH_FIELD_##ID] = {.id = #ID,                                                                                 \
                        .name = #name_,                                                                            \
                        .unit = unit_,                                                                             \
                        .unit2 = unit2_,                                                                           \
                        .label = label_,                                                                             \
                        .about = about_,                                                                           \
                        .colour = colour_,                                                                         \
                        .vector = SPH_COMPS_##comps,                                                               \
                        .kind = SPH_KIND_##kind_,                                                                  \
                        .made_by = SPH_PASS_##made_by_,                                                            \
                        .check = SPH_CHECK_##check_},
    SPH_FIELDS(SPH_FIELD_ROW)
#undef SPH_FIELD_ROW
};

const char *const sph_pass_group_names[SPH_GROUP_COUNT] = {
#define SPH_GROUP_NAME(id, name) name,
    SPH_PASS_GROUPS(SPH_GROUP_NAME)
#undef SPH_GROUP_NAME
};

bool sph_field_allocated(int f, const sph_scene_def *def, const bool in_pipeline[SPH_PASS_COUNT])
{
    const sph_field_info *info = &sph_field_infos[f];
    if (info->made_by != SPH_PASS_COUNT && !in_pipeline[info->made_by]) return false;
    if (f == SPH_FIELD_POS_R) return def->position_sum == SPH_POSSUM_COMPENSATED;
    return true;
}

const char *sph_field_unit(int f, int dim)
{
    return dim == 2 ? sph_field_infos[f].unit2 : sph_field_infos[f].unit;
}

int sph_field_find(const char *name)
{
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if (strcmp(name, sph_field_infos[f].name) == 0) return f;
    return -1;
}

void sph_mask_names(sph_mask m, char *out, int n)
{
    static const struct {
        sph_mask bit;
        const char *name;
    } resources[] = {
        {SPH_RES_ID, "id"},
        {SPH_RES_ENTRIES, "entries"},
        {SPH_RES_START, "start"},
        {SPH_RES_LISTS, "nbr_start nbr"},
    };
    int used = 0;
    if (n <= 0) return;
    out[0] = '\0';
    for (int f = 0; f < SPH_FIELD_COUNT; f++)
        if (m & SPH_FIELD_BIT(f)) {
            int k = snprintf(out + used, (size_t)(n - used), "%s%s", used ? " " : "", sph_field_infos[f].name);
            if (k < 0 || k >= n - used) return;
            used += k;
        }
    for (size_t r = 0; r < sizeof resources / sizeof resources[0]; r++)
        if (m & resources[r].bit) {
            int k = snprintf(out + used, (size_t)(n - used), "%s%s", used ? " " : "", resources[r].name);
            if (k < 0 || k >= n - used) return;
            used += k;
        }
}
