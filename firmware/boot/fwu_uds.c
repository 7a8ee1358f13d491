/* UDS binding of the update receiver (fwu_uds.h). */
#include "fwu_uds.h"

#include <stddef.h>

bool fwu_uds_authorised(const uds_server_t *srv)
{
    return srv != NULL && srv->session == UDS_SESSION_PROGRAMMING &&
           srv->unlocked_level == UDS_SEC_LEVEL_FIRMWARE;
}

uint8_t fwu_uds_download_begin(fwu_t *f, const uds_server_t *srv, uint32_t size)
{
    return fwu_nrc(fwu_begin(f, fwu_uds_authorised(srv), size));
}

uint8_t fwu_uds_download_data(fwu_t *f, const uds_server_t *srv, uint32_t offset,
                              const uint8_t *data, uint16_t len)
{
    bool done = false;
    const boot_status_t st = fwu_data_step(f, fwu_uds_authorised(srv), offset, data, len,
                                           FWU_DATA_BYTES_PER_CALL, &done);
    return done ? fwu_nrc(st) : UDS_NRC_RESPONSE_PENDING;
}

uint8_t fwu_uds_download_end(fwu_t *f, const uds_server_t *srv, uint32_t *crc32_out)
{
    bool done = false;
    const boot_status_t st = fwu_end_step(f, fwu_uds_authorised(srv), crc32_out,
                                          FWU_VERIFY_ROUNDS_PER_CALL, &done);
    return done ? fwu_nrc(st) : UDS_NRC_RESPONSE_PENDING;
}

bool fwu_uds_owns_rid(uint16_t rid)
{
    return rid == FWU_RID_MARK_TEST || rid == FWU_RID_CONFIRM;
}

uint8_t fwu_uds_routine(fwu_t *f, const uds_server_t *srv, uint8_t sub, uint16_t rid,
                        const uint8_t *data, uint16_t len, uint8_t *out, uint16_t cap,
                        uint16_t *out_len)
{
    (void)out;
    (void)cap;
    *out_len = 0u;
    if (sub != UDS_ROUTINE_START) {
        return UDS_NRC_SUBFUNCTION_NOT_SUPPORTED;
    }
    if (rid == FWU_RID_MARK_TEST) {
        fs_wire_mark_test_t m;
        const proto_status_t ps = fs_wire_mark_test_unpack(&m, data, len);
        if (ps != PROTO_OK) {
            return ps == PROTO_ERR_WIRE_LENGTH ? UDS_NRC_INCORRECT_LENGTH
                                               : UDS_NRC_REQUEST_OUT_OF_RANGE;
        }
        return fwu_nrc(fwu_mark_test(f, fwu_uds_authorised(srv), m.options));
    }
    if (rid == FWU_RID_CONFIRM) {
        if (!fwu_uds_authorised(srv)) {
            return UDS_NRC_SECURITY_ACCESS_DENIED; /* no node confirms an image without level 3 */
        }
        return len == 0u ? fwu_nrc(fwu_confirm(f)) : UDS_NRC_INCORRECT_LENGTH;
    }
    return UDS_NRC_REQUEST_OUT_OF_RANGE;
}

uint8_t fwu_uds_read_did(const fwu_t *f, uint8_t *out, uint16_t cap, uint16_t *out_len)
{
    *out_len = fwu_status(f, out, cap);
    return *out_len == 0u ? UDS_NRC_RESPONSE_TOO_LONG : UDS_NRC_OK;
}
