/* Binding of the update receiver (fwu.h) to the UDS server (firmware/proto/uds.h): the
 * application's uds_app_t hooks delegate here for the firmware address, routines and DID, so the
 * UDS server itself needs no change. Library fs_boot_uds (fs_boot + fs_proto). */
#ifndef FWU_UDS_H
#define FWU_UDS_H

#include <stdbool.h>
#include <stdint.h>
#include "fwu.h"
#include "uds.h"

/** Programming session with SecurityAccess level UDS_SEC_LEVEL_FIRMWARE unlocked. */
bool fwu_uds_authorised(const uds_server_t *srv);

/** download_begin for addr == FWU_DOWNLOAD_ADDRESS (the caller routes by address). */
uint8_t fwu_uds_download_begin(fwu_t *f, const uds_server_t *srv, uint32_t size);


/** download_data while a firmware download is active: the block kept at the first call (data
 *  not NULL), then programmed a slice a call (data NULL), UDS_NRC_RESPONSE_PENDING until done. */
uint8_t fwu_uds_download_data(fwu_t *f, const uds_server_t *srv, uint32_t offset,
                              const uint8_t *data, uint16_t len);


/** download_end while a firmware download is active (*crc32_out: CRC-32 of the image): the
 *  verification a slice a call, UDS_NRC_RESPONSE_PENDING until it ends. */
uint8_t fwu_uds_download_end(fwu_t *f, const uds_server_t *srv, uint32_t *crc32_out);

/** True for the routine identifiers handled by fwu_uds_routine. */
bool fwu_uds_owns_rid(uint16_t rid);

/** RoutineControl for FWU_RID_MARK_TEST (start, option byte) and FWU_RID_CONFIRM (start); both
 *  need the programming session with level UDS_SEC_LEVEL_FIRMWARE (else 0x33). */
uint8_t fwu_uds_routine(fwu_t *f, const uds_server_t *srv, uint8_t sub, uint16_t rid,
                        const uint8_t *data, uint16_t len, uint8_t *out, uint16_t cap,
                        uint16_t *out_len);

/** ReadDataByIdentifier FWU_DID_STATUS. */
uint8_t fwu_uds_read_did(const fwu_t *f, uint8_t *out, uint16_t cap, uint16_t *out_len);

#endif /* FWU_UDS_H */
