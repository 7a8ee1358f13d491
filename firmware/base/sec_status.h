/* Status codes: Security.
 * generated from firmware/base/codes.toml by tools/gen_codes.py; do not edit. */
#ifndef SEC_STATUS_H
#define SEC_STATUS_H

/** Security (550-569, sec_*): results that are not UDS negative response codes. */
typedef enum {
    SEC_OK = 0,
    SEC_ERR_NULL_ARG = 550, /* a required pointer was NULL */
    SEC_ERR_RNG = 551,      /* the random source failed or returned a degenerate seed */
    SEC_ERR_CONFIG = 552,   /* configuration invalid (secret length, attempts, delays) */
} sec_status_t;

#endif /* SEC_STATUS_H */
