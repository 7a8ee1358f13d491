/* SHA-256 (FIPS 180-4 section 6.2) and HMAC-SHA256 (FIPS 198-1): see sec_sha256.h. */
#include "sec_sha256.h"

#include <stddef.h>
#include <string.h>

static const uint32_t K256[64] = {
    0x428a2f98u, 0x71374491u, 0xb5c0fbcfu, 0xe9b5dba5u, 0x3956c25bu, 0x59f111f1u, 0x923f82a4u,
    0xab1c5ed5u, 0xd807aa98u, 0x12835b01u, 0x243185beu, 0x550c7dc3u, 0x72be5d74u, 0x80deb1feu,
    0x9bdc06a7u, 0xc19bf174u, 0xe49b69c1u, 0xefbe4786u, 0x0fc19dc6u, 0x240ca1ccu, 0x2de92c6fu,
    0x4a7484aau, 0x5cb0a9dcu, 0x76f988dau, 0x983e5152u, 0xa831c66du, 0xb00327c8u, 0xbf597fc7u,
    0xc6e00bf3u, 0xd5a79147u, 0x06ca6351u, 0x14292967u, 0x27b70a85u, 0x2e1b2138u, 0x4d2c6dfcu,
    0x53380d13u, 0x650a7354u, 0x766a0abbu, 0x81c2c92eu, 0x92722c85u, 0xa2bfe8a1u, 0xa81a664bu,
    0xc24b8b70u, 0xc76c51a3u, 0xd192e819u, 0xd6990624u, 0xf40e3585u, 0x106aa070u, 0x19a4c116u,
    0x1e376c08u, 0x2748774cu, 0x34b0bcb5u, 0x391c0cb3u, 0x4ed8aa4au, 0x5b9cca4fu, 0x682e6ff3u,
    0x748f82eeu, 0x78a5636fu, 0x84c87814u, 0x8cc70208u, 0x90befffau, 0xa4506cebu, 0xbef9a3f7u,
    0xc67178f2u,
};

static uint32_t rotr(uint32_t x, uint32_t n)
{
    return (x >> n) | (x << (32u - n));
}

/* The big-endian word at p. GCC and Clang on a little-endian target: one load and a byte
 * reverse (the byte-wise form costs ~13 instructions a word on the Cortex-M4). */
static uint32_t be32_load(const uint8_t *p)
{
#if defined(__GNUC__) && defined(__BYTE_ORDER__) && __BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__
    uint32_t x;
    (void)memcpy(&x, p, sizeof x);
    return __builtin_bswap32(x);
#else
    return ((uint32_t)p[0] << 24) | ((uint32_t)p[1] << 16) | ((uint32_t)p[2] << 8) | (uint32_t)p[3];
#endif
}

/* Start the compression of one block into job: the schedule's first 16 words, the working
 * variables from h. */
static void job_begin(sec_sha256_job_t *job, const uint32_t h[8],
                      const uint8_t blk[SEC_SHA256_BLOCK])
{
    for (uint32_t t = 0u; t < 16u; t++) {
        job->w[t] = be32_load(&blk[4u * t]);
    }
    (void)memcpy(job->v, h, sizeof job->v);
    job->round = 0u;
    job->active = 1u;
}

static uint32_t sig0(uint32_t x)
{
    return rotr(x, 7u) ^ rotr(x, 18u) ^ (x >> 3);
}

static uint32_t sig1(uint32_t x)
{
    return rotr(x, 17u) ^ rotr(x, 19u) ^ (x >> 10);
}

/* The schedule's word of round t in the 16-word window, w[t & 15], as it is (rounds 0..15) or
 * computed in place (16..63): (t - 15) & 15 = (t + 1) & 15, (t - 7) & 15 = (t + 9) & 15,
 * (t - 2) & 15 = (t + 14) & 15. */
