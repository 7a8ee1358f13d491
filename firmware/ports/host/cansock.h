/* SocketCAN driver of the host port (cansock_): one classic CAN raw socket, non-blocking, as a
 * Linux controller or adapter presents it (can0, vcan0). It converts frames to and from
 * struct can_frame, consumes error frames (bus-off latches; a restart is requested
 * CANSOCK_RESTART_MS after it and every CANSOCK_RESTART_MS while still off; the controller's
 * "restarted" error frame clears it), and transmits without blocking: a full queue (EAGAIN from
 * the socket buffer, ENOBUFS from the interface queue) refuses the frame, the caller retries.
 * While bus-off every transmit is refused, as the simulator's controller does. CAN FD
 * (cansock_enable_fd, CAN_RAW_FD_FRAMES on an interface with the FD MTU of 72): FD frames
 * (struct canfd_frame, BRS kept) go both ways, classic frames still pass; without it the socket
 * stays classic and FD frames are refused on the way out.
 *
 * The operating-system calls go through cansock_ops_t: cansock_linux_ops opens an AF_CAN raw
 * socket and uses libsocketcan for the bit rate and the restart; tests pass their own ops and
 * run the driver over a socket pair carrying struct can_frame where the kernel has no AF_CAN.
 * Used by hal_can_socketcan.c (the HAL's CAN functions) and by `hil_sim serve --socketcan`. */
#ifndef CANSOCK_H
#define CANSOCK_H

#include <stdbool.h>
#include <stdint.h>
#include <sys/types.h>
#include <linux/can.h>
#include <linux/can/error.h>

#include "can_frame.h"

#define CANSOCK_IFNAME_MAX 16u   /* IFNAMSIZ, terminating zero included */
#define CANSOCK_RESTART_MS 100u  /* bus-off: first restart request after this, then repeated */
#define CANSOCK_RX_SKIP_MAX 256u /* error/foreign frames consumed per receive call at most */
#define CANSOCK_ERR_MASK (CAN_ERR_BUSOFF | CAN_ERR_RESTARTED | CAN_ERR_CRTL | CAN_ERR_ACK)

/** The operating-system side; every function returns 0 (or a descriptor) or -errno. */
typedef struct cansock_ops {
    /* a raw CAN socket bound to ifname, error frames of CANSOCK_ERR_MASK enabled (err: why not) */
    int (*open_raw)(const char *ifname, char *err, uint32_t err_len);
    /* the interface's bit rate (-EOPNOTSUPP: it has no bit timing, e.g. vcan) */
    int (*get_bitrate)(const char *ifname, uint32_t *bitrate_bps);
    /* link down, set the bit rate, link up again (also when setting failed) */
    int (*set_bitrate)(const char *ifname, uint32_t bitrate_bps);
    /* restart a bus-off controller */
    int (*restart)(const char *ifname);
    /* write one frame of size bytes, CAN_MTU (struct can_frame) or CANFD_MTU (struct
     * canfd_frame) (write(2) semantics: bytes written or -1 with errno) */
    ssize_t (*write_frame)(int fd, const void *frame, size_t size);
    /* accept CAN FD frames on the open socket (CAN_RAW_FD_FRAMES); -EOPNOTSUPP with one line in
     * err if the interface is classic only (MTU 16); NULL: never */
    int (*enable_fd)(int fd, const char *ifname, char *err, uint32_t err_len);
} cansock_ops_t;

/** AF_CAN raw socket + libsocketcan (libsocketcan's own stderr messages are suppressed). */
extern const cansock_ops_t cansock_linux_ops;

/** What a received struct can_frame is to this product. */
typedef enum {
    CANSOCK_RX_DATA = 0,   /* an 11-bit data frame */
    CANSOCK_RX_ERROR = 1,  /* an error frame (CAN_ERR_FLAG) */
    CANSOCK_RX_FOREIGN = 2 /* extended id or remote frame: not this product's, ignored */
} cansock_rx_kind_t;

