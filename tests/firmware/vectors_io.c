/* Test-only: see vectors_io.h. */
#include "vectors_io.h"

#include <stdio.h>

#ifndef FS_VECTORS_DIR
#error "FS_VECTORS_DIR must point at tests/vectors"
#endif

uint32_t tv_read(const char *name, uint8_t *buf, uint32_t cap)
{
    char path[512];
    snprintf(path, sizeof path, "%s/%s", FS_VECTORS_DIR, name);
    FILE *f = fopen(path, "rb");
    if (f == NULL) {
        return 0u;
    }
    const size_t n = fread(buf, 1, cap, f);
    const int bad = ferror(f);
    fclose(f);
    return bad ? 0u : (uint32_t)n;
}