#define SHA_W(t) (w[(t)&15u])
#define SHA_S(t) (w[(t)&15u] += sig0(SHA_W((t) + 1u)) + SHA_W((t) + 9u) + sig1(SHA_W((t) + 14u)))

/* One round on the working variables a..h in place (d and h take the new e and a; the next
 * round names the eight one place on), k the round's constant, x its schedule word. */
#define SHA_ROUND(a, b, c, d, e, f, g, h, k, x)                                        \
    do {                                                                               \
        const uint32_t t1_ = (h) + (rotr((e), 6u) ^ rotr((e), 11u) ^ rotr((e), 25u)) + \
                             ((g) ^ ((e) & ((f) ^ (g)))) + (k) + (x);                  \
        (d) += t1_;                                                                    \
        (h) = t1_ + (rotr((a), 2u) ^ rotr((a), 13u) ^ rotr((a), 22u)) +                \
              (((a) & (b)) | ((c) & ((a) | (b))));                                     \
    } while (0)

/* Eight rounds from a round t = 8j (base = t & 15, a constant: the window's indices fold), W the
 * schedule's form (SHA_W before round 16, SHA_S from it); k points at K256[t]. */
#define SHA_ROUNDS8(base, W)                                      \
    do {                                                          \
        SHA_ROUND(a, b, c, d, e, f, g, hh, k[0], W((base) + 0u)); \
        SHA_ROUND(hh, a, b, c, d, e, f, g, k[1], W((base) + 1u)); \
        SHA_ROUND(g, hh, a, b, c, d, e, f, k[2], W((base) + 2u)); \
        SHA_ROUND(f, g, hh, a, b, c, d, e, k[3], W((base) + 3u)); \
        SHA_ROUND(e, f, g, hh, a, b, c, d, k[4], W((base) + 4u)); \
        SHA_ROUND(d, e, f, g, hh, a, b, c, k[5], W((base) + 5u)); \
        SHA_ROUND(c, d, e, f, g, hh, a, b, k[6], W((base) + 6u)); \
        SHA_ROUND(b, c, d, e, f, g, hh, a, k[7], W((base) + 7u)); \
    } while (0)

/* Up to n more of the job's 64 rounds (the schedule kept in a 16-word window); at the last one the
 * block is added into h and the job's words wiped. Returns the rounds run. Within a call the
 * working variables stay in registers, eight rounds at a time unrolled with constant window
 * indices where the round and the budget allow (~40 instructions a round on the Cortex-M4 from
 * round 16 on, against ~75 one at a time from memory). */
static uint32_t job_run(sec_sha256_job_t *job, uint32_t h[8], uint32_t n)
{
    uint32_t *w = job->w;
    uint32_t a = job->v[0], b = job->v[1], c = job->v[2], d = job->v[3];
    uint32_t e = job->v[4], f = job->v[5], g = job->v[6], hh = job->v[7];
    uint32_t t = job->round;
    uint32_t done = 0u;
    while (done < n && t < 64u) {
        const uint32_t *k = &K256[t];
        if ((t & 7u) == 0u && n - done >= 8u) {
            switch ((t >= 16u ? 2u : 0u) | ((t >> 3) & 1u)) {
            case 0u: SHA_ROUNDS8(0u, SHA_W); break;
            case 1u: SHA_ROUNDS8(8u, SHA_W); break;
            case 2u: SHA_ROUNDS8(0u, SHA_S); break;
            default: SHA_ROUNDS8(8u, SHA_S); break;
            }
            t += 8u;
            done += 8u;
            continue;
        }
        const uint32_t x = t >= 16u ? SHA_S(t) : SHA_W(t);
        SHA_ROUND(a, b, c, d, e, f, g, hh, k[0], x);
        const uint32_t na = hh; /* the names of the next round */
        hh = g;
        g = f;
        f = e;
        e = d;
        d = c;
        c = b;
        b = a;
        a = na;
        t++;
        done++;
    }
    job->v[0] = a;
    job->v[1] = b;
    job->v[2] = c;
    job->v[3] = d;
    job->v[4] = e;
    job->v[5] = f;
    job->v[6] = g;
    job->v[7] = hh;
    job->round = t;
    if (t == 64u && job->active != 0u) {
        for (uint32_t i = 0u; i < 8u; i++) {
            h[i] += job->v[i];
        }
        sec_wipe(job, sizeof *job);
    }
    return done;
}
#undef SHA_ROUNDS8
#undef SHA_ROUND
#undef SHA_S
#undef SHA_W

