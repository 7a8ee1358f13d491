/* hil_sim serve (see serve.h). One thread: ppoll() on the sockets with a timeout up to the next
 * 1 kHz firmware tick or bus event; simulated time = wall time x speed. */
#define _GNU_SOURCE
#include "serve.h"

#include <errno.h>
#include <math.h>
#include <poll.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "app_config.h"
#include "bus_model.h"
#include "hal_host.h"
#include "proto_ids.h"
#include "scand.h"
#include "sim_couple.h"
#include "sim_model.h"
#include "sim_rng.h"
#include "sim_scenario.h"
#ifdef HIL_SIM_HAVE_SOCKETCAN
#include "serve_socketcan.h"
#endif

#define TICK_NS 1000000ull
#define MAX_LAG_NS 100000000ull /* fall further behind than this: slip (count it) */
#define DEVICE_MAILBOXES 3u     /* transmit mailboxes of the device's controller (bxCAN: 3) */

static const char SERVE_USAGE[] =
    "usage: hil_sim serve [--port PORT] [--host ADDR] [--speed S] [--scenario FILE]\n"
    "                     [--node N] [--channel NAME] [--bitrate BPS] [--duration S] [--verbose]\n"
    "                     [--socketcan IFACE [--fd]]\n"
    "Run the device firmware against the simulated plant in real time (x S) and serve its CAN bus\n"
    "with the socketcand protocol: python-can connects with\n"
    "  can.Bus(interface=\"socketcand\", host=ADDR, port=PORT, channel=NAME)\n"
    "  --port PORT      TCP port (default 29536; 0 = any free port, printed on the first line)\n"
    "  --host ADDR      listen address (default 127.0.0.1)\n"
    "  --speed S        simulated seconds per wall second (default 1)\n"
    "  --scenario FILE  plant, object, operator and sensors (hil_sim/scenarios/*.toml); the\n"
    "                   operator demonstrates whenever the device enters TEACH\n"
    "  --node N         device node id 0..15 (default 0): CAN ids = base + N\n"
    "  --channel NAME   socketcand channel name (default can0)\n"
    "  --bitrate BPS    simulated bus bitrate (default 1000000)\n"
    "  --duration S     exit after S simulated seconds (default: run until SIGINT/SIGTERM)\n"
    "  --host-timeout MS  device's host-silence timeout, 20..500 ms (default 100; raise it when\n"
    "                   the host tools share a heavily loaded machine)\n"
    "fault injection (seeded by the scenario's seed), on frames from clients to the device:\n"
    "  --drop P         lose each frame with probability P\n"
    "  --corrupt P      flip one random data bit of each frame with probability P (E2E/ISO-TP see "
    "it)\n"
    "  --bus-off-at S   the device's controller goes bus-off at S simulated seconds\n"
    "  --bus-off-for S  ... for S seconds (default 0.5)\n"
    "  --drop-telemetry P  lose each telemetry frame of the device with probability P on its way\n"
    "                   to the hosts (an adapter that misses frames)\n"
    "on a real bus instead (docs/hil.md):\n"
    "  --socketcan IFACE  the device on a SocketCAN interface (can0 on an adapter, vcan0): no TCP\n"
    "                   server and no bus model, hosts use python-can's socketcan interface;\n"
    "                   --bitrate then sets the interface's rate with libsocketcan (needs\n"
    "                   CAP_NET_ADMIN; default: as configured); --port, --host, --channel and the\n"
    "                   fault injection options do not apply\n"
    "  --fd             with --socketcan: CAN FD (the interface needs the FD MTU 72): the device\n"
    "                   answers UDS in 64-byte FD frames with bit-rate switching and takes FD\n"
    "                   and classic frames; the cyclic frames stay classic 8-byte frames\n";

static volatile sig_atomic_t g_stop;

static void on_signal(int sig)
{
    (void)sig;
    g_stop = 1;
}

