/* `hil_sim serve --socketcan IFACE`: the device and plant of `hil_sim serve` on a SocketCAN
 * interface (a real controller or adapter, or vcan) instead of the simulated socketcand bus.
 * The device keeps the host port's transmit and receive queues (hal_can_sim.c: the same depth,
 * order and bus-off behaviour as on the simulated bus); every 1 ms tick the bridge moves the
 * interface's frames into the receive queue through the port's SocketCAN driver (cansock.h:
 * frame conversion, error frames, bus-off and its restart), passes the driver's bus-off state to
 * the device's controller, runs the tick, then writes queued frames while the interface takes
 * them (a full interface queue leaves them queued, as a busy bus does). Time is wall time x
 * speed; hosts on a real bus expect speed 1. */
#ifndef SERVE_SOCKETCAN_H
#define SERVE_SOCKETCAN_H

#include <signal.h>
#include <stdbool.h>
#include <stdint.h>

#include "cansock.h"

/** One 1 ms step of the device and the plant. */
typedef void (*serve_tick_fn)(void *ctx);

/** What to run and where. */
typedef struct {
    const char *ifname;
    const cansock_ops_t *ops; /* NULL: the Linux ones (AF_CAN + libsocketcan) */
    uint32_t bitrate_bps;     /* 0: the interface as configured */
    double speed;             /* simulated seconds per wall second */
    uint64_t end_ns;          /* stop at this simulated time (UINT64_MAX: when *stop) */
    uint8_t node;
    const char *scenario; /* for the first line; NULL: the default scenario */
    serve_tick_fn tick;
    void *ctx;
    const uint32_t *device_tx_dropped; /* the device's count of frames it could not queue */
    volatile sig_atomic_t *stop;       /* set by a signal handler */
    bool fd;                           /* CAN FD frames (cansock_enable_fd) */
} serve_socketcan_cfg_t;

/** Open the interface and run until stopped; 0, or 1 with one line on stderr (no AF_CAN, no
 *  such interface, fd on an interface without the CAN FD MTU). A refused bit rate is one line on stderr, and the run goes on. */
int serve_socketcan_run(const serve_socketcan_cfg_t *cfg);

/** Check the command line of `serve --socketcan ifname`: 0, or -1 with one line on stderr (an
 *  invalid interface name, an option of the simulated bus). */
int serve_socketcan_check(const char *ifname, int argc, char *const *argv);

/** True if argv sets --bitrate (without it the interface keeps its rate). */
bool serve_socketcan_bitrate_given(int argc, char *const *argv);

/** Bridge, before the tick: frames from the interface into the device's receive queue while it
 *  has room (the rest stay queued in the socket), the driver's bus-off state to the device's
 *  controller (now_us: simulated time). */
void serve_socketcan_rx(cansock_t *c, uint64_t now_us);

/** Bridge, after the tick: the device's queued frames to the interface while it takes them. */
void serve_socketcan_tx(cansock_t *c);

#endif /* SERVE_SOCKETCAN_H */