static void compress(uint32_t h[8], const uint8_t blk[SEC_SHA256_BLOCK])
{
    sec_sha256_job_t job;
    job_begin(&job, h, blk);
    (void)job_run(&job, h, 64u);
}

uint32_t sec_sha256_feed(sec_sha256_t *s, sec_sha256_job_t *job, const uint8_t *data, uint32_t len,
                         uint32_t *rounds)
{
    uint32_t i = 0u;
    for (;;) {
        if (job->active != 0u) {
            *rounds -= job_run(job, s->h, *rounds);
            if (job->active != 0u) {
                return i; /* the budget is spent inside a block */
            }
            s->block_len = 0u;
        }
        if (i == len) {
            return i;
        }
        uint32_t k = SEC_SHA256_BLOCK - s->block_len;
        if (k > len - i) {
            k = len - i;
        }
        (void)memcpy(s->block + s->block_len, data + i, k);
        s->block_len += k;
        s->total_len += k;
        i += k;
        if (s->block_len == SEC_SHA256_BLOCK) {
            job_begin(job, s->h, s->block);
            if (*rounds == 0u) {
                return i;
            }
        }
    }
}

uint32_t sec_sha256_padding(const sec_sha256_t *s, uint8_t pad[SEC_SHA256_PAD_MAX])
{
    const uint64_t bits = s->total_len * 8u;
    const uint32_t used = (uint32_t)(s->total_len % SEC_SHA256_BLOCK);
    const uint32_t n = (used < SEC_SHA256_BLOCK - 8u ? SEC_SHA256_BLOCK : 2u * SEC_SHA256_BLOCK) -
                       used;
    (void)memset(pad, 0, n);
    pad[0] = 0x80u;
    for (uint32_t i = 0u; i < 8u; i++) {
        pad[n - 1u - i] = (uint8_t)(bits >> (8u * i));
    }
    return n;
}

void sec_sha256_digest(sec_sha256_t *s, uint8_t out[SEC_SHA256_LEN])
{
    for (uint32_t i = 0u; i < 8u; i++) {
        out[4u * i] = (uint8_t)(s->h[i] >> 24);
        out[4u * i + 1u] = (uint8_t)(s->h[i] >> 16);
        out[4u * i + 2u] = (uint8_t)(s->h[i] >> 8);
        out[4u * i + 3u] = (uint8_t)s->h[i];
    }
    sec_wipe(s, sizeof *s);
}

void sec_sha256_init(sec_sha256_t *s)
{
    static const uint32_t h0[8] = {0x6a09e667u, 0xbb67ae85u, 0x3c6ef372u, 0xa54ff53au,
                                   0x510e527fu, 0x9b05688cu, 0x1f83d9abu, 0x5be0cd19u};
    if (s == NULL) {
        return;
    }
    (void)memcpy(s->h, h0, sizeof h0);
    s->total_len = 0u;
    s->block_len = 0u;
}

void sec_sha256_update(sec_sha256_t *s, const uint8_t *data, uint32_t len)
{
    if (s == NULL || (data == NULL && len != 0u)) {
        return;
    }
    s->total_len += len;
    uint32_t i = 0u;
    while (i < len) {
        uint32_t k = SEC_SHA256_BLOCK - s->block_len;
        if (k > len - i) {
            k = len - i;
        }
        (void)memcpy(s->block + s->block_len, data + i, k);
        s->block_len += k;
        i += k;
        if (s->block_len == SEC_SHA256_BLOCK) {
            compress(s->h, s->block);
            s->block_len = 0u;
        }
    }
}

