/* The scenario as a flat parameter block, for a plant that runs where no scenario file can be
 * read (the processor-in-the-loop Cortex-M image: `hil_sim pil` parses the file, packs the
 * block, qemu loads it into the board's memory, the image unpacks it). Little-endian:
 *   u32 magic "FSPB", u32 version 1, u32 count, u32 node, u32 host_timeout_ms, u32 flags,
 *   u8 seed[32],
 *   then count float64 values, one per numeric scenario field (fixed order, sim_params.c).
 * Names, paths, skills and the injected fault are not carried (the PIL plant needs none). */
#ifndef SIM_PARAMS_H
#define SIM_PARAMS_H

#include <stdint.h>
#include "sim_scenario.h"

#define SIM_PARAMS_MAGIC 0x42505346u /* "FSPB" */
#define SIM_PARAMS_VERSION 2u
#define SIM_PARAMS_SEED_LEN 32u
#define SIM_PARAMS_HEADER 56u /* 6 x u32 + seed */
#define SIM_PARAMS_PACE \
    0x1u /* flags: the board's clock runs free (qemu -icount
                                          sleep=off): the image paces it to the host's */
#define SIM_PARAMS_MAX_BYTES 1024u

/** Device settings carried with the scenario. */
typedef struct {
    uint32_t node;
    uint32_t host_timeout_ms;
    uint32_t flags;                    /* SIM_PARAMS_* */
    uint8_t seed[SIM_PARAMS_SEED_LEN]; /* the device's random seed (no entropy on the board) */
} sim_params_dev_t;

/** Pack sc and dev into out (cap bytes); returns the length, 0 if cap is too small. */
uint32_t sim_params_pack(const sim_scenario_t *sc, const sim_params_dev_t *dev, uint8_t *out,
                         uint32_t cap);

/** Unpack a block into a zeroed scenario (no name, paths or fault); 0 on success, -1 if it is not a valid block. */
int sim_params_unpack(const uint8_t *in, uint32_t len, sim_scenario_t *sc, sim_params_dev_t *dev);

#endif /* SIM_PARAMS_H */
