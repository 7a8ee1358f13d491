/* ARM semihosting (bkpt 0xAB on M-profile) for output and exit under qemu
 * (-semihosting-config enable=on,target=native). Debug-only I/O: a real device has no host. */
#ifndef CM_SEMIHOST_H
#define CM_SEMIHOST_H

#include <stdint.h>

/** Write a NUL-terminated string to the host console (SYS_WRITE0). */
void sh_puts(const char *s);

/** Append text to the line buffer, flushed by sh_flush or when full. */
void sh_buf_str(const char *s);

/** Append an unsigned decimal number to the line buffer. */
void sh_buf_u32(uint32_t v);

/** Append 8 lowercase hex digits to the line buffer. */
void sh_buf_hex32(uint32_t v);

/** Write out the line buffer. */
void sh_flush(void);

/** Host time elapsed since the emulator started, in microseconds (SYS_ELAPSED / SYS_TICKFREQ);
 *  0 if the host does not provide it. */
uint64_t sh_host_elapsed_us(void);

/** Stop the program: qemu exits with status 0 (ok != 0) or 1. Does not return. */
void sh_exit(int ok) __attribute__((noreturn));

#endif /* CM_SEMIHOST_H */