void sec_sha256_final(sec_sha256_t *s, uint8_t out[SEC_SHA256_LEN])
{
    if (s == NULL || out == NULL) {
        return;
    }
    uint8_t pad[SEC_SHA256_PAD_MAX];
    const uint32_t n = sec_sha256_padding(s, pad);
    sec_sha256_update(s, pad, n);
    sec_sha256_digest(s, out);
}

void sec_sha256(const uint8_t *data, uint32_t len, uint8_t out[SEC_SHA256_LEN])
{
    sec_sha256_t s;
    sec_sha256_init(&s);
    sec_sha256_update(&s, data, len);
    sec_sha256_final(&s, out);
}

void sec_hmac_init(sec_hmac_t *h, const uint8_t *key, uint32_t key_len)
{
    if (h == NULL || (key == NULL && key_len != 0u)) {
        return;
    }
    uint8_t k0[SEC_SHA256_BLOCK];
    (void)memset(k0, 0, sizeof k0);
    if (key_len > SEC_SHA256_BLOCK) {
        sec_sha256(key, key_len, k0);
    } else if (key_len != 0u) {
        (void)memcpy(k0, key, key_len);
    }
    uint8_t ipad[SEC_SHA256_BLOCK];
    for (uint32_t i = 0u; i < SEC_SHA256_BLOCK; i++) {
        ipad[i] = (uint8_t)(k0[i] ^ 0x36u);
        h->okey[i] = (uint8_t)(k0[i] ^ 0x5Cu);
    }
    sec_sha256_init(&h->inner);
    sec_sha256_update(&h->inner, ipad, SEC_SHA256_BLOCK);
    sec_wipe(k0, sizeof k0);
    sec_wipe(ipad, sizeof ipad);
}

void sec_hmac_update(sec_hmac_t *h, const uint8_t *data, uint32_t len)
{
    if (h != NULL) {
        sec_sha256_update(&h->inner, data, len);
    }
}

void sec_hmac_final(sec_hmac_t *h, uint8_t out[SEC_SHA256_LEN])
{
    if (h == NULL || out == NULL) {
        return;
    }
    uint8_t ih[SEC_SHA256_LEN];
    sec_sha256_final(&h->inner, ih);
    sec_sha256_t o;
    sec_sha256_init(&o);
    sec_sha256_update(&o, h->okey, SEC_SHA256_BLOCK);
    sec_sha256_update(&o, ih, SEC_SHA256_LEN);
    sec_sha256_final(&o, out);
    sec_wipe(ih, sizeof ih);
    sec_wipe(h, sizeof *h);
}

void sec_hmac_sha256(const uint8_t *key, uint32_t key_len, const uint8_t *msg, uint32_t msg_len,
                     uint8_t out[SEC_SHA256_LEN])
{
    sec_hmac_t h;
    sec_hmac_init(&h, key, key_len);
    sec_hmac_update(&h, msg, msg_len);
    sec_hmac_final(&h, out);
}

int sec_ct_equal(const uint8_t *a, const uint8_t *b, uint32_t len)
{
    if (a == NULL || b == NULL) {
        return 0;
    }
    volatile uint8_t diff = 0u;
    for (uint32_t i = 0u; i < len; i++) {
        diff = (uint8_t)(diff | (uint8_t)(a[i] ^ b[i]));
    }
    /* 1 iff diff == 0, without a data-dependent branch */
    return (int)(1u & (((uint32_t)diff - 1u) >> 8));
}

