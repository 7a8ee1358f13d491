#define _POSIX_C_SOURCE 200809L
/* Test harness for the generated DBC code: reads commands from stdin, one per line, and prints
 * what the generated C does with them, so tests/firmware/proto/check_dbc.py can compare it with
 * cantools on random values:
 *   list                         -> "MSG ID SIG1 SIG2 ..." for every message
 *   pack MSG r1 r2 ...           -> hex of the 8 packed bytes (raw signal values in list order)
 *   unpack MSG HEX               -> "raw1 ... rawN | phys1 ... physN" (decode functions)  */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "fs_dbc.h"

#define MESSAGES(X)                                                                                \
    X(emergency, EMERGENCY, "Emergency",                                                           \
      F(fault_code, "FaultCode") F(state, "State") F(n_latched, "NLatched") F(tick, "Tick")        \
          F(counter, "Counter") F(crc, "Crc"))                                                     \
    X(host_command, HOST_COMMAND, "HostCommand",                                                   \
      F(mode, "Mode") F(slot, "Slot") F(goal_scale, "GoalScale") F(time_scale, "TimeScale")        \
          F(end_policy, "EndPolicy") F(mac, "Mac") F(counter, "Counter") F(freshness, "Freshness") \
              F(crc, "Crc"))                                                                       \
    X(host_heartbeat, HOST_HEARTBEAT, "HostHeartbeat",                                             \
      F(telemetry_period, "TelemetryPeriod") F(command_freshness, "CommandFreshness")              \
          F(mac, "Mac") F(counter, "Counter") F(freshness, "Freshness") F(crc, "Crc"))             \
    X(device_status, DEVICE_STATUS, "DeviceStatus",                                                \
      F(state, "State") F(slot, "Slot") F(fault_code, "FaultCode") F(tick, "Tick")                 \
          F(counter, "Counter") F(actuator_enabled, "ActuatorEnabled") F(host_alive, "HostAlive")  \
              F(sequence_step, "SequenceStep") F(crc, "Crc"))                                      \
    X(telemetry_position, TELEMETRY_POSITION, "TelemetryPosition",                                 \
      F(pos_x, "PosX") F(pos_y, "PosY") F(band_outside, "BandOutside") F(tick, "Tick"))            \
    X(telemetry_force, TELEMETRY_FORCE, "TelemetryForce",                                          \
      F(force_contact, "ForceContact") F(force_operator, "ForceOperator") F(force_cmd, "ForceCmd") \
          F(force_ref, "ForceRef"))

static int parse_hex(const char *s, uint8_t *out, size_t n)
{
    if (strlen(s) < 2 * n) {
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        unsigned v = 0;
        if (sscanf(s + 2 * i, "%2x", &v) != 1) {
            return -1;
        }
        out[i] = (uint8_t)v;
    }
    return 0;
}

static void print_hex(const uint8_t *b, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        printf("%02x", b[i]);
    }
    printf("\n");
}

#define F(field, sname) printf(" %s", sname);
#define X(lc, uc, name, fields)                              \
    printf("%s %u", name, (unsigned)FS_DBC_##uc##_FRAME_ID); \
    fields printf("\n");
static void cmd_list(void)
{
    MESSAGES(X)
}
#undef X
#undef F

static int cmd_pack(const char *name, char *rest)
{
    uint8_t buf[8];
    char *save = NULL;
    char *tok = NULL;
#define F(field, sname)                   \
    tok = strtok_r(rest, " \t\n", &save); \
    rest = NULL;                          \
    if (tok == NULL)                      \
        return -1;                        \
    msg.field = (__typeof__(msg.field))strtoll(tok, NULL, 10);
#define X(lc, uc, mname, fields)                                   \
    if (strcmp(name, mname) == 0) {                                \
        struct fs_dbc_##lc##_t msg;                                \
        memset(&msg, 0, sizeof(msg));                              \
        fields int n = fs_dbc_##lc##_pack(buf, &msg, sizeof(buf)); \
        if (n < 0)                                                 \
            return -1;                                             \
        print_hex(buf, (size_t)n);                                 \
        return 0;                                                  \
    }
    MESSAGES(X)
#undef X
#undef F
    return -1;
}

static int cmd_unpack(const char *name, const char *hex)
{
    uint8_t buf[8];
    if (parse_hex(hex, buf, 8) != 0) {
        return -1;
    }
#define F(field, sname) printf("%" PRId64 " ", (int64_t)msg.field);
#define G(lc, field) printf(" %.9g", (double)fs_dbc_##lc##_##field##_decode(msg.field));
#define X(lc, uc, mname, fields)                               \
    if (strcmp(name, mname) == 0) {                            \
        struct fs_dbc_##lc##_t msg;                            \
        memset(&msg, 0, sizeof(msg));                          \
        if (fs_dbc_##lc##_unpack(&msg, buf, sizeof(buf)) != 0) \
            return -1;                                         \
        fields printf("|");                                    \
        PHYS_##lc printf("\n");                                \
        return 0;                                              \
    }
#define PHYS_emergency                                                                   \
    G(emergency, fault_code)                                                             \
    G(emergency, state) G(emergency, n_latched) G(emergency, tick) G(emergency, counter) \
        G(emergency, crc)
#define PHYS_host_command                                                         \
    G(host_command, mode)                                                         \
    G(host_command, slot) G(host_command, goal_scale) G(host_command, time_scale) \
        G(host_command, end_policy) G(host_command, mac) G(host_command, counter) \
            G(host_command, freshness) G(host_command, crc)
#define PHYS_host_heartbeat                                                                \
    G(host_heartbeat, telemetry_period)                                                    \
    G(host_heartbeat, command_freshness) G(host_heartbeat, mac) G(host_heartbeat, counter) \
        G(host_heartbeat, freshness) G(host_heartbeat, crc)
#define PHYS_device_status                                                                        \
    G(device_status, state)                                                                       \
    G(device_status, slot) G(device_status, fault_code) G(device_status, tick)                    \
        G(device_status, counter) G(device_status, actuator_enabled) G(device_status, host_alive) \
            G(device_status, sequence_step) G(device_status, crc)
#define PHYS_telemetry_position  \
    G(telemetry_position, pos_x) \
    G(telemetry_position, pos_y) G(telemetry_position, band_outside) G(telemetry_position, tick)
#define PHYS_telemetry_force          \
    G(telemetry_force, force_contact) \
    G(telemetry_force, force_operator) G(telemetry_force, force_cmd) G(telemetry_force, force_ref)
    MESSAGES(X)
#undef X
#undef F
    return -1;
}

int main(void)
{
    char line[512];
    while (fgets(line, sizeof(line), stdin) != NULL) {
        char cmd[32];
        char name[64];
        int off = 0;
        int rc = 0;
        if (sscanf(line, "%31s%n", cmd, &off) != 1) {
            continue;
        }
        if (strcmp(cmd, "list") == 0) {
            cmd_list();
        } else if (sscanf(line + off, "%63s%n", name, &off) == 1 || 1) {
            char *rest = strstr(line, name) + strlen(name);
            if (strcmp(cmd, "pack") == 0) {
                rc = cmd_pack(name, rest);
            } else if (strcmp(cmd, "unpack") == 0) {
                char hex[32] = {0};
                rc = (sscanf(rest, "%31s", hex) == 1) ? cmd_unpack(name, hex) : -1;
            } else {
                rc = -1;
            }
        }
        if (rc != 0) {
            printf("error\n");
        }
        fflush(stdout);
    }
    return 0;
}
