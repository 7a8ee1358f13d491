/* hil_sim pil (see sim_pil.h). Builds nothing: finds the image in the build tree (or --image),
 * packs the scenario into the image's parameter block (sim_params.h), keeps the board's flash in
 * a file (the PSRAM, memory-backend-file: survives board resets and, with --flash, restarts),
 * starts qemu and runs until SIGINT/SIGTERM. */
#define _GNU_SOURCE
#include "sim_pil.h"

#include <arpa/inet.h>
#include <errno.h>
#include <math.h>
#include <netinet/in.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/random.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <time.h>
#include <unistd.h>

#include "cm_board.h"
#include "cm_devinfo.h"
#include "hal_host.h"
#include "sim_params.h"
#include "sim_scenario.h"

#ifndef FS_SOURCE_DIR
#define FS_SOURCE_DIR "."
#endif

#define PIL_FLASH_BYTES CM_PSRAM_SIZE /* the board's PSRAM */
#define PIL_MAX_EXTRA 16

static const char PIL_USAGE[] =
    "usage: hil_sim pil --target cortex-m4f|cortex-m3 [--port PORT] [--host ADDR] [--image ELF]\n"
    "                   [--scenario FILE] [--flash FILE] [--node N] [--host-timeout MS]\n"
    "                   [--icount-shift K] [--qemu EXE] [--qemu-arg ARG]...\n"
    "Run the product's Cortex-M image (hil_sim/pil fs_pil.elf) under qemu with the\n"
    "simulator's plant linked in; its UART0 carries the CAN bus in SLCAN on a TCP port:\n"
    "  forceskill status -i slcan -c socket://ADDR:PORT\n"
    "  --target T       cortex-m4f (mps2-an386) or cortex-m3 (mps2-an385)\n"
    "  --port PORT      TCP port of the board's serial port (default 29537; 0 = any free port)\n"
    "  --host ADDR      listen address (default 127.0.0.1)\n"
    "  --image ELF      the image (default: build/<target>/hil_sim/pil/fs_pil.elf)\n"
    "  --scenario FILE  plant, object, operator and sensors (hil_sim/scenarios/*.toml)\n"
    "  --flash FILE     the board's flash (created erased if missing; default: a fresh one,\n"
    "                   removed at exit)\n"
    "  --node N         device node id 0..15 (default 0)\n"
    "  --host-timeout MS  device's host-silence timeout, 20..500 ms (default 100)\n"
    "  --icount-shift K qemu -icount shift (default 2: 4 ns per instruction, 250 MIPS; the\n"
    "                   cortex-m3 image, float in software, 1: 500 MIPS): the\n"
    "                   board's clock follows its instructions; the image paces it to the host's\n"
    "                   clock (never ahead of it; behind when qemu cannot keep up)\n"
    "  --qemu EXE       qemu-system-arm to run (default: from PATH)\n"
    "  --qemu-arg ARG   one more argument for qemu (repeatable; e.g. the exec trace of\n"
    "                   bench/qemu_tick.sh)\n"
    "Runs until SIGINT/SIGTERM; one client at a time (a serial port).\n";

static volatile sig_atomic_t g_stop;

static void on_signal(int sig)
{
    (void)sig;
    g_stop = 1;
}

static int parse_num(const char *opt, const char *v, double lo, double hi, double *out)
{
    char *end = NULL;
    errno = 0;
    const double d = strtod(v, &end);
    if (end == v || *end != '\0' || errno != 0 || !(d >= lo && d <= hi) || d != floor(d)) {
        fprintf(stderr, "hil_sim pil: %s must be an integer %g..%g, got '%s'\n", opt, lo, hi, v);
        return -1;
    }
    *out = d;
    return 0;
}

/* A free TCP port on host (bound then released). */
static int free_port(const char *host)
{
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) {
        return -1;
    }
    struct sockaddr_in a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = 0;
    if (inet_pton(AF_INET, host, &a.sin_addr) != 1 ||
        bind(fd, (struct sockaddr *)&a, sizeof a) != 0) {
        close(fd);
        return -1;
    }
    socklen_t len = sizeof a;
    const int rc = getsockname(fd, (struct sockaddr *)&a, &len);
    close(fd);
    return rc == 0 ? (int)ntohs(a.sin_port) : -1;
}

/* True once something listens on host:port. */
static int can_connect(const char *host, int port)
{
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) {
        return 0;
    }
    struct sockaddr_in a;
    memset(&a, 0, sizeof a);
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)port);
    (void)inet_pton(AF_INET, host, &a.sin_addr);
    const int ok = connect(fd, (struct sockaddr *)&a, sizeof a) == 0;
    close(fd);
    return ok;
}

