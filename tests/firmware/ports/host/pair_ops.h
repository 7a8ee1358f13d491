/* Test seam of the SocketCAN driver: cansock_ops_t over a Unix socket pair (SOCK_SEQPACKET, one
 * struct can_frame per record) instead of an AF_CAN socket. The test holds the other end, the
 * "bus": it reads what the driver transmitted and writes what the driver receives (data frames,
 * error frames). Bit rate, restart and write failures are scripted through pair_ctl. */
#ifndef PAIR_OPS_H
#define PAIR_OPS_H

#include <stdbool.h>
#include <stdint.h>

#include <sys/types.h>

#include "cansock.h"

/** Scripted behaviour and observations of the fake operating system. */
typedef struct {
    int bus_fd;                  /* the test's end of the pair (-1 before open) */
    int open_result;             /* < 0: open_raw fails with it */
    int get_result;              /* get_bitrate result (0: reports bitrate_bps) */
    int set_result;              /* set_bitrate result */
    uint32_t bitrate_bps;        /* the "interface's" bit rate */
    unsigned set_calls;
    int restart_result;          /* restart result; 0 also puts a "restarted" error frame on the bus */
    unsigned restart_calls;
    unsigned write_fail_count;   /* the next N writes fail with write_fail_errno */
    int write_fail_errno;
    bool fd_capable;             /* enable_fd succeeds (an interface with the CAN FD MTU) */
} pair_ctl_t;

extern pair_ctl_t pair_ctl;
extern const cansock_ops_t pair_ops;

/** Reset pair_ctl (closing a previous bus end). */
void pair_reset(void);

/** Put a raw struct can_frame on the bus (the driver receives it). */
void pair_put(uint32_t can_id, uint8_t len, const uint8_t *data);

/** Take the next frame the driver transmitted; false if none is waiting. */
bool pair_take(struct can_frame *f);

/** Put a raw struct canfd_frame (CANFD_MTU bytes) on the bus. */
void pair_put_fd(uint32_t can_id, uint8_t len, uint8_t flags, const uint8_t *data);

/** Take the next record the driver wrote, classic or FD: its size (CAN_MTU, CANFD_MTU), or <= 0
 *  if none is waiting. */
ssize_t pair_take_any(struct canfd_frame *f);

#endif /* PAIR_OPS_H */
