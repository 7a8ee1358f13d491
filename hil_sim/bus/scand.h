/* socketcand-protocol TCP server (the subset python-can's "socketcand" interface uses):
 *   server: "< hi >" on connect; client "< open CHANNEL >" -> "< ok >"; client "< rawmode >" ->
 *   "< ok >"; then client "< send ID DLC B0 B1 ... >" (hex) and server
 *   "< frame ID SEC.USEC HEXDATA >" (%03X standard / %08X extended id, uppercase, no spaces).
 * Each handshake reply is written alone (python-can reads each reply with one recv): the frames
 * of the bus from the moment a client enters raw mode are queued for it, but written only once
 * it has sent its first command in raw mode (it has read the "< ok >" then) or
 * SCAND_FRAME_HOLDOFF_MS after that "< ok >", whichever comes first. No frame is lost meanwhile,
 * so the answer to a request sent right after the handshake reaches the client.
 * Non-blocking sockets, poll() driven by the caller; no threads. Per-client output buffers;
 * a client that does not read fast enough loses frames (counted), like a full CAN rx FIFO. */
#ifndef SCAND_H
#define SCAND_H

#include <poll.h>
#include <stdbool.h>
#include <stdint.h>
#include "can_frame.h"

#define SCAND_MAX_CLIENTS 16u
#define SCAND_IN_BUF 8192u
#define SCAND_OUT_BUF (1u << 20)
#define SCAND_FRAME_HOLDOFF_MS 50u

typedef enum {
    SCAND_FREE = 0,
    SCAND_HELLO = 1,
    SCAND_OPEN = 2,
    SCAND_RAW = 3
} scand_state_t;

typedef struct {
    int fd;
    scand_state_t state;
    char in[SCAND_IN_BUF];
    uint32_t in_len;
    char *out; /* SCAND_OUT_BUF bytes (static storage per slot) */
    uint32_t out_head;
    uint32_t out_len;
    uint64_t frames_from_ms; /* wall ms after which queued frames are written anyway */
    bool hold;               /* raw mode entered, frames queued but not written yet */
    uint64_t frames_in;
    uint64_t frames_out;
    uint64_t dropped;
    uint64_t garbage; /* input discarded: a command longer than SCAND_IN_BUF */
} scand_client_t;

/** A frame a client sent: client index 0..SCAND_MAX_CLIENTS-1. */
typedef void (*scand_frame_fn)(void *ctx, unsigned client, const can_frame_t *f, bool extended);

typedef struct {
    int listen_fd;
    uint16_t port; /* bound port (useful with port 0) */
    char channel[32];
    scand_client_t clients[SCAND_MAX_CLIENTS];
    scand_frame_fn on_frame;
    void *ctx;
    bool verbose;
} scand_t;

/** Listen on host:port (port 0: any free port; the bound one is in s->port). 0 or -1 + err. */
int scand_listen(scand_t *s, const char *host, uint16_t port, const char *channel,
                 scand_frame_fn on_frame, void *ctx, char *err, uint32_t err_len);

/** Fill pollfds (listen socket + clients); returns how many were written (<= max). */
unsigned scand_pollfds(const scand_t *s, struct pollfd *fds, unsigned max);

/** Handle what poll() reported (accept, read, parse, write); now_ms is wall time. */
void scand_handle(scand_t *s, const struct pollfd *fds, unsigned n, uint64_t now_ms);

/** Queue a frame for every client in raw mode except skip_client (-1: none); t_ns is its
 *  timestamp (simulated bus time). */
void scand_broadcast(scand_t *s, int skip_client, const can_frame_t *f, bool extended,
                     uint64_t t_ns);

/** Try to write pending output to every client (non-blocking); now_ms is wall time (ends the
 *  hold-off after the handshake). */
void scand_flush(scand_t *s, uint64_t now_ms);

/** Number of connected clients. */
unsigned scand_clients(const scand_t *s);

/** Close everything. */
void scand_close(scand_t *s);

#endif /* SCAND_H */
