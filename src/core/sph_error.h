/* Errors: one X-macro list gives the codes and their names together. */
#ifndef SPH_ERROR_H
#define SPH_ERROR_H

#include <stdarg.h>

#define SPH_ERRORS(X)                                                   \
    X(OK, "ok")                                                         \
    X(IO, "cannot read or write a file")                                \
    X(SYNTAX, "syntax error")                                           \
    X(UNKNOWN_SECTION, "unknown section")                               \
    X(UNKNOWN_KEY, "unknown key")                                       \
    X(DUPLICATE_KEY, "duplicate key")                                   \
    X(PARSE, "value does not parse")                                    \
    X(RANGE, "value out of range")                                      \
    X(SCENE, "inconsistent scene")                                      \
    X(MEMORY, "out of memory")                                          \
    X(USAGE, "bad command line")

typedef enum sph_error_code {
#define SPH_ERROR_ENUM(id, text) SPH_ERR_##id,
    SPH_ERRORS(SPH_ERROR_ENUM)
#undef SPH_ERROR_ENUM
    SPH_ERR_COUNT
} sph_error_code;

/* A failed call fills one of these; msg is a whole sentence for the user,
 * already naming the file, line, key and accepted range where they apply. */
typedef struct sph_error {
    sph_error_code code;
    char msg[768];
} sph_error;

const char *sph_error_name(sph_error_code code);

/* Sets err (if not NULL) and returns code, so callers can `return sph_fail(...)`. */
sph_error_code sph_fail(sph_error *err, sph_error_code code, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));

#endif
