/* The firmware's AES-128, AES-CMAC, SHA-256 and HMAC-SHA256 (firmware/security) on inputs read
 * from stdin, one a line, for tests/host/wire/test_firmware_crypto.py to compare with the
 * `cryptography` package and Python's hashlib/hmac:
 *     aes KEY BLOCK      -> the block encrypted, and again by the sliced job (3 rounds a call)
 *     cmac KEY MSG       -> the tag
 *     sha MSG            -> the digest, and again fed in pieces of 1, 7, 64 and 65 bytes
 *     hmac KEY MSG       -> the MAC
 * every field hex ("-" for no bytes), every answer one hex line. */
#include <stdio.h>
#include <string.h>

#include "sec_aes.h"
#include "sec_sha256.h"

#define MAX_BYTES 512u
#define LINE_MAX_CHARS (4u * MAX_BYTES + 32u)

static uint32_t from_hex(const char *hex, uint8_t *out)
{
    uint32_t n = 0u;
    if (strcmp(hex, "-") == 0) {
        return 0u;
    }
    for (; hex[0] != '\0' && hex[1] != '\0' && n < MAX_BYTES; hex += 2) {
        unsigned b = 0u;
        if (sscanf(hex, "%2x", &b) != 1) {
            break;
        }
        out[n++] = (uint8_t)b;
    }
    return n;
}

static void put_hex(const uint8_t *d, uint32_t n)
{
    for (uint32_t i = 0u; i < n; i++) {
        printf("%02x", d[i]);
    }
    printf("\n");
}

static void do_aes(const uint8_t *key, const uint8_t *block)
{
    sec_aes128_t a;
    uint8_t out[SEC_AES_BLOCK];
    sec_aes128_init(&a, key);
    sec_aes128_encrypt(&a, block, out);
    put_hex(out, SEC_AES_BLOCK);
    sec_aes128_job_t j;
    sec_aes128_job_begin(&j, &a, block);
    memset(out, 0, sizeof(out));
    for (int calls = 0; calls < 10; calls++) {
        uint32_t rounds = 3u;
        if (sec_aes128_job_run(&j, &a, &rounds, out)) {
            break;
        }
    }
    put_hex(out, SEC_AES_BLOCK);
}

static void do_sha(const uint8_t *msg, uint32_t len)
{
    uint8_t out[SEC_SHA256_LEN];
    sec_sha256(msg, len, out);
    put_hex(out, SEC_SHA256_LEN);
    static const uint32_t PIECES[] = {1u, 7u, 64u, 65u};
    sec_sha256_t s;
    sec_sha256_init(&s);
    uint32_t at = 0u;
    for (uint32_t k = 0u; at < len; k++) {
        uint32_t n = PIECES[k % 4u];
        n = (n > len - at) ? len - at : n;
        sec_sha256_update(&s, &msg[at], n);
        at += n;
    }
    sec_sha256_final(&s, out);
    put_hex(out, SEC_SHA256_LEN);
}

int main(void)
{
    static char line[LINE_MAX_CHARS];
    static char f1[LINE_MAX_CHARS], f2[LINE_MAX_CHARS], f3[LINE_MAX_CHARS];
    static uint8_t a[MAX_BYTES], b[MAX_BYTES];
    while (fgets(line, sizeof(line), stdin) != NULL) {
        f2[0] = f3[0] = '\0';
        if (sscanf(line, "%s %s %s", f1, f2, f3) < 2) {
            continue;
        }
        const uint32_t na = from_hex(f2, a);
        const uint32_t nb = (f3[0] != '\0') ? from_hex(f3, b) : 0u;
        if (strcmp(f1, "aes") == 0 && na == SEC_AES128_KEY_LEN && nb == SEC_AES_BLOCK) {
            do_aes(a, b);
        } else if (strcmp(f1, "cmac") == 0 && na == SEC_AES128_KEY_LEN) {
            sec_cmac_t c;
            uint8_t tag[SEC_AES_BLOCK];
            sec_cmac_init(&c, a);
            sec_cmac(&c, b, nb, tag);
            put_hex(tag, SEC_AES_BLOCK);
        } else if (strcmp(f1, "sha") == 0) {
            do_sha(a, na);
        } else if (strcmp(f1, "hmac") == 0) {
            uint8_t mac[SEC_SHA256_LEN];
            sec_hmac_sha256(a, na, b, nb, mac);
            put_hex(mac, SEC_SHA256_LEN);
        } else {
            printf("?\n");
        }
        fflush(stdout);
    }
    return 0;
}
