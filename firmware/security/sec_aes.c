/* AES-128 (FIPS 197) encryption and AES-CMAC (SP 800-38B): see sec_aes.h. */
#include "sec_aes.h"

#include <string.h>

#include "sec_sha256.h"

/* TE0[x] = S[x] * (02, 01, 01, 03): SubBytes and MixColumns of one byte, the other three columns'
 * tables are its rotations; SBOX the S-box (last round, key expansion). */
static const uint32_t TE0[256] = {
    0xc66363a5u, 0xf87c7c84u, 0xee777799u, 0xf67b7b8du, 0xfff2f20du, 0xd66b6bbdu, 0xde6f6fb1u,
    0x91c5c554u, 0x60303050u, 0x02010103u, 0xce6767a9u, 0x562b2b7du, 0xe7fefe19u, 0xb5d7d762u,
    0x4dababe6u, 0xec76769au, 0x8fcaca45u, 0x1f82829du, 0x89c9c940u, 0xfa7d7d87u, 0xeffafa15u,
    0xb25959ebu, 0x8e4747c9u, 0xfbf0f00bu, 0x41adadecu, 0xb3d4d467u, 0x5fa2a2fdu, 0x45afafeau,
    0x239c9cbfu, 0x53a4a4f7u, 0xe4727296u, 0x9bc0c05bu, 0x75b7b7c2u, 0xe1fdfd1cu, 0x3d9393aeu,
    0x4c26266au, 0x6c36365au, 0x7e3f3f41u, 0xf5f7f702u, 0x83cccc4fu, 0x6834345cu, 0x51a5a5f4u,
    0xd1e5e534u, 0xf9f1f108u, 0xe2717193u, 0xabd8d873u, 0x62313153u, 0x2a15153fu, 0x0804040cu,
    0x95c7c752u, 0x46232365u, 0x9dc3c35eu, 0x30181828u, 0x379696a1u, 0x0a05050fu, 0x2f9a9ab5u,
    0x0e070709u, 0x24121236u, 0x1b80809bu, 0xdfe2e23du, 0xcdebeb26u, 0x4e272769u, 0x7fb2b2cdu,
    0xea75759fu, 0x1209091bu, 0x1d83839eu, 0x582c2c74u, 0x341a1a2eu, 0x361b1b2du, 0xdc6e6eb2u,
    0xb45a5aeeu, 0x5ba0a0fbu, 0xa45252f6u, 0x763b3b4du, 0xb7d6d661u, 0x7db3b3ceu, 0x5229297bu,
    0xdde3e33eu, 0x5e2f2f71u, 0x13848497u, 0xa65353f5u, 0xb9d1d168u, 0x00000000u, 0xc1eded2cu,
    0x40202060u, 0xe3fcfc1fu, 0x79b1b1c8u, 0xb65b5bedu, 0xd46a6abeu, 0x8dcbcb46u, 0x67bebed9u,
    0x7239394bu, 0x944a4adeu, 0x984c4cd4u, 0xb05858e8u, 0x85cfcf4au, 0xbbd0d06bu, 0xc5efef2au,
    0x4faaaae5u, 0xedfbfb16u, 0x864343c5u, 0x9a4d4dd7u, 0x66333355u, 0x11858594u, 0x8a4545cfu,
    0xe9f9f910u, 0x04020206u, 0xfe7f7f81u, 0xa05050f0u, 0x783c3c44u, 0x259f9fbau, 0x4ba8a8e3u,
    0xa25151f3u, 0x5da3a3feu, 0x804040c0u, 0x058f8f8au, 0x3f9292adu, 0x219d9dbcu, 0x70383848u,
    0xf1f5f504u, 0x63bcbcdfu, 0x77b6b6c1u, 0xafdada75u, 0x42212163u, 0x20101030u, 0xe5ffff1au,
    0xfdf3f30eu, 0xbfd2d26du, 0x81cdcd4cu, 0x180c0c14u, 0x26131335u, 0xc3ecec2fu, 0xbe5f5fe1u,
    0x359797a2u, 0x884444ccu, 0x2e171739u, 0x93c4c457u, 0x55a7a7f2u, 0xfc7e7e82u, 0x7a3d3d47u,
    0xc86464acu, 0xba5d5de7u, 0x3219192bu, 0xe6737395u, 0xc06060a0u, 0x19818198u, 0x9e4f4fd1u,
    0xa3dcdc7fu, 0x44222266u, 0x542a2a7eu, 0x3b9090abu, 0x0b888883u, 0x8c4646cau, 0xc7eeee29u,
    0x6bb8b8d3u, 0x2814143cu, 0xa7dede79u, 0xbc5e5ee2u, 0x160b0b1du, 0xaddbdb76u, 0xdbe0e03bu,
    0x64323256u, 0x743a3a4eu, 0x140a0a1eu, 0x924949dbu, 0x0c06060au, 0x4824246cu, 0xb85c5ce4u,
    0x9fc2c25du, 0xbdd3d36eu, 0x43acacefu, 0xc46262a6u, 0x399191a8u, 0x319595a4u, 0xd3e4e437u,
    0xf279798bu, 0xd5e7e732u, 0x8bc8c843u, 0x6e373759u, 0xda6d6db7u, 0x018d8d8cu, 0xb1d5d564u,
    0x9c4e4ed2u, 0x49a9a9e0u, 0xd86c6cb4u, 0xac5656fau, 0xf3f4f407u, 0xcfeaea25u, 0xca6565afu,
    0xf47a7a8eu, 0x47aeaee9u, 0x10080818u, 0x6fbabad5u, 0xf0787888u, 0x4a25256fu, 0x5c2e2e72u,
    0x381c1c24u, 0x57a6a6f1u, 0x73b4b4c7u, 0x97c6c651u, 0xcbe8e823u, 0xa1dddd7cu, 0xe874749cu,
    0x3e1f1f21u, 0x964b4bddu, 0x61bdbddcu, 0x0d8b8b86u, 0x0f8a8a85u, 0xe0707090u, 0x7c3e3e42u,
    0x71b5b5c4u, 0xcc6666aau, 0x904848d8u, 0x06030305u, 0xf7f6f601u, 0x1c0e0e12u, 0xc26161a3u,
    0x6a35355fu, 0xae5757f9u, 0x69b9b9d0u, 0x17868691u, 0x99c1c158u, 0x3a1d1d27u, 0x279e9eb9u,
    0xd9e1e138u, 0xebf8f813u, 0x2b9898b3u, 0x22111133u, 0xd26969bbu, 0xa9d9d970u, 0x078e8e89u,
    0x339494a7u, 0x2d9b9bb6u, 0x3c1e1e22u, 0x15878792u, 0xc9e9e920u, 0x87cece49u, 0xaa5555ffu,
    0x50282878u, 0xa5dfdf7au, 0x038c8c8fu, 0x59a1a1f8u, 0x09898980u, 0x1a0d0d17u, 0x65bfbfdau,
    0xd7e6e631u, 0x844242c6u, 0xd06868b8u, 0x824141c3u, 0x299999b0u, 0x5a2d2d77u, 0x1e0f0f11u,
    0x7bb0b0cbu, 0xa85454fcu, 0x6dbbbbd6u, 0x2c16163au,
};

