/* Test-only: read a file of tests/vectors (the golden skill images the Python package writes),
 * shared by the C tests of every module (library fs_test_vectors, tests/CMakeLists.txt). */
#ifndef VECTORS_IO_H
#define VECTORS_IO_H

#include <stdint.h>

/** Read tests/vectors/<name> into buf (at most cap bytes): the bytes read, 0 if it cannot be
 *  opened or read. */
uint32_t tv_read(const char *name, uint8_t *buf, uint32_t cap);

#endif /* VECTORS_IO_H */
