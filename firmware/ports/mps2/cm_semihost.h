/* ARM semihosting (bkpt 0xAB on M-profile) for output and exit under qemu
 * (-semihosting-config enable=on,target=native), shared by the bootloader, its test application
 * and the product image. Debug-only I/O: a real device has no host. */
#ifndef CM_SEMIHOST_H
#define CM_SEMIHOST_H

#include <stdint.h>

/** Write a NUL-terminated string to the host console (SYS_WRITE0), after the line buffer. */
void sh_puts(const char *s);

/** Write v in decimal to the host console. */
void sh_putdec(uint32_t v);

/** Write v as 0x and 8 hex digits to the host console. */
void sh_puthex(uint32_t v);

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

/** Stop the program: qemu exits with status code (SYS_EXIT_EXTENDED, after the line buffer).
 *  Does not return. */
void sh_exit(uint32_t code) __attribute__((noreturn));

#endif /* CM_SEMIHOST_H */
