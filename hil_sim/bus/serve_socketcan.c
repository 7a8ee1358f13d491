/* hil_sim serve --socketcan (see serve_socketcan.h). One thread: the ticks due by wall time x
 * speed, then sleep until the next one. */
#define _GNU_SOURCE
#include "serve_socketcan.h"

#include <errno.h>
#include <stdio.h>
#include <string.h>
#include <time.h>

#include "hal_host.h"

#define TICK_NS 1000000ull
#define MAX_LAG_NS 100000000ull /* fall further behind than this: slip (count it) */

/* options of the simulated bus (TCP server, bus model, fault injection on it) */
static const char *const TCP_BUS_OPTIONS[] = {"--port",    "--host",       "--channel",    "--drop",
                                              "--corrupt", "--bus-off-at", "--bus-off-for"};

static bool has_option(int argc, char *const *argv, const char *opt)
{
    for (int i = 0; i < argc; i++) {
        if (strcmp(argv[i], opt) == 0) {
            return true;
        }
    }
    return false;
}

int serve_socketcan_check(const char *ifname, int argc, char *const *argv)
{
    if (!cansock_valid_ifname(ifname)) {
        fprintf(stderr,
                "hil_sim serve: --socketcan needs an interface name of 1..%u characters without "
                "'/', ':' or spaces, got '%.40s'\n",
                CANSOCK_IFNAME_MAX - 1u, ifname);
        return -1;
    }
    for (size_t k = 0; k < sizeof(TCP_BUS_OPTIONS) / sizeof(TCP_BUS_OPTIONS[0]); k++) {
        if (has_option(argc, argv, TCP_BUS_OPTIONS[k])) {
            fprintf(stderr,
                    "hil_sim serve: %s applies to the simulated bus, not with --socketcan\n",
                    TCP_BUS_OPTIONS[k]);
            return -1;
        }
    }
    return 0;
}

bool serve_socketcan_bitrate_given(int argc, char *const *argv)
{
    return has_option(argc, argv, "--bitrate");
}

void serve_socketcan_rx(cansock_t *c, uint64_t now_us)
{
    /* No more than the device's FIFO takes: the rest waits in the socket's receive queue. A
     * SocketCAN interface without a bit rate (vcan) hands over a host's burst at once (ISO-TP
     * consecutive frames at STmin 0, a late cyclic task catching up) that a bus would spread
     * over milliseconds; bus-off still reads (and drops) everything, error frames included. */
    can_frame_t f;
    while ((c->bus_off || hal_sim_can_rx_free() > 0u) && cansock_receive(c, &f, now_us)) {
        (void)hal_sim_can_deliver(&f); /* off the bus: dropped (counted) */
    }
    hal_sim_can_set_bus_off(c->bus_off); /* bus-off empties the device's transmit queue */
}

void serve_socketcan_tx(cansock_t *c)
{
    can_frame_t f;
    while (hal_sim_can_tx_peek(&f) && cansock_send(c, &f)) {
        hal_sim_can_tx_pop();
    }
}

static uint64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

static void sleep_until_ns(uint64_t t_ns)
{
    const struct timespec ts = {(time_t)(t_ns / 1000000000ull), (long)(t_ns % 1000000000ull)};
    (void)clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &ts, NULL); /* a signal ends it early */
}

/* What the driver saw since the last tick, one line each on stderr: bus-off and back, and the
 * first of each kind of failure (a restart refused, a write error). */
typedef struct {
    bool bus_off;
    int restart_errno;
    int tx_errno;
} seen_t;

