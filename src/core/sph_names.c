/* Nearest names for "did you mean" hints (sph_names.h). */
#include "sph_names.h"

#include <string.h>

int sph_edit_distance(const char *a, const char *b)
{
    /* optimal string alignment over the first 63 characters */
    enum { M = 64 };
    int d[M][M];
    size_t na = strlen(a), nb = strlen(b);
    if (na >= M) na = M - 1;
    if (nb >= M) nb = M - 1;
    for (size_t i = 0; i <= na; i++) d[i][0] = (int)i;
    for (size_t j = 0; j <= nb; j++) d[0][j] = (int)j;
    for (size_t i = 1; i <= na; i++)
        for (size_t j = 1; j <= nb; j++) {
            int best = d[i - 1][j - 1] + (a[i - 1] != b[j - 1]);
            if (d[i - 1][j] + 1 < best) best = d[i - 1][j] + 1;
            if (d[i][j - 1] + 1 < best) best = d[i][j - 1] + 1;
            if (i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] && d[i - 2][j - 2] + 1 < best)
                best = d[i - 2][j - 2] + 1;
            d[i][j] = best;
        }
    return d[na][nb];
}

int sph_name_near(const char *a, const char *b)
{
    size_t na = strlen(a);
    int limit = na / 3 > 2 ? (int)(na / 3) : 2;
    return sph_edit_distance(a, b) <= limit;
}
