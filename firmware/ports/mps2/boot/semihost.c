/* ARM semihosting calls (semihost.h). */
#include "semihost.h"

static uint32_t sh_call(uint32_t op, const void *arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register const void *r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void sh_puts(const char *s)
{
    (void)sh_call(0x04u, s); /* SYS_WRITE0 */
}

void sh_puthex(uint32_t v)
{
    char b[11] = "0x";
    for (int i = 0; i < 8; i++) {
        const uint32_t d = (v >> (28 - 4 * i)) & 0xFu;
        b[2 + i] = (char)(d < 10u ? '0' + d : 'A' + d - 10u);
    }
    b[10] = '\0';
    sh_puts(b);
}

void sh_putdec(uint32_t v)
{
    char b[11];
    int i = 10;
    b[i] = '\0';
    do {
        b[--i] = (char)('0' + v % 10u);
        v /= 10u;
    } while (v != 0u && i > 0);
    sh_puts(&b[i]);
}

void sh_exit(uint32_t code)
{
    const uint32_t block[2] = {0x20026u, code}; /* ADP_Stopped_ApplicationExit, code */
    for (;;) {
        (void)sh_call(0x20u, block); /* SYS_EXIT_EXTENDED */
    }
}
