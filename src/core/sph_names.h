/* The nearest of a list of names to a misspelt one, for "did you mean"
 * hints (scene keys and sections here; commands in src/app/). */
#ifndef SPH_NAMES_H
#define SPH_NAMES_H

/* Edits (insertions, deletions, substitutions, swaps of neighbours) from a to b. */
int sph_edit_distance(const char *a, const char *b);
/* Whether b is near enough to a typed word a to be offered for it: within
 * 2 edits, or a third of a's length for long words. */
int sph_name_near(const char *a, const char *b);

#endif