typedef struct {
    sim_scenario_t sc;
    bool have_scenario;
    double speed;
    uint8_t node;
    sim_couple_plant_t plant;
    bus_t bus;
    scand_t sd;
    app_t *app; /* app_device(): one device per process */
    app_config_t app_cfg;
    uint64_t sim_ns;
    uint64_t slips;
    uint64_t wall0;
    uint64_t next_tick_ns;
    double drop_p, corrupt_p, drop_tel_p;
    uint64_t bus_off_from_ns, bus_off_until_ns;
    sim_rng_t rng_faults;
    uint64_t dropped, corrupted, tel_dropped;
} serve_t;

static serve_t S; /* large (bus FIFOs, app): static storage */

static uint64_t mono_ns(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (uint64_t)ts.tv_sec * 1000000000ull + (uint64_t)ts.tv_nsec;
}

static void device_tx_to_bus(serve_t *s, uint64_t t_ns);

static void deliver(void *ctx, const bus_item_t *it, uint64_t t_end_ns)
{
    serve_t *s = ctx;
    if (it->src == 0u) {
        device_tx_to_bus(s, t_end_ns); /* a mailbox is free again */
    }
    if (it->src != 0u && !it->extended) {
        can_frame_t f = it->f;
        if (s->drop_p > 0.0 && sim_rng_uniform(&s->rng_faults) < s->drop_p) {
            s->dropped++;
        } else {
            if (s->corrupt_p > 0.0 && f.len > 0u &&
                sim_rng_uniform(&s->rng_faults) < s->corrupt_p) {
                const unsigned bit = (unsigned)(sim_rng_uniform(&s->rng_faults) * 8.0 *
                                                (double)f.len);
                f.data[(bit / 8u) % f.len] ^= (uint8_t)(1u << (bit % 8u));
                s->corrupted++;
            }
            (void)hal_sim_can_deliver(&f);
        }
    }
    if (it->src == 0u && s->drop_tel_p > 0.0 && !it->extended &&
        (it->f.id == PROTO_ID_TELEM_POS(s->node) || it->f.id == PROTO_ID_TELEM_FORCE(s->node)) &&
        sim_rng_uniform(&s->rng_faults) < s->drop_tel_p) {
        s->tel_dropped++; /* on the bus, but not seen by the hosts */
        return;
    }
    scand_broadcast(&s->sd, it->src == 0u ? -1 : (int)it->src - 1, &it->f, it->extended, t_end_ns);
}

static void on_client_frame(void *ctx, unsigned client, const can_frame_t *f, bool extended)
{
    serve_t *s = ctx;
    (void)bus_enqueue(&s->bus, (uint8_t)(client + 1u), f, extended, s->sim_ns);
}

static void device_boot(serve_t *s)
{
    hal_sim_can_reset();
    hal_host_set_time_us(s->plant.n_tick * 1000u);
    app_init(s->app, &s->app_cfg);
}

/* One 1 ms step: sensors at t, firmware tick, actuator, plant over the tick (sim_couple.h). */
static void sim_tick(serve_t *s)
{
    hal_host_set_time_us(s->plant.n_tick * 1000u);
    hal_sensors_t hs;
    sim_couple_sense(&s->plant, &s->sc, app_state(s->app) == APP_TEACH, app_tick_count(s->app),
                     &hs);
    hal_host_set_sensors(&hs);

    app_tick(s->app, false);
    uint8_t reset_type = 0u;
    if (hal_host_take_reset(&reset_type)) {
        device_boot(s); /* ECUReset: firmware restarts, flash keeps the slots */
    }

    bool enable = false;
    fs_real_t f[2];
    hal_host_get_actuator(&enable, f);
    (void)sim_couple_step(&s->plant, &s->sc, app_state(s->app), enable, f);
}

/* The device's controller: its most urgent queued frames wait in DEVICE_MAILBOXES mailboxes on
 * the bus; when all are busy, a more urgent frame aborts the least urgent waiting one, which goes
 * back to the driver's queue (first among its identifier), as drivers of such controllers do. */
