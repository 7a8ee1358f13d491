/* ARM semihosting (bkpt 0xAB) for output and exit under qemu: the bootloader and the test
 * application print through these, nothing else. */
#ifndef SEMIHOST_H
#define SEMIHOST_H

#include <stdint.h>

/** Print a NUL-terminated string on the host's stdout. */
void sh_puts(const char *s);

/** Print v as 0x%08X. */
void sh_puthex(uint32_t v);

/** Print v in decimal. */
void sh_putdec(uint32_t v);

/** End the simulation with exit code (SYS_EXIT_EXTENDED); does not return. */
void sh_exit(uint32_t code) __attribute__((noreturn));

#endif /* SEMIHOST_H */