/* Create path as an erased flash (0xFF) of PIL_FLASH_BYTES if it does not exist. */
static int flash_file(const char *path)
{
    struct stat st;
    if (stat(path, &st) == 0) {
        if ((uint64_t)st.st_size != PIL_FLASH_BYTES) {
            fprintf(stderr, "hil_sim pil: flash file %s is %lld bytes, not %u\n", path,
                    (long long)st.st_size, PIL_FLASH_BYTES);
            return -1;
        }
        return 0;
    }
    FILE *f = fopen(path, "wb");
    if (f == NULL) {
        fprintf(stderr, "hil_sim pil: cannot create flash file %s: %s\n", path, strerror(errno));
        return -1;
    }
    static uint8_t block[65536];
    memset(block, 0xFF, sizeof block);
    for (uint32_t n = 0; n < PIL_FLASH_BYTES; n += (uint32_t)sizeof block) {
        if (fwrite(block, 1, sizeof block, f) != sizeof block) {
            fclose(f);
            fprintf(stderr, "hil_sim pil: cannot write flash file %s\n", path);
            return -1;
        }
    }
    return fclose(f) == 0 ? 0 : -1;
}

/* Provision the board's device-unique area (cm_devinfo.h) in the flash file at path if it is
 * erased: the simulator's documented SecurityAccess secrets, one per level (as the host port). */
static int provision(const char *path)
{
    FILE *f = fopen(path, "r+b");
    uint8_t rec[CM_DEVINFO_SECRET_OFF(CM_DEVINFO_LEVELS)];
    if (f == NULL || fseek(f, (long)CM_DEVINFO_OFFSET, SEEK_SET) != 0 ||
        fread(rec, 1, 4, f) != 4u) {
        fprintf(stderr, "hil_sim pil: cannot read flash file %s\n", path);
        if (f != NULL) {
            fclose(f);
        }
        return -1;
    }
    if (rec[0] != 0xFFu || rec[1] != 0xFFu || rec[2] != 0xFFu || rec[3] != 0xFFu) {
        return fclose(f) == 0 ? 0 : -1; /* provisioned before: keep it */
    }
    memset(rec, 0xFF, sizeof rec);
    const char *secret[CM_DEVINFO_LEVELS] = {HAL_HOST_SECRET_DEFAULT, HAL_HOST_FW_SECRET_DEFAULT};
    for (uint32_t i = 0; i < 4u; i++) {
        rec[i] = (uint8_t)(CM_DEVINFO_MAGIC >> (8u * i));
        rec[4u + i] = (uint8_t)(CM_DEVINFO_VERSION >> (8u * i));
    }
    for (uint32_t l = 0; l < CM_DEVINFO_LEVELS; l++) {
        const size_t n = strlen(secret[l]);
        rec[CM_DEVINFO_SECRET_OFF(l)] = (uint8_t)n;
        memcpy(&rec[CM_DEVINFO_SECRET_OFF(l) + 1u], secret[l], n);
    }
    const int ok = fseek(f, (long)CM_DEVINFO_OFFSET, SEEK_SET) == 0 &&
                   fwrite(rec, 1, sizeof rec, f) == sizeof rec;
    if (fclose(f) != 0 || !ok) {
        fprintf(stderr, "hil_sim pil: cannot write flash file %s\n", path);
        return -1;
    }
    return 0;
}

/* The command line of `hil_sim pil`. */
typedef struct {
    const char *target, *host, *image, *scenario, *flash, *qemu;
    double port, node, host_timeout, shift;
    char *extra[PIL_MAX_EXTRA];
    int n_extra;
} pil_opts_t;

/* Parse the options into *o: -1 to go on, else the exit status (0 after --help, 2 on an error). */
static int pil_parse(int argc, char **argv, pil_opts_t *o)
{
    for (int i = 0; i < argc; i++) {
        const char *a = argv[i];
        const char *v = (i + 1 < argc) ? argv[i + 1] : NULL;
        if (strcmp(a, "-h") == 0 || strcmp(a, "--help") == 0) {
            fputs(PIL_USAGE, stdout);
            return 0;
        }
        if (v == NULL) {
            fprintf(stderr, "hil_sim pil: %s needs a value (or unknown option)\n", a);
            return 2;
        }
        int rc = 0;
        if (strcmp(a, "--target") == 0)
            o->target = v;
        else if (strcmp(a, "--port") == 0)
            rc = parse_num(a, v, 0.0, 65535.0, &o->port);
        else if (strcmp(a, "--host") == 0)
            o->host = v;
        else if (strcmp(a, "--image") == 0)
            o->image = v;
        else if (strcmp(a, "--scenario") == 0)
            o->scenario = v;
        else if (strcmp(a, "--flash") == 0)
            o->flash = v;
        else if (strcmp(a, "--node") == 0)
            rc = parse_num(a, v, 0.0, 15.0, &o->node);
        else if (strcmp(a, "--host-timeout") == 0)
            rc = parse_num(a, v, 20.0, 500.0, &o->host_timeout);
        else if (strcmp(a, "--icount-shift") == 0)
            rc = parse_num(a, v, 0.0, 10.0, &o->shift);
        else if (strcmp(a, "--qemu") == 0)
            o->qemu = v;
        else if (strcmp(a, "--qemu-arg") == 0 && o->n_extra < PIL_MAX_EXTRA)
            o->extra[o->n_extra++] = (char *)v;
        else {
            fprintf(stderr, "hil_sim pil: unknown option '%s'\n%s", a, PIL_USAGE);
            return 2;
        }
        if (rc != 0) {
            return 2;
        }
        i++;
    }
    return -1;
}