static const uint8_t SBOX[256] = {
    0x63u, 0x7cu, 0x77u, 0x7bu, 0xf2u, 0x6bu, 0x6fu, 0xc5u, 0x30u, 0x01u, 0x67u, 0x2bu, 0xfeu,
    0xd7u, 0xabu, 0x76u, 0xcau, 0x82u, 0xc9u, 0x7du, 0xfau, 0x59u, 0x47u, 0xf0u, 0xadu, 0xd4u,
    0xa2u, 0xafu, 0x9cu, 0xa4u, 0x72u, 0xc0u, 0xb7u, 0xfdu, 0x93u, 0x26u, 0x36u, 0x3fu, 0xf7u,
    0xccu, 0x34u, 0xa5u, 0xe5u, 0xf1u, 0x71u, 0xd8u, 0x31u, 0x15u, 0x04u, 0xc7u, 0x23u, 0xc3u,
    0x18u, 0x96u, 0x05u, 0x9au, 0x07u, 0x12u, 0x80u, 0xe2u, 0xebu, 0x27u, 0xb2u, 0x75u, 0x09u,
    0x83u, 0x2cu, 0x1au, 0x1bu, 0x6eu, 0x5au, 0xa0u, 0x52u, 0x3bu, 0xd6u, 0xb3u, 0x29u, 0xe3u,
    0x2fu, 0x84u, 0x53u, 0xd1u, 0x00u, 0xedu, 0x20u, 0xfcu, 0xb1u, 0x5bu, 0x6au, 0xcbu, 0xbeu,
    0x39u, 0x4au, 0x4cu, 0x58u, 0xcfu, 0xd0u, 0xefu, 0xaau, 0xfbu, 0x43u, 0x4du, 0x33u, 0x85u,
    0x45u, 0xf9u, 0x02u, 0x7fu, 0x50u, 0x3cu, 0x9fu, 0xa8u, 0x51u, 0xa3u, 0x40u, 0x8fu, 0x92u,
    0x9du, 0x38u, 0xf5u, 0xbcu, 0xb6u, 0xdau, 0x21u, 0x10u, 0xffu, 0xf3u, 0xd2u, 0xcdu, 0x0cu,
    0x13u, 0xecu, 0x5fu, 0x97u, 0x44u, 0x17u, 0xc4u, 0xa7u, 0x7eu, 0x3du, 0x64u, 0x5du, 0x19u,
    0x73u, 0x60u, 0x81u, 0x4fu, 0xdcu, 0x22u, 0x2au, 0x90u, 0x88u, 0x46u, 0xeeu, 0xb8u, 0x14u,
    0xdeu, 0x5eu, 0x0bu, 0xdbu, 0xe0u, 0x32u, 0x3au, 0x0au, 0x49u, 0x06u, 0x24u, 0x5cu, 0xc2u,
    0xd3u, 0xacu, 0x62u, 0x91u, 0x95u, 0xe4u, 0x79u, 0xe7u, 0xc8u, 0x37u, 0x6du, 0x8du, 0xd5u,
    0x4eu, 0xa9u, 0x6cu, 0x56u, 0xf4u, 0xeau, 0x65u, 0x7au, 0xaeu, 0x08u, 0xbau, 0x78u, 0x25u,
    0x2eu, 0x1cu, 0xa6u, 0xb4u, 0xc6u, 0xe8u, 0xddu, 0x74u, 0x1fu, 0x4bu, 0xbdu, 0x8bu, 0x8au,
    0x70u, 0x3eu, 0xb5u, 0x66u, 0x48u, 0x03u, 0xf6u, 0x0eu, 0x61u, 0x35u, 0x57u, 0xb9u, 0x86u,
    0xc1u, 0x1du, 0x9eu, 0xe1u, 0xf8u, 0x98u, 0x11u, 0x69u, 0xd9u, 0x8eu, 0x94u, 0x9bu, 0x1eu,
    0x87u, 0xe9u, 0xceu, 0x55u, 0x28u, 0xdfu, 0x8cu, 0xa1u, 0x89u, 0x0du, 0xbfu, 0xe6u, 0x42u,
    0x68u, 0x41u, 0x99u, 0x2du, 0x0fu, 0xb0u, 0x54u, 0xbbu, 0x16u,
};