static void device_tx_to_bus(serve_t *s, uint64_t t_ns)
{
    can_frame_t f;
    while (hal_sim_can_tx_peek(&f)) {
        if (bus_pending(&s->bus, 0u) >= DEVICE_MAILBOXES) {
            bus_item_t worst;
            if (!bus_least_urgent(&s->bus, 0u, false, &worst) ||
                busm_key(&f, false) >= busm_key(&worst.f, worst.extended)) {
                return;
            }
            (void)bus_least_urgent(&s->bus, 0u, true, &worst);
            hal_sim_can_tx_pop();
            (void)hal_sim_can_tx_requeue(&worst.f); /* room: f has just left the queue */
            (void)bus_enqueue(&s->bus, 0u, &f, false, t_ns);
            continue;
        }
        if (!bus_enqueue(&s->bus, 0u, &f, false, t_ns)) {
            return;
        }
        hal_sim_can_tx_pop();
    }
}

/* Wait up to wait_ns for socket activity and handle it. Frames read are stamped with s->sim_ns,
 * or with the current simulated time when s->sim_ns is UINT64_MAX. */
static void poll_clients(serve_t *s, struct pollfd *fds, uint64_t wait_ns)
{
    const unsigned nfds = scand_pollfds(&s->sd, fds, SCAND_MAX_CLIENTS + 1u);
    struct timespec to = {(time_t)(wait_ns / 1000000000ull), (long)(wait_ns % 1000000000ull)};
    const int r = ppoll(fds, nfds, &to, NULL);
    if (r <= 0) {
        return;
    }
    if (s->sim_ns == UINT64_MAX) {
        uint64_t now = (uint64_t)((double)(mono_ns() - s->wall0) * s->speed);
        if (now + TICK_NS < s->next_tick_ns) {
            now = s->next_tick_ns - TICK_NS;
        }
        s->sim_ns = now;
    }
    scand_handle(&s->sd, fds, nfds, mono_ns() / 1000000ull);
    for (unsigned i = 0; i < SCAND_MAX_CLIENTS; i++) {
        if (s->sd.clients[i].fd < 0) {
            bus_flush_source(&s->bus, (uint8_t)(i + 1u));
        }
    }
}

static int parse_double(const char *opt, const char *v, double *out)
{
    char *end = NULL;
    errno = 0;
    const double d = strtod(v, &end);
    if (end == v || *end != '\0' || errno != 0 || !isfinite(d)) {
        fprintf(stderr, "hil_sim serve: %s needs a number, got '%s'\n", opt, v);
        return -1;
    }
    *out = d;
    return 0;
}

/* --socketcan: the same device and plant on a SocketCAN interface (serve_socketcan.h) */
#ifdef HIL_SIM_HAVE_SOCKETCAN
static int serve_check_socketcan(const char *ifname, int argc, char **argv)
{
    return serve_socketcan_check(ifname, argc, argv);
}

static void socketcan_tick(void *ctx)
{
    (void)ctx;
    sim_tick(
        &S); /* the one serve_t: passed through ctx, GCC -O2 -fsanitize misreports an overread */
}

static int serve_run_socketcan(serve_t *s, const char *ifname, int argc, char **argv,
                               uint32_t bitrate, double duration, const char *scenario)
{
    const bool fd = s->app_cfg.uds_tx_dl == CAN_FD_MAX_LEN;
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    const serve_socketcan_cfg_t cfg = {
        .ifname = ifname,
        .ops = NULL,
        .bitrate_bps = serve_socketcan_bitrate_given(argc, argv) ? bitrate : 0u,
        .speed = s->speed,
        .end_ns = duration > 0.0 ? (uint64_t)(duration * 1e9) : UINT64_MAX,
        .node = s->node,
        .scenario = scenario,
        .tick = socketcan_tick,
        .ctx = NULL,
        .device_tx_dropped = app_tx_dropped(s->app),
        .stop = &g_stop,
        .fd = fd};
    return serve_socketcan_run(&cfg);
}
#else
static int serve_check_socketcan(const char *ifname, int argc, char **argv)
{
    (void)ifname;
    (void)argc;
    (void)argv;
    fprintf(stderr, "hil_sim serve: --socketcan needs a build with libsocketcan (apt install "
                    "libsocketcan-dev)\n");
    return -1;
}

static int serve_run_socketcan(serve_t *s, const char *ifname, int argc, char **argv,
                               uint32_t bitrate, double duration, const char *scenario)
{
    (void)s, (void)ifname, (void)argc, (void)argv, (void)bitrate, (void)duration, (void)scenario;
    return 2;
}
#endif

