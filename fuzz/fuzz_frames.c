/* libFuzzer harness: the DBC-generated frame decoders and the E2E check (firmware/proto,
 * read-only use). Every cyclic frame's unpack runs on the input (any length); the E2E receiver
 * is fed the input as a stream of frames. Sanitizers catch out-of-bounds reads; a protected
 * frame must always pass its own check once (abort() otherwise). */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "e2e.h"
#include "fs_dbc.h"

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    struct fs_dbc_emergency_t em;
    struct fs_dbc_host_command_t hc;
    struct fs_dbc_host_heartbeat_t hb;
    struct fs_dbc_device_status_t ds;
    struct fs_dbc_telemetry_position_t tp;
    struct fs_dbc_telemetry_force_t tf;
    (void)fs_dbc_emergency_unpack(&em, data, size);
    (void)fs_dbc_host_command_unpack(&hc, data, size);
    (void)fs_dbc_host_heartbeat_unpack(&hb, data, size);
    (void)fs_dbc_device_status_unpack(&ds, data, size);
    (void)fs_dbc_telemetry_position_unpack(&tp, data, size);
    (void)fs_dbc_telemetry_force_unpack(&tf, data, size);

    e2e_rx_t rx;
    e2e_rx_reset(&rx);
    for (size_t i = 0; i + 10u <= size; i += 10u) {
        can_frame_t f;
        f.id = ((uint32_t)data[i] | ((uint32_t)data[i + 1] << 8)) & CAN_STD_ID_MASK;
        f.len = (uint8_t)(data[i + 1] >> 4);
        if (f.len > 8u) {
            f.len = 8u;
        }
        memcpy(f.data, data + i + 2, 8);
        (void)e2e_check(&rx, &f);
        /* protect it ourselves: a fresh receiver must accept it */
        e2e_protect(&f, data[i + 2]);
        e2e_rx_t fresh;
        e2e_rx_reset(&fresh);
        if (e2e_check(&fresh, &f) != PROTO_OK) {
            abort();
        }
    }
    return 0;
}
