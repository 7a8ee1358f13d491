/* Semihosting calls: r0 = operation, r1 = argument, bkpt 0xAB. */
#include "cm_semihost.h"

#define SH_SYS_WRITE0 0x04u
#define SH_SYS_EXIT_EXTENDED 0x20u
#define SH_SYS_ELAPSED 0x30u
#define SH_SYS_TICKFREQ 0x31u
#define SH_ADP_APPLICATION_EXIT 0x20026u
#define SH_BUF_SIZE 1024u

static char sh_buf[SH_BUF_SIZE + 1u];
static uint32_t sh_len;

static uint32_t sh_call(uint32_t op, uint32_t arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register uint32_t r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
    return r0;
}

void sh_flush(void)
{
    if (sh_len > 0u) {
        sh_buf[sh_len] = '\0';
        (void)sh_call(SH_SYS_WRITE0, (uint32_t)(uintptr_t)sh_buf);
        sh_len = 0u;
    }
}

void sh_puts(const char *s)
{
    sh_flush();
    (void)sh_call(SH_SYS_WRITE0, (uint32_t)(uintptr_t)s);
}

static void sh_putc(char c)
{
    if (sh_len >= SH_BUF_SIZE) {
        sh_flush();
    }
    sh_buf[sh_len++] = c;
}

void sh_buf_str(const char *s)
{
    while (*s != '\0') {
        sh_putc(*s++);
    }
}

void sh_buf_u32(uint32_t v)
{
    char tmp[10];
    uint32_t n = 0u;
    do {
        tmp[n++] = (char)('0' + (v % 10u));
        v /= 10u;
    } while (v != 0u);
    while (n > 0u) {
        sh_putc(tmp[--n]);
    }
}

void sh_buf_hex32(uint32_t v)
{
    static const char digits[] = "0123456789abcdef";
    for (int shift = 28; shift >= 0; shift -= 4) {
        sh_putc(digits[(v >> (uint32_t)shift) & 0xFu]);
    }
}

void sh_putdec(uint32_t v)
{
    sh_buf_u32(v);
    sh_flush();
}

void sh_puthex(uint32_t v)
{
    sh_buf_str("0x");
    sh_buf_hex32(v);
    sh_flush();
}

void sh_exit(uint32_t code)
{
    sh_flush();
    const uint32_t block[2] = {SH_ADP_APPLICATION_EXIT, code};
    for (;;) {
        (void)sh_call(SH_SYS_EXIT_EXTENDED, (uint32_t)(uintptr_t)block);
    }
}

uint64_t sh_host_elapsed_us(void)
{
    static uint32_t ticks_per_us;
    if (ticks_per_us == 0u) {
        const uint32_t f = sh_call(SH_SYS_TICKFREQ, 0u);
        ticks_per_us = (f >= 1000000u && f != 0xFFFFFFFFu) ? f / 1000000u : 1u;
    }
    uint32_t block[2] = {0u, 0u};
    if (sh_call(SH_SYS_ELAPSED, (uint32_t)(uintptr_t)block) != 0u) {
        return 0u;
    }
    return (((uint64_t)block[1] << 32) | block[0]) / ticks_per_us;
}