/* The options of `hil_sim serve`. */
typedef struct {
    const char *host, *channel, *scenario, *socketcan;
    double port, speed, node, bitrate, duration, host_timeout;
    double drop, corrupt, drop_tel, bus_off_at, bus_off_for;
    bool verbose, fd;
} serve_opts_t;

/* argv into o; -1 to go on, else the exit status (0 after --help, 2 on a usage error). */
static int parse_serve_args(int argc, char **argv, serve_opts_t *o)
{
    const struct {
        const char *name;
        double *num;
        const char **str;
    } opts[] = {{"--port", &o->port, NULL},
                {"--host", NULL, &o->host},
                {"--speed", &o->speed, NULL},
                {"--scenario", NULL, &o->scenario},
                {"--socketcan", NULL, &o->socketcan},
                {"--node", &o->node, NULL},
                {"--channel", NULL, &o->channel},
                {"--bitrate", &o->bitrate, NULL},
                {"--duration", &o->duration, NULL},
                {"--host-timeout", &o->host_timeout, NULL},
                {"--drop", &o->drop, NULL},
                {"--corrupt", &o->corrupt, NULL},
                {"--drop-telemetry", &o->drop_tel, NULL},
                {"--bus-off-at", &o->bus_off_at, NULL},
                {"--bus-off-for", &o->bus_off_for, NULL}};
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(SERVE_USAGE, stdout);
            return 0;
        }
        if (strcmp(a, "--verbose") == 0) {
            o->verbose = true;
            continue;
        }
        if (strcmp(a, "--fd") == 0) {
            o->fd = true;
            continue;
        }
        if (v == NULL) {
            fprintf(stderr, "hil_sim serve: %s needs a value (or unknown option)\n", a);
            return 2;
        }
        size_t k = 0;
        while (k < sizeof opts / sizeof opts[0] && strcmp(a, opts[k].name) != 0) {
            k++;
        }
        if (k == sizeof opts / sizeof opts[0]) {
            fprintf(stderr, "hil_sim serve: unknown option '%s'\n%s", a, SERVE_USAGE);
            return 2;
        }
        if (opts[k].str != NULL) {
            *opts[k].str = v;
        } else if (parse_double(a, v, opts[k].num) != 0) {
            return 2;
        }
        i++;
    }
    return -1;
}

/* The ranges of the options; 0, or -1 after a one-line message. */
static int check_serve_opts(const serve_opts_t *o)
{
    if (!(o->port >= 0.0 && o->port <= 65535.0) || o->port != floor(o->port)) {
        fprintf(stderr, "hil_sim serve: --port must be 0..65535, got %g\n", o->port);
        return -1;
    }
    if (!(o->speed > 0.0 && o->speed <= 1000.0)) {
        fprintf(stderr, "hil_sim serve: --speed must be in (0, 1000], got %g\n", o->speed);
        return -1;
    }
    if (!(o->node >= 0.0 && o->node <= (double)PROTO_NODE_MAX) || o->node != floor(o->node)) {
        fprintf(stderr, "hil_sim serve: --node must be 0..%u, got %g\n", PROTO_NODE_MAX, o->node);
        return -1;
    }
    if (!(o->bitrate >= 10000.0 && o->bitrate <= 1e6)) {
        fprintf(stderr, "hil_sim serve: --bitrate must be 10000..1000000, got %g\n", o->bitrate);
        return -1;
    }
    if (!(o->host_timeout >= (double)WDG_TIMEOUT_MIN_MS &&
          o->host_timeout <= (double)WDG_TIMEOUT_MAX_MS)) {
        fprintf(stderr, "hil_sim serve: --host-timeout must be %u..%u ms, got %g\n",
                WDG_TIMEOUT_MIN_MS, WDG_TIMEOUT_MAX_MS, o->host_timeout);
        return -1;
    }
    if (!(o->drop >= 0.0 && o->drop <= 1.0) || !(o->corrupt >= 0.0 && o->corrupt <= 1.0) ||
        !(o->drop_tel >= 0.0 && o->drop_tel <= 1.0) || !(o->bus_off_for >= 0.0)) {
        fprintf(stderr, "hil_sim serve: --drop/--corrupt/--drop-telemetry must be probabilities "
                        "0..1, --bus-off-for >= 0\n");
        return -1;
    }
    return 0;
}

