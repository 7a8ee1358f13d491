/* Status codes: Security.
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef SEC_STATUS_H
#define SEC_STATUS_H

/** Security (550-569, sec_*): results that are not UDS negative response codes. */
typedef enum {
    SEC_OK = 0,
    SEC_ERR_NULL_ARG = 550,        /* a required pointer was NULL */
    SEC_ERR_RNG = 551,             /* the random source failed or returned a degenerate seed */
    SEC_ERR_CONFIG = 552,          /* configuration invalid (secret length, attempts, delays) */
    /* authenticated host frame refused: wrong MAC (forged, corrupted, or sent with another key) */
    SEC_ERR_MAC = 553,
    /* authenticated host frame refused: its freshness value was already used (replay) */
    SEC_ERR_REPLAY = 554,
    /* host frame refused: no motion key established (SecurityAccess level 1, then DID 0x0302) */
    SEC_ERR_NO_KEY = 555,
    /* authenticated host frame refused: the 32-bit freshness counter is used up (a new key
     * restarts it) */
    SEC_ERR_FRESHNESS = 556,
    /* HostCommand EXECUTE refused: not preceded by its RUN_OPTIONS frame (the previous freshness
     * value) */
    SEC_ERR_EXECUTE_OPTIONS = 557,
    /* UDS write refused (0x33): the unlocked session belongs to the other tester id, the one
     * whose SecurityAccess unlocked it */
    SEC_ERR_SESSION_OWNER = 558,
    /* authenticated HostCommand refused as late: it arrived more than 50 ms after the previous
     * host frame the device accepted, or after a stop, a UDS fault clear or run stop, or a new
     * motion key, with no heartbeat between (a withheld command never acts late) */
    SEC_ERR_STALE = 559,
    /* SecurityAccess sendKey refused (0x24): no seed of this tester id, or its reception began
     * before that seed was sent */
    SEC_ERR_KEY_SEQUENCE = 560,
} sec_status_t;

#endif /* SEC_STATUS_H */