/* Start qemu on the board of the target with the image, the parameter block, the flash file and
 * the board's serial port on host:p; the child's pid (or -1). */
static pid_t pil_spawn(const pil_opts_t *o, const char *machine, const char *cpu, int p,
                       const char *params_path, const char *flash_path)
{
    char serial[128], loader[128], backend[SIM_PATH_MAX + 96], icount[64];
    snprintf(serial, sizeof serial, "tcp:%s:%d,server=on,wait=off", o->host, p);
    snprintf(loader, sizeof loader, "loader,file=%s,addr=0x%08X,force-raw=on", params_path,
             (unsigned)CM_PARAMS_ADDR);
    snprintf(backend, sizeof backend, "memory-backend-file,id=flash,size=16M,mem-path=%s,share=on",
             flash_path);
    snprintf(icount, sizeof icount, "shift=%d,sleep=off", (int)o->shift);
    char *qargv[24 + PIL_MAX_EXTRA] = {(char *)o->qemu,
                                       "-M",
                                       (char *)machine,
                                       "-cpu",
                                       (char *)cpu,
                                       "-nographic",
                                       "-monitor",
                                       "none",
                                       "-semihosting-config",
                                       "enable=on,target=native",
                                       "-kernel",
                                       (char *)o->image,
                                       "-device",
                                       loader,
                                       "-serial",
                                       serial,
                                       "-object",
                                       backend,
                                       "-machine",
                                       "memory-backend=flash",
                                       "-icount",
                                       icount};
    int qn = 22;
    for (int i = 0; i < o->n_extra; i++) {
        qargv[qn++] = o->extra[i];
    }
    qargv[qn] = NULL;
    const pid_t pid = p > 0 ? fork() : -1;
    if (pid == 0) {
        execvp(o->qemu, qargv);
        fprintf(stderr, "hil_sim pil: cannot run %s: %s\n", o->qemu, strerror(errno));
        _exit(127);
    }
    return pid;
}

/* Wait for the board's serial port, announce it, run until SIGINT/SIGTERM or qemu's exit: 0 when
 * it ran and was stopped, else 1. */
static int pil_supervise(const pil_opts_t *o, pid_t pid, int p, const char *machine)
{
    int wst = 0;
    int up = 0;
    for (int i = 0; i < 500 && !g_stop && !up; i++) {
        if (waitpid(pid, &wst, WNOHANG) == pid) {
            break;
        }
        up = can_connect(o->host, p);
        if (!up) {
            const struct timespec ts = {0, 10000000L};
            nanosleep(&ts, NULL);
        }
    }
    if (up) {
        printf("hil_sim pil: listening on %s:%d target %s (%s) image %s%s%s\n", o->host, p,
               o->target, machine, o->image, o->scenario != NULL ? " scenario " : "",
               o->scenario != NULL ? o->scenario : "");
        fflush(stdout);
        while (!g_stop && waitpid(pid, &wst, WNOHANG) == 0) {
            const struct timespec ts = {0, 50000000L};
            nanosleep(&ts, NULL);
        }
    }
    int status = 1;
    if (waitpid(pid, &wst, WNOHANG) == 0) {
        kill(pid, SIGTERM);
        (void)waitpid(pid, &wst, 0);
        status = up ? 0 : 1;
    } else {
        fprintf(stderr, "hil_sim pil: qemu exited (%d)\n",
                WIFEXITED(wst) ? WEXITSTATUS(wst) : 128 + WTERMSIG(wst));
    }
    if (!up) {
        fprintf(stderr, "hil_sim pil: the board's serial port never listened on %s:%d\n", o->host,
                p);
    }
    return status;
}