/* The serve state from the options: injections, the scenario, the device booted on the plant.
 * 0, or -1 after a one-line message. */
static int serve_setup(serve_t *s, const serve_opts_t *o)
{
    memset(s, 0, sizeof(*s));
    s->app = app_device();
    s->drop_p = o->drop;
    s->corrupt_p = o->corrupt;
    s->drop_tel_p = o->drop_tel;
    s->bus_off_from_ns = o->bus_off_at >= 0.0 ? (uint64_t)(o->bus_off_at * 1e9) : UINT64_MAX;
    s->bus_off_until_ns = o->bus_off_at >= 0.0 ? (uint64_t)((o->bus_off_at + o->bus_off_for) * 1e9)
                                               : UINT64_MAX;
    s->speed = o->speed;
    s->node = (uint8_t)o->node;
    char err[SIM_ERR_MAX];
    sim_scenario_defaults(&s->sc);
    if (o->scenario != NULL && sim_scenario_load(&s->sc, o->scenario, err) != 0) {
        fprintf(stderr, "hil_sim serve: %s\n", err);
        return -1;
    }
    /* the device, configured as the scenario's controller */
    sim_couple_device_config(&s->sc, &s->app_cfg);
    s->app_cfg.node = s->node;
    s->app_cfg.saf.wdg.timeout_ms = (uint16_t)o->host_timeout;
    if (o->fd) { /* UDS in 64-byte FD frames, bit-rate switched (the cyclic frames stay 8 bytes) */
        s->app_cfg.uds_tx_dl = CAN_FD_MAX_LEN;
        s->app_cfg.uds_brs = true;
    }
    sim_rng_seed(&s->rng_faults, s->sc.seed ^ 0xFA17FA17FA17FA17ull);
    hal_host_init();
    sim_couple_start(&s->plant, &s->sc);
    device_boot(s);
    return 0;
}

/* Every 1 ms tick due by simulated time target (before end_ns): clients' frames when catching
 * up, the bus, the bus-off window, the device and plant tick, the device's frames. */
static void run_due_ticks(serve_t *s, struct pollfd *fds, uint64_t target, uint64_t *next_tick_ns,
                          uint64_t end_ns)
{
    while (*next_tick_ns <= target && *next_tick_ns < end_ns) {
        const uint64_t t = *next_tick_ns;
        if (target - t >= TICK_NS) {
            /* catching up (the process was descheduled): take what clients sent meanwhile
             * before each tick, so a late burst of ticks does not look like host silence */
            s->sim_ns = t;
            poll_clients(s, fds, 0u);
        }
        bus_run(&s->bus, t, deliver, s);
        s->sim_ns = t;
        hal_sim_can_set_bus_off(t >= s->bus_off_from_ns && t < s->bus_off_until_ns);
        sim_tick(s);
        device_tx_to_bus(s, t);
        *next_tick_ns = t + TICK_NS;
    }
}

/* The real-time loop until a signal or end_ns: ticks on the wall clock scaled by the speed
 * (slipping when the machine cannot keep up), the bus between ticks, the clients polled until
 * the next event. Returns the simulated time reached in ns. */
