#include "sph_error.h"

#include <stdio.h>

static const char *const error_names[SPH_ERR_COUNT] = {
#define SPH_ERROR_NAME(id, text) text,
    SPH_ERRORS(SPH_ERROR_NAME)
#undef SPH_ERROR_NAME
};

const char *sph_error_name(sph_error_code code)
{
    return (unsigned)code < SPH_ERR_COUNT ? error_names[code] : "unknown error";
}

sph_error_code sph_fail(sph_error *err, sph_error_code code, const char *fmt, ...)
{
    if (err) {
        va_list ap;
        va_start(ap, fmt);
        err->code = code;
        vsnprintf(err->msg, sizeof err->msg, fmt, ap);
        va_end(ap);
    }
    return code;
}