static uint32_t ror(uint32_t x, uint32_t n)
{
    return (x >> n) | (x << (32u - n));
}

static uint32_t get_be32(const uint8_t *p)
{
    return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | (uint32_t)p[3];
}

static void put_be32(uint8_t *p, uint32_t v)
{
    p[0] = (uint8_t)(v >> 24);
    p[1] = (uint8_t)(v >> 16);
    p[2] = (uint8_t)(v >> 8);
    p[3] = (uint8_t)v;
}

static uint32_t sub_word(uint32_t w)
{
    return ((uint32_t)SBOX[w >> 24] << 24) | ((uint32_t)SBOX[(w >> 16) & 0xFFu] << 16) |
           ((uint32_t)SBOX[(w >> 8) & 0xFFu] << 8) | (uint32_t)SBOX[w & 0xFFu];
}

void sec_aes128_init(sec_aes128_t *a, const uint8_t key[SEC_AES128_KEY_LEN])
{
    static const uint8_t rcon[10] = {0x01u, 0x02u, 0x04u, 0x08u, 0x10u,
                                     0x20u, 0x40u, 0x80u, 0x1Bu, 0x36u};
    for (uint32_t i = 0u; i < 4u; i++) {
        a->rk[i] = get_be32(&key[4u * i]);
    }
    for (uint32_t i = 4u; i < 44u; i++) {
        uint32_t t = a->rk[i - 1u];
        if ((i & 3u) == 0u) {
            t = sub_word((t << 8) | (t >> 24)) ^ ((uint32_t)rcon[i / 4u - 1u] << 24);
        }
        a->rk[i] = a->rk[i - 4u] ^ t;
    }
}