void sec_wipe(void *p, uint32_t len)
{
    volatile uint8_t *v = (volatile uint8_t *)p;
    if (v == NULL) {
        return;
    }
    uint32_t i = 0u;
    /* the aligned middle a word a store, four words an iteration (a hash job's state in a
     * fraction of a tick); the unaligned ends a byte a store */
    for (; i < len && ((uintptr_t)&v[i] & 3u) != 0u; i++) {
        v[i] = 0u;
    }
    volatile uint32_t *w = (volatile uint32_t *)(volatile void *)&v[i];
    for (; i + 16u <= len; i += 16u) {
        w[0] = 0u;
        w[1] = 0u;
        w[2] = 0u;
        w[3] = 0u;
        w += 4;
    }
    for (; i + 4u <= len; i += 4u) {
        *w = 0u;
        w++;
    }
    for (; i < len; i++) {
        v[i] = 0u;
    }
}

bool sec_hmac_job_begin(sec_hmac_job_t *j, const uint8_t *key, uint32_t key_len, const uint8_t *msg,
                        uint32_t len)
{
    if (key_len > SEC_SHA256_BLOCK || len > SEC_HMAC_JOB_MSG_MAX) {
        return false;
    }
    (void)memset(j, 0, sizeof *j);
    (void)memcpy(j->ikey, key, key_len);
    for (uint32_t i = 0u; i < SEC_SHA256_BLOCK; i++) {
        j->okey[i] = (uint8_t)(j->ikey[i] ^ 0x5Cu);
        j->ikey[i] ^= 0x36u;
    }
    (void)memcpy(j->msg, msg, len);
    j->msg_len = len;
    sec_sha256_init(&j->inner);
    j->chunk = j->ikey;
    j->chunk_len = SEC_SHA256_BLOCK;
    return true;
}

static void job_chunk(sec_hmac_job_t *j, const uint8_t *p, uint32_t len)
{
    j->chunk = p;
    j->chunk_len = len;
    j->chunk_off = 0u;
}

/* The stages: key ^ ipad, message, padding (inner); key ^ opad, inner digest, padding (outer). */
bool sec_hmac_job_run(sec_hmac_job_t *j, uint32_t rounds, uint8_t out[SEC_SHA256_LEN])
{
    const bool sliced = rounds != UINT32_MAX;
    const uint32_t budget = rounds;
    for (;;) {
        sec_sha256_t *h = j->stage < 3u ? &j->inner : &j->outer;
        j->chunk_off += sec_sha256_feed(h, &j->job, j->chunk + j->chunk_off,
                                        j->chunk_len - j->chunk_off, &rounds);
        if (j->chunk_off < j->chunk_len || j->job.active != 0u) {
            return false; /* the budget is spent */
        }
        if (sliced && rounds != budget) {
            return false; /* a call that compressed leaves the stage's end (a padding, a digest,
                             the wipes) to the next one */
        }
        switch (j->stage++) { /* each key pad wiped once fed, not all at the end: bounded ticks */
        case 0u:
            sec_wipe(j->ikey, SEC_SHA256_BLOCK);
            job_chunk(j, j->msg, j->msg_len);
            break;
        case 1u: job_chunk(j, j->buf, sec_sha256_padding(&j->inner, j->buf)); break;
        case 2u:
            sec_sha256_digest(&j->inner,
                              j->msg); /* the message is in: its buffer holds the digest */
            sec_sha256_init(&j->outer);
            job_chunk(j, j->okey, SEC_SHA256_BLOCK);
            break;
        case 3u:
            sec_wipe(j->okey, SEC_SHA256_BLOCK);
            job_chunk(j, j->msg, SEC_SHA256_LEN);
            break;
        case 4u: job_chunk(j, j->buf, sec_sha256_padding(&j->outer, j->buf)); break;
        default:
            sec_sha256_digest(&j->outer, out); /* wipes the outer state; the inner one is */
            sec_wipe(j->msg, SEC_SHA256_LEN);  /* the inner digest */
            sec_wipe(j->buf, SEC_SHA256_PAD_MAX);
            j->chunk = NULL;
            j->chunk_len = 0u;
            j->chunk_off = 0u;
            return true;
        }
    }
}