static void report_events(const cansock_t *c, seen_t *seen, uint64_t t_ns)
{
    const double t_s = (double)t_ns * 1e-9;
    if (c->bus_off != seen->bus_off) {
        if (c->bus_off) {
            fprintf(stderr,
                    "hil_sim serve: %s bus-off at %.3f s (device fault 501); restart requested "
                    "every %u ms\n",
                    c->ifname, t_s, CANSOCK_RESTART_MS);
        } else {
            fprintf(stderr, "hil_sim serve: %s back on the bus at %.3f s\n", c->ifname, t_s);
        }
        seen->bus_off = c->bus_off;
    }
    if (c->last_restart_errno != 0 && c->last_restart_errno != seen->restart_errno) {
        fprintf(stderr,
                "hil_sim serve: restart of %s failed: %s (it needs CAP_NET_ADMIN; or let the "
                "interface restart itself: ip link set %s type can restart-ms 100)\n",
                c->ifname, strerror(c->last_restart_errno), c->ifname);
        seen->restart_errno = c->last_restart_errno;
    }
    if (c->last_tx_errno != 0 && c->last_tx_errno != seen->tx_errno) {
        fprintf(stderr,
                "hil_sim serve: writing to %s failed at %.3f s: %s (frames are lost until it "
                "works)\n",
                c->ifname, t_s, strerror(c->last_tx_errno));
        seen->tx_errno = c->last_tx_errno;
    }
}

int serve_socketcan_run(const serve_socketcan_cfg_t *cfg)
{
    static cansock_t drv;
    char err[320];
    if (cansock_open(&drv, cfg->ops, cfg->ifname, err, sizeof(err)) != 0) {
        fprintf(stderr, "hil_sim serve: %s\n", err);
        return 1;
    }
    if (cfg->fd && cansock_enable_fd(&drv, err, sizeof(err)) != 0) {
        fprintf(stderr, "hil_sim serve: --fd: %s\n", err);
        cansock_close(&drv);
        return 1;
    }
    char rate[48] = "as configured";
    if (cfg->bitrate_bps > 0u) {
        if (cansock_set_bitrate(&drv, cfg->bitrate_bps, err, sizeof(err)) < 0) {
            fprintf(stderr, "hil_sim serve: %s; --bitrate ignored\n", err);
        } else {
            snprintf(rate, sizeof(rate), "%u", cfg->bitrate_bps);
        }
    }
    printf("hil_sim serve: on SocketCAN %s%s node %u speed %g bitrate %s%s%s\n", drv.ifname,
           drv.fd_mode ? " (CAN FD)" : "", (unsigned)cfg->node, cfg->speed, rate,
           cfg->scenario != NULL ? " scenario " : "", cfg->scenario != NULL ? cfg->scenario : "");
    fflush(stdout);

    seen_t seen = {false, 0, 0};
    uint64_t wall0 = mono_ns();
    uint64_t next_ns = 0u;
    uint64_t slips = 0u;
    while (!*cfg->stop && next_ns < cfg->end_ns) {
        uint64_t target = (uint64_t)((double)(mono_ns() - wall0) * cfg->speed);
        if (target > next_ns + MAX_LAG_NS) {
            /* cannot keep up (machine busy): slip the clock rather than burst ticks */
            wall0 += (uint64_t)((double)(target - next_ns) / cfg->speed);
            target = next_ns;
            slips++;
        }
        while (next_ns <= target && next_ns < cfg->end_ns) {
            serve_socketcan_rx(&drv, next_ns / 1000u);
            cfg->tick(cfg->ctx);
            serve_socketcan_tx(&drv);
            report_events(&drv, &seen, next_ns);
            next_ns += TICK_NS;
        }
        sleep_until_ns(wall0 + (uint64_t)((double)next_ns / cfg->speed));
    }
    const cansock_stats_t *st = &drv.st;
    fprintf(
        stderr,
        "hil_sim serve: stopped at %.3f s simulated; SocketCAN %s: %u frames in (%u FD), %u out "
        "(%u FD), %u refused "
        "(queue full), %u write errors, %u error frames, %u bus-off, %u restarts (%u failed), %u "
        "extended/remote ignored; %llu clock slips; device rx overflows %u, tx dropped %u\n",
        (double)next_ns * 1e-9, drv.ifname, st->rx_frames, st->rx_fd_frames, st->tx_frames,
        st->tx_fd_frames, st->tx_full, st->tx_errors, st->error_frames, st->bus_offs, st->restarts,
        st->restart_failures, st->rx_foreign, (unsigned long long)slips, hal_sim_can_rx_overflows(),
        cfg->device_tx_dropped != NULL ? *cfg->device_tx_dropped : 0u);
    cansock_close(&drv);
    return 0;
}