/* One column of a middle round: SubBytes, ShiftRows, MixColumns of columns a, b, c, d. */
static uint32_t round_col(uint32_t a, uint32_t b, uint32_t c, uint32_t d, uint32_t k)
{
    return TE0[a >> 24] ^ ror(TE0[(b >> 16) & 0xFFu], 8u) ^ ror(TE0[(c >> 8) & 0xFFu], 16u) ^
           ror(TE0[d & 0xFFu], 24u) ^ k;
}

/* One column of the last round (no MixColumns). */
static uint32_t last_col(uint32_t a, uint32_t b, uint32_t c, uint32_t d, uint32_t k)
{
    return (((uint32_t)SBOX[a >> 24] << 24) | ((uint32_t)SBOX[(b >> 16) & 0xFFu] << 16) |
            ((uint32_t)SBOX[(c >> 8) & 0xFFu] << 8) | (uint32_t)SBOX[d & 0xFFu]) ^
           k;
}

/* Rounds from+1 .. to (1..10) of the cipher on state st; round 10 has no MixColumns. */
static void aes_rounds(const uint32_t rk_all[44], uint32_t st[4], uint32_t from, uint32_t to)
{
    uint32_t s0 = st[0], s1 = st[1], s2 = st[2], s3 = st[3];
    const uint32_t middle_end = (to < 10u) ? to : 9u;
    for (uint32_t r = from + 1u; r <= middle_end; r++) {
        const uint32_t *rk = &rk_all[4u * r];
        const uint32_t t0 = round_col(s0, s1, s2, s3, rk[0]);
        const uint32_t t1 = round_col(s1, s2, s3, s0, rk[1]);
        const uint32_t t2 = round_col(s2, s3, s0, s1, rk[2]);
        const uint32_t t3 = round_col(s3, s0, s1, s2, rk[3]);
        s0 = t0;
        s1 = t1;
        s2 = t2;
        s3 = t3;
    }
    if (to == 10u) {
        const uint32_t *rk = &rk_all[40];
        const uint32_t t0 = last_col(s0, s1, s2, s3, rk[0]);
        const uint32_t t1 = last_col(s1, s2, s3, s0, rk[1]);
        const uint32_t t2 = last_col(s2, s3, s0, s1, rk[2]);
        const uint32_t t3 = last_col(s3, s0, s1, s2, rk[3]);
        s0 = t0;
        s1 = t1;
        s2 = t2;
        s3 = t3;
    }
    st[0] = s0;
    st[1] = s1;
    st[2] = s2;
    st[3] = s3;
}

void sec_aes128_job_begin(sec_aes128_job_t *j, const sec_aes128_t *a,
                          const uint8_t in[SEC_AES_BLOCK])
{
    for (uint32_t i = 0u; i < 4u; i++) {
        j->s[i] = get_be32(&in[4u * i]) ^ a->rk[i];
    }
    j->round = 0u;
}

bool sec_aes128_job_run(sec_aes128_job_t *j, const sec_aes128_t *a, uint32_t *rounds,
                        uint8_t out[SEC_AES_BLOCK])
{
    const uint32_t left = 10u - j->round;
    const uint32_t n = (*rounds < left) ? *rounds : left;
    aes_rounds(a->rk, j->s, j->round, j->round + n);
    j->round += n;
    *rounds -= n;
    if (j->round < 10u) {
        return false;
    }
    for (uint32_t i = 0u; i < 4u; i++) {
        put_be32(&out[4u * i], j->s[i]);
    }
    return true;
}