static uint64_t serve_loop(serve_t *s, double speed, uint64_t end_ns)
{
    uint64_t wall0 = mono_ns();
    uint64_t next_tick_ns = 0u;
    struct pollfd fds[SCAND_MAX_CLIENTS + 1u];
    while (!g_stop && next_tick_ns < end_ns) {
        uint64_t target = (uint64_t)((double)(mono_ns() - wall0) * speed);
        if (target > next_tick_ns + MAX_LAG_NS) {
            /* cannot keep up (machine busy): slip the clock rather than burst ticks */
            wall0 += (uint64_t)((double)(target - next_tick_ns) / speed);
            target = next_tick_ns;
            s->slips++;
        }
        run_due_ticks(s, fds, target, &next_tick_ns, end_ns);
        bus_run(&s->bus, target, deliver, s);
        device_tx_to_bus(s, target);
        s->sim_ns = target;
        scand_flush(&s->sd, mono_ns() / 1000000ull);

        uint64_t next_ev = bus_next_event_ns(&s->bus);
        if (next_ev > next_tick_ns) {
            next_ev = next_tick_ns;
        }
        const uint64_t now_sim = (uint64_t)((double)(mono_ns() - wall0) * speed);
        uint64_t wait_ns = next_ev > now_sim ? (uint64_t)((double)(next_ev - now_sim) / speed) : 0u;
        if (wait_ns > 20000000ull) {
            wait_ns = 20000000ull;
        }
        s->sim_ns = UINT64_MAX; /* poll_clients stamps frames with the time they are read */
        s->wall0 = wall0;
        s->next_tick_ns = next_tick_ns;
        poll_clients(s, fds, wait_ns);
    }
    return next_tick_ns;
}

int bus_cmd_serve(int argc, char **argv)
{
    serve_opts_t o = {.host = "127.0.0.1",
                      .channel = "can0",
                      .port = 29536.0,
                      .speed = 1.0,
                      .bitrate = 1e6,
                      .host_timeout = 100.0,
                      .bus_off_at = -1.0,
                      .bus_off_for = 0.5};
    const int status = parse_serve_args(argc, argv, &o);
    if (status >= 0) {
        return status;
    }
    if (o.fd && o.socketcan == NULL) {
        fprintf(stderr,
                "hil_sim serve: --fd needs --socketcan (the simulated bus is classic CAN)\n");
        return 2;
    }
    if (check_serve_opts(&o) != 0 ||
        (o.socketcan != NULL && serve_check_socketcan(o.socketcan, argc, argv) != 0)) {
        return 2;
    }
    serve_t *s = &S;
    if (serve_setup(s, &o) != 0) {
        return 2;
    }
    if (o.socketcan != NULL) {
        return serve_run_socketcan(s, o.socketcan, argc, argv, (uint32_t)o.bitrate, o.duration,
                                   o.scenario);
    }
    bus_init(&s->bus, (uint32_t)o.bitrate);
    char err[SIM_ERR_MAX];
    if (scand_listen(&s->sd, o.host, (uint16_t)o.port, o.channel, on_client_frame, s, err,
                     sizeof(err)) != 0) {
        fprintf(stderr, "hil_sim serve: %s\n", err);
        return 1;
    }
    s->sd.verbose = o.verbose;
    signal(SIGINT, on_signal);
    signal(SIGTERM, on_signal);
    signal(SIGPIPE, SIG_IGN);
    printf("hil_sim serve: listening on %s:%u channel %s node %u speed %g bitrate %u%s%s\n", o.host,
           (unsigned)s->sd.port, o.channel, (unsigned)s->node, o.speed, (unsigned)o.bitrate,
           o.scenario != NULL ? " scenario " : "", o.scenario != NULL ? o.scenario : "");
    fflush(stdout);
    const uint64_t end_ns = o.duration > 0.0 ? (uint64_t)(o.duration * 1e9) : UINT64_MAX;
    const uint64_t next_tick_ns = serve_loop(s, o.speed, end_ns);
    scand_close(&s->sd);
    fprintf(stderr,
            "hil_sim serve: stopped at %.3f s simulated; bus %llu frames, load %.1f %%; %llu clock "
            "slips; "
            "device rx overflows %u, tx dropped %u; injected: %llu lost, %llu corrupted, %llu "
            "telemetry frames lost\n",
            (double)next_tick_ns * 1e-9, (unsigned long long)s->bus.frames,
            next_tick_ns > 0u
                ? 100.0 * (double)s->bus.bits * (double)s->bus.bit_ns / (double)next_tick_ns
                : 0.0,
            (unsigned long long)s->slips, hal_sim_can_rx_overflows(), *app_tx_dropped(s->app),
            (unsigned long long)s->dropped, (unsigned long long)s->corrupted,
            (unsigned long long)s->tel_dropped);
    return 0;
}