/** Counters (since open). */
typedef struct {
    uint32_t rx_frames;
    uint32_t tx_frames;
    uint32_t rx_foreign;   /* extended/remote frames ignored */
    uint32_t rx_fd_frames; /* of rx_frames, CAN FD frames */
    uint32_t tx_fd_frames; /* of tx_frames, CAN FD frames */
    uint32_t rx_errors;    /* failed or short reads */
    uint32_t error_frames;
    uint32_t bus_offs; /* transitions into bus-off */
    uint32_t restarts; /* restart requests */
    uint32_t restart_failures;
    uint32_t tx_full;       /* refused: queue full (EAGAIN/ENOBUFS) */
    uint32_t tx_bus_off;    /* refused: bus-off */
    uint32_t tx_errors;     /* refused: any other write error (interface down, ...) */
    uint8_t tx_err_counter; /* controller error counters of the last error frame with them */
    uint8_t rx_err_counter;
} cansock_stats_t;

/** One open interface. */
typedef struct cansock {
    int fd; /* -1: closed */
    char ifname[CANSOCK_IFNAME_MAX];
    const cansock_ops_t *ops;
    bool bus_off;
    bool fd_mode;           /* CAN FD frames accepted (cansock_enable_fd) */
    uint64_t restart_at_us; /* next restart request while bus-off */
    int last_tx_errno;      /* of the last tx error (not queue full), 0 if none */
    int last_restart_errno; /* of the last failed restart, 0 if none */
    cansock_stats_t st;
} cansock_t;

/** Linux's rule for interface names (dev_valid_name): 1..15 bytes, not "." or "..", no '/',
 *  ':' or white space. */
bool cansock_valid_ifname(const char *name);

/** A closed driver (fd -1, counters zero). */
void cansock_init(cansock_t *c);

/** Open ifname through ops (NULL: cansock_linux_ops) and make it non-blocking; 0, or -errno with
 *  one line in err (invalid name, no AF_CAN, no such interface). */
int cansock_open(cansock_t *c, const cansock_ops_t *ops, const char *ifname, char *err,
                 uint32_t err_len);

/** Ask for bitrate_bps: 0 set, 1 already at that rate, or -errno with one line in err
 *  (-EPERM/-EACCES: needs CAP_NET_ADMIN, interface untouched; -EOPNOTSUPP: no bit timing). */
int cansock_set_bitrate(cansock_t *c, uint32_t bitrate_bps, char *err, uint32_t err_len);

/** Accept CAN FD frames from now on: 0, or -errno with one line in err (-EOPNOTSUPP: the
 *  interface or the ops are classic only; the socket stays classic). */
int cansock_enable_fd(cansock_t *c, char *err, uint32_t err_len);

/** Close the socket (counters kept). */
void cansock_close(cansock_t *c);

/** struct can_frame of an 11-bit data frame; false (out untouched) if id > 0x7FF or dlc > 8. */
bool cansock_to_linux(const can_frame_t *f, struct can_frame *out);

/** Classify a received frame; for a data frame fill out (data beyond dlc zeroed). */
cansock_rx_kind_t cansock_from_linux(const struct can_frame *in, can_frame_t *out);

/** struct canfd_frame of an 11-bit data frame, classic or FD: the bytes to write (CAN_MTU for a
 *  classic frame, in struct can_frame's layout; CANFD_MTU for an FD frame, CANFD_BRS from
 *  CAN_FRAME_BRS), 0 (out untouched) if id > 0x7FF or the length is not one its kind has. */
size_t cansock_to_linux_fd(const can_frame_t *f, struct canfd_frame *out);

/** Classify size bytes read from an FD socket (CAN_MTU: classic, CANFD_MTU: FD); for a data
 *  frame fill out (flags CAN_FRAME_FD/BRS of an FD frame). Other sizes count as foreign. */
cansock_rx_kind_t cansock_from_linux_fd(const struct canfd_frame *in, size_t size,
                                        can_frame_t *out);

/** Transmit without blocking; false if refused (queue full, bus-off, write error, bad frame). */
bool cansock_send(cansock_t *c, const can_frame_t *f);

/** Next received data frame, consuming error and foreign frames on the way; false if none.
 *  now_us drives the bus-off restart requests (call at least once per tick). */
bool cansock_receive(cansock_t *c, can_frame_t *f, uint64_t now_us);

/** Apply one error frame (bus-off, restarted, error counters); now_us as cansock_receive. */
void cansock_on_error_frame(cansock_t *c, const struct can_frame *f, uint64_t now_us);

/** True when nothing written is still waiting in the socket (SIOCOUTQ is 0, or unknown). */
bool cansock_tx_idle(const cansock_t *c);

#endif /* CANSOCK_H */