void sec_aes128_encrypt(const sec_aes128_t *a, const uint8_t in[SEC_AES_BLOCK],
                        uint8_t out[SEC_AES_BLOCK])
{
    sec_aes128_job_t j;
    uint32_t rounds = 10u;
    sec_aes128_job_begin(&j, a, in);
    (void)sec_aes128_job_run(&j, a, &rounds, out);
}

/* out = in << 1 in GF(2^128), reduced by R128 = 0x87 (SP 800-38B 6.1), without a branch: the
 * block as four big-endian words. */
static void dbl(const uint8_t in[SEC_AES_BLOCK], uint8_t out[SEC_AES_BLOCK])
{
    uint32_t w[4];
    for (uint32_t i = 0u; i < 4u; i++) {
        w[i] = get_be32(&in[4u * i]);
    }
    const uint32_t msb = w[0] >> 31;
    for (uint32_t i = 0u; i < 3u; i++) {
        put_be32(&out[4u * i], (w[i] << 1) | (w[i + 1u] >> 31));
    }
    put_be32(&out[12], (w[3] << 1) ^ (0x87u & (0u - msb)));
}

void sec_cmac_init(sec_cmac_t *c, const uint8_t key[SEC_AES128_KEY_LEN])
{
    sec_cmac_init_schedule(c, key);
    sec_cmac_init_subkeys(c);
}

void sec_cmac_init_schedule(sec_cmac_t *c, const uint8_t key[SEC_AES128_KEY_LEN])
{
    sec_aes128_init(&c->aes, key);
}

void sec_cmac_init_subkeys(sec_cmac_t *c)
{
    uint8_t l[SEC_AES_BLOCK];
    memset(l, 0, sizeof l);
    sec_aes128_encrypt(&c->aes, l, l);
    dbl(l, c->k1);
    dbl(c->k1, c->k2);
    sec_wipe(l, sizeof l);
}

/* dst ^= a over one block, a word at a time (memcpy: any alignment, no aliasing). */
static void xor_block(uint8_t dst[SEC_AES_BLOCK], const uint8_t a[SEC_AES_BLOCK])
{
    uint32_t d[4], x[4];
    memcpy(d, dst, sizeof d);
    memcpy(x, a, sizeof x);
    for (uint32_t i = 0u; i < 4u; i++) {
        d[i] ^= x[i];
    }
    memcpy(dst, d, sizeof d);
}

void sec_cmac_one_block(const sec_cmac_t *c, const uint8_t *msg, uint32_t len,
                        uint8_t block[SEC_AES_BLOCK])
{
    memset(block, 0, SEC_AES_BLOCK);
    const uint32_t n = (len < SEC_AES_BLOCK) ? len : SEC_AES_BLOCK;
    if (n != 0u) {
        memcpy(block, msg, n);
    }
    if (n < SEC_AES_BLOCK) {
        block[n] = 0x80u; /* padding 10*: only an incomplete last block */
    }
    xor_block(block, (n == SEC_AES_BLOCK) ? c->k1 : c->k2);
}

void sec_cmac(const sec_cmac_t *c, const uint8_t *msg, uint32_t len, uint8_t out[SEC_AES_BLOCK])
{
    uint8_t x[SEC_AES_BLOCK];
    memset(x, 0, sizeof x);
    uint32_t pos = 0u;
    while (len - pos > SEC_AES_BLOCK) { /* every block but the last */
        xor_block(x, &msg[pos]);
        sec_aes128_encrypt(&c->aes, x, x);
        pos += SEC_AES_BLOCK;
    }
    uint8_t last[SEC_AES_BLOCK];
    sec_cmac_one_block(c, &msg[pos], len - pos, last);
    xor_block(x, last);
    sec_aes128_encrypt(&c->aes, x, out);
    sec_wipe(x, sizeof x);
}