/* The board of --target and the image (default: the build tree's): 0, else 2 with a message. */
static int pil_board(pil_opts_t *o, const char **machine, const char **cpu, char *image_buf,
                     size_t image_cap)
{
    if (o->target != NULL && strcmp(o->target, "cortex-m4f") == 0) {
        *machine = "mps2-an386";
        *cpu = "cortex-m4";
    } else if (o->target != NULL && strcmp(o->target, "cortex-m3") == 0) {
        *machine = "mps2-an385";
        *cpu = "cortex-m3";
    } else {
        fprintf(stderr, "hil_sim pil: --target must be cortex-m4f or cortex-m3\n");
        return 2;
    }
    if (o->image == NULL) {
        snprintf(image_buf, image_cap, "%s/build/%s/hil_sim/pil/fs_pil.elf", FS_SOURCE_DIR,
                 o->target);
        o->image = image_buf;
    }
    if (access(o->image, R_OK) != 0) {
        fprintf(stderr,
                "hil_sim pil: no image at %s: build it with `cmake --preset %s && "
                "cmake --build build/%s --target fs_pil` or pass --image\n",
                o->image, o->target, o->target);
        return 2;
    }
    return 0;
}

/* The parameter block the image reads at boot (scenario and device settings) into blk: its
 * length, 0 on an error (reported). */
static uint32_t pil_params(const pil_opts_t *o, uint8_t *blk, uint32_t cap)
{
    sim_scenario_t sc;
    char err[SIM_ERR_MAX];
    sim_scenario_defaults(&sc);
    if (o->scenario != NULL && sim_scenario_load(&sc, o->scenario, err) != 0) {
        fprintf(stderr, "hil_sim pil: %s\n", err);
        return 0u;
    }
    sim_params_dev_t dev;
    memset(&dev, 0, sizeof dev);
    dev.node = (uint32_t)o->node;
    dev.host_timeout_ms = (uint32_t)o->host_timeout;
    dev.flags = SIM_PARAMS_PACE; /* qemu runs with -icount sleep=off */
    if (getrandom(dev.seed, sizeof dev.seed, 0) != (ssize_t)sizeof dev.seed) {
        fprintf(stderr, "hil_sim pil: getrandom failed\n");
        return 0u;
    }
    const uint32_t n = sim_params_pack(&sc, &dev, blk, cap);
    if (n == 0u) {
        fprintf(stderr, "hil_sim pil: the scenario does not fit the image's parameter block\n");
    }
    return n;
}

int sim_cmd_pil(int argc, char **argv)
{
    pil_opts_t o = {NULL,    "127.0.0.1", NULL,  NULL, NULL,   "qemu-system-arm",
                    29537.0, 0.0,         100.0, -1.0, {NULL}, 0};
    const int parsed = pil_parse(argc, argv, &o);
    if (parsed >= 0) {
        return parsed;
    }
    const char *machine = NULL, *cpu = NULL;
    char image_buf[SIM_PATH_MAX + 64];
    if (pil_board(&o, &machine, &cpu, image_buf, sizeof image_buf) != 0) {
        return 2;
    }
    if (o.shift < 0.0) {
        /* the M3 image runs float32 in software: the tick that commits a skill download executes
         * ~240,000 instructions, the whole 1 ms at 250 MIPS (fault 511), so it runs at 500 MIPS */
        o.shift = (strcmp(o.target, "cortex-m3") == 0) ? 1.0 : 2.0;
    }
    static uint8_t blk[SIM_PARAMS_MAX_BYTES];
    const uint32_t blk_len = pil_params(&o, blk, (uint32_t)sizeof blk);
    if (blk_len == 0u) {
        return 2;
    }
    char dir[] = "/tmp/hil_sim_pil.XXXXXX";
    if (mkdtemp(dir) == NULL) {
        fprintf(stderr, "hil_sim pil: cannot create a work folder: %s\n", strerror(errno));
        return 1;
    }
    char params_path[64], flash_tmp[64];
    snprintf(params_path, sizeof params_path, "%s/params.bin", dir);
    snprintf(flash_tmp, sizeof flash_tmp, "%s/flash.bin", dir);
    int status = 1;
    FILE *pf = fopen(params_path, "wb");
    const int wrote = pf != NULL && fwrite(blk, 1, blk_len, pf) == blk_len;
    if (pf != NULL) {
        fclose(pf);
    }
    const char *flash_path = o.flash != NULL ? o.flash : flash_tmp;
    if (!wrote) {
        fprintf(stderr, "hil_sim pil: cannot write the parameter block\n");
    } else if (flash_file(flash_path) == 0 && provision(flash_path) == 0) {
        const int p = (o.port == 0.0) ? free_port(o.host) : (int)o.port;
        signal(SIGINT, on_signal);
        signal(SIGTERM, on_signal);
        const pid_t pid = pil_spawn(&o, machine, cpu, p, params_path, flash_path);
        if (pid < 0) {
            fprintf(stderr, "hil_sim pil: cannot start qemu (port %d)\n", p);
        } else {
            status = pil_supervise(&o, pid, p, machine);
        }
    }
    unlink(params_path);
    unlink(flash_tmp);
    rmdir(dir);
    return status;
}
