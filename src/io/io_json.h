/* JSON outputs through cJSON (Debian's libcjson): build a tree with cJSON's
 * own functions, then print it here, or save it through the atomic writer.
 * The layout is fixed: two spaces an indentation level, "key": value, arrays
 * of numbers or strings on one line; cJSON escapes strings and writes
 * numbers (a NaN or an infinity becomes null). */
#ifndef SPH_IO_JSON_H
#define SPH_IO_JSON_H

#include <stdbool.h>
#include <stddef.h>
#include <stdio.h>

#include <cjson/cJSON.h>

/* Prints V at indentation DEPTH (its first line not indented, no final
 * newline); false if the stream has an error or cJSON runs out of memory. */
bool sph_json_fput(FILE *f, const cJSON *v, int depth);
/* PATH holds ROOT and a newline, written through the atomic writer. */
bool sph_json_save(const char *path, const cJSON *root, char *err, size_t n);
/* V rounded to DIGITS significant digits, for a number cJSON then prints short. */
double sph_json_round(double v, int digits);
/* cJSON_AddNumberToObject with V rounded to DIGITS significant digits; false
 * (the tree unchanged) when out of memory. */
bool sph_json_add_num(cJSON *obj, const char *key, double v, int digits);

#endif
