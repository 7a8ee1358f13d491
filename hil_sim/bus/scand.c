/* socketcand-protocol server (see scand.h). */
#define _GNU_SOURCE
#include "scand.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <unistd.h>

static char g_out_mem[SCAND_MAX_CLIENTS][SCAND_OUT_BUF];

int scand_listen(scand_t *s, const char *host, uint16_t port, const char *channel,
                 scand_frame_fn on_frame, void *ctx, char *err, uint32_t err_len)
{
    memset(s, 0, sizeof(*s));
    s->listen_fd = -1;
    for (unsigned i = 0; i < SCAND_MAX_CLIENTS; i++) {
        s->clients[i].fd = -1;
        s->clients[i].out = g_out_mem[i];
    }
    snprintf(s->channel, sizeof(s->channel), "%s", channel);
    s->on_frame = on_frame;
    s->ctx = ctx;
    const int fd = socket(AF_INET, SOCK_STREAM, 0);
    if (fd < 0) {
        snprintf(err, err_len, "socket: %s", strerror(errno));
        return -1;
    }
    const int one = 1;
    (void)setsockopt(fd, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
    struct sockaddr_in a;
    memset(&a, 0, sizeof(a));
    a.sin_family = AF_INET;
    a.sin_port = htons(port);
    if (inet_pton(AF_INET, host, &a.sin_addr) != 1) {
        snprintf(err, err_len, "bad host address '%s'", host);
        close(fd);
        return -1;
    }
    if (bind(fd, (struct sockaddr *)&a, sizeof(a)) != 0 || listen(fd, 8) != 0) {
        snprintf(err, err_len, "cannot listen on %s:%u: %s", host, (unsigned)port, strerror(errno));
        close(fd);
        return -1;
    }
    socklen_t alen = sizeof(a);
    (void)getsockname(fd, (struct sockaddr *)&a, &alen);
    s->port = ntohs(a.sin_port);
    (void)fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
    s->listen_fd = fd;
    return 0;
}

unsigned scand_pollfds(const scand_t *s, struct pollfd *fds, unsigned max)
{
    unsigned n = 0u;
    if (max == 0u) {
        return 0u;
    }
    fds[n].fd = s->listen_fd;
    fds[n].events = POLLIN;
    fds[n].revents = 0;
    n++;
    for (unsigned i = 0; i < SCAND_MAX_CLIENTS && n < max; i++) {
        const scand_client_t *c = &s->clients[i];
        if (c->fd < 0) {
            continue;
        }
        fds[n].fd = c->fd;
        fds[n].events = (short)(POLLIN | (c->out_len > 0u && !c->hold ? POLLOUT : 0));
        fds[n].revents = 0;
        n++;
    }
    return n;
}

static void drop_client(scand_t *s, scand_client_t *c)
{
    if (s->verbose) {
        fprintf(stderr,
                "hil_sim serve: client %d left (%llu frames in, %llu out, %llu dropped, "
                "%llu input bytes discarded)\n",
                (int)(c - s->clients), (unsigned long long)c->frames_in,
                (unsigned long long)c->frames_out, (unsigned long long)c->dropped,
                (unsigned long long)c->garbage);
    }
    close(c->fd);
    c->fd = -1;
    c->state = SCAND_FREE;
    c->hold = false;
    c->in_len = 0u;
    c->out_len = 0u;
    c->out_head = 0u;
}

/* A handshake reply: written alone and directly (the output buffer is empty before raw mode). */
static void reply(scand_t *s, scand_client_t *c, const char *msg)
{
    const size_t n = strlen(msg);
    if (send(c->fd, msg, n, MSG_NOSIGNAL) != (ssize_t)n) {
        drop_client(s, c);
    }
}

static int hexval(char ch)
{
    if (ch >= '0' && ch <= '9')
        return ch - '0';
    if (ch >= 'a' && ch <= 'f')
        return ch - 'a' + 10;
    if (ch >= 'A' && ch <= 'F')
        return ch - 'A' + 10;
    return -1;
}

static bool parse_hex_token(const char *tok, uint32_t *out, unsigned max_digits)
{
    uint32_t v = 0u;
    unsigned n = 0u;
    for (; *tok != '\0'; tok++, n++) {
        const int h = hexval(*tok);
        if (h < 0 || n >= max_digits) {
            return false;
        }
        v = (v << 4) | (uint32_t)h;
    }
    if (n == 0u) {
        return false;
    }
    *out = v;
    return true;
}

/* "< send ID DLC B0 ... >" -> frame; false if malformed. */
static bool parse_send(char *body, can_frame_t *f, bool *ext)
{
    char *save = NULL;
    char *tok = strtok_r(body, " ", &save); /* "send" */
    tok = strtok_r(NULL, " ", &save);
    uint32_t id = 0u;
    if (tok == NULL || !parse_hex_token(tok, &id, 8u)) {
        return false;
    }
    *ext = strlen(tok) > 3u || id > 0x7FFu;
    if ((*ext && id > 0x1FFFFFFFu)) {
        return false;
    }
    tok = strtok_r(NULL, " ", &save);
    uint32_t dlc = 0u;
    if (tok == NULL || !parse_hex_token(tok, &dlc, 1u) || dlc > CAN_CLASSIC_MAX_LEN) {
        return false;
    }
    f->id = id;
    f->len = (uint8_t)dlc;
    f->flags = 0u; /* socketcand's "send" carries classic frames */
    memset(f->data, 0, sizeof(f->data));
    for (uint32_t i = 0; i < dlc; i++) {
        tok = strtok_r(NULL, " ", &save);
        uint32_t b = 0u;
        if (tok == NULL || !parse_hex_token(tok, &b, 2u)) {
            return false;
        }
        f->data[i] = (uint8_t)b;
    }
    return strtok_r(NULL, " ", &save) == NULL;
}

static void handle_command(scand_t *s, scand_client_t *c, char *cmd, uint64_t now_ms)
{
    /* cmd is the text between '<' and '>' with surrounding blanks trimmed */
    char word[16] = {0};
    sscanf(cmd, "%15s", word);
    if (c->state == SCAND_HELLO) {
        char chan[64] = {0};
        if (strcmp(word, "open") == 0 && sscanf(cmd, "open %63s", chan) == 1) {
            if (strcmp(chan, s->channel) == 0) {
                c->state = SCAND_OPEN;
                reply(s, c, "< ok >");
            } else {
                reply(s, c, "< error could not open bus >");
            }
            return;
        }
        reply(s, c, "< error unknown command >");
        return;
    }
    if (c->state == SCAND_OPEN) {
        if (strcmp(word, "rawmode") == 0) {
            c->state = SCAND_RAW;
            c->hold = true; /* frames queue from now on (see scand.h) */
            c->frames_from_ms = now_ms + SCAND_FRAME_HOLDOFF_MS;
            reply(s, c, "< ok >");
            return;
        }
        reply(s, c, "< error unknown command >");
        return;
    }
    c->hold = false; /* it read "< ok >": frames may flow */
    if (strcmp(word, "send") == 0) {
        can_frame_t f;
        bool ext = false;
        if (parse_send(cmd, &f, &ext)) {
            c->frames_in++;
            s->on_frame(s->ctx, (unsigned)(c - s->clients), &f, ext);
        } else if (s->verbose) {
            fprintf(stderr, "hil_sim serve: malformed send ignored\n");
        }
        return;
    }
    if (strcmp(word, "echo") == 0) {
        /* keep-alive of socketcand: answered in-band */
        static const char msg[] = "< echo >";
        if (c->out_len + sizeof(msg) - 1u <= SCAND_OUT_BUF) {
            for (size_t i = 0; i + 1u < sizeof(msg); i++) {
                c->out[(c->out_head + c->out_len + i) % SCAND_OUT_BUF] = msg[i];
            }
            c->out_len += (uint32_t)(sizeof(msg) - 1u);
        }
    }
    /* other commands of socketcand's raw mode are ignored */
}

/* Handle every complete "< ... >" command in the input buffer and keep the incomplete rest. */
static void parse_client(scand_t *s, scand_client_t *c, uint64_t now_ms)
{
    uint32_t pos = 0u;
    for (;;) {
        char *lt = memchr(c->in + pos, '<', c->in_len - pos);
        if (lt == NULL) {
            pos = c->in_len;
            break;
        }
        char *gt = memchr(lt, '>', (size_t)(c->in + c->in_len - lt));
        if (gt == NULL) {
            pos = (uint32_t)(lt - c->in);
            break;
        }
        *gt = '\0';
        char *b = lt + 1;
        while (*b == ' ')
            b++;
        char *e = gt - 1;
        while (e > b && *e == ' ')
            *e-- = '\0';
        handle_command(s, c, b, now_ms);
        if (c->fd < 0) {
            return;
        }
        pos = (uint32_t)(gt - c->in) + 1u;
    }
    memmove(c->in, c->in + pos, c->in_len - pos);
    c->in_len -= pos;
}

/* Read what the client sent, parsing after every read: a burst larger than the input buffer
 * (a 4 KB ISO-TP message is ~590 "< send >" commands, ~24 KB) is handled piece by piece. Only a
 * buffer full of one unterminated command is discarded (garbage). */
static void read_client(scand_t *s, scand_client_t *c, uint64_t now_ms)
{
    for (;;) {
        if (c->in_len >= SCAND_IN_BUF - 1u) {
            c->garbage += c->in_len; /* one "command" longer than the buffer */
            c->in_len = 0u;
        }
        const ssize_t n = recv(c->fd, c->in + c->in_len, SCAND_IN_BUF - 1u - c->in_len, 0);
        if (n == 0) {
            drop_client(s, c);
            return;
        }
        if (n < 0) {
            if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
                drop_client(s, c);
            }
            return;
        }
        c->in_len += (uint32_t)n;
        parse_client(s, c, now_ms);
        if (c->fd < 0) {
            return;
        }
    }
}

static void write_client(scand_t *s, scand_client_t *c)
{
    while (c->out_len > 0u && !c->hold) {
        uint32_t chunk = SCAND_OUT_BUF - c->out_head;
        if (chunk > c->out_len) {
            chunk = c->out_len;
        }
        const ssize_t n = send(c->fd, c->out + c->out_head, chunk, MSG_NOSIGNAL | MSG_DONTWAIT);
        if (n < 0) {
            if (errno != EAGAIN && errno != EWOULDBLOCK && errno != EINTR) {
                drop_client(s, c);
            }
            return;
        }
        c->out_head = (c->out_head + (uint32_t)n) % SCAND_OUT_BUF;
        c->out_len -= (uint32_t)n;
        if ((uint32_t)n < chunk) {
            return;
        }
    }
}

void scand_handle(scand_t *s, const struct pollfd *fds, unsigned n, uint64_t now_ms)
{
    for (unsigned k = 0; k < n; k++) {
        if (fds[k].revents == 0) {
            continue;
        }
        if (fds[k].fd == s->listen_fd) {
            for (;;) {
                const int fd = accept(s->listen_fd, NULL, NULL);
                if (fd < 0) {
                    break;
                }
                scand_client_t *c = NULL;
                for (unsigned i = 0; i < SCAND_MAX_CLIENTS; i++) {
                    if (s->clients[i].fd < 0) {
                        c = &s->clients[i];
                        break;
                    }
                }
                if (c == NULL) {
                    static const char full[] = "< error too many clients >";
                    (void)send(fd, full, sizeof(full) - 1u, MSG_NOSIGNAL);
                    close(fd);
                    continue;
                }
                const int one = 1;
                (void)setsockopt(fd, IPPROTO_TCP, TCP_NODELAY, &one, sizeof(one));
                (void)fcntl(fd, F_SETFL, fcntl(fd, F_GETFL) | O_NONBLOCK);
                c->fd = fd;
                c->state = SCAND_HELLO;
                c->hold = false;
                c->in_len = 0u;
                c->out_len = 0u;
                c->out_head = 0u;
                c->frames_in = c->frames_out = c->dropped = c->garbage = 0u;
                if (s->verbose) {
                    fprintf(stderr, "hil_sim serve: client %d connected\n", (int)(c - s->clients));
                }
                reply(s, c, "< hi >");
            }
            continue;
        }
        for (unsigned i = 0; i < SCAND_MAX_CLIENTS; i++) {
            scand_client_t *c = &s->clients[i];
            if (c->fd != fds[k].fd) {
                continue;
            }
            if ((fds[k].revents & (POLLERR | POLLNVAL)) != 0) {
                drop_client(s, c);
                break;
            }
            if ((fds[k].revents & (POLLIN | POLLHUP)) != 0) {
                read_client(s, c, now_ms);
            }
            if (c->fd >= 0 && (fds[k].revents & POLLOUT) != 0) {
                write_client(s, c);
            }
            break;
        }
    }
}

void scand_broadcast(scand_t *s, int skip_client, const can_frame_t *f, bool extended,
                     uint64_t t_ns)
{
    if (!can_frame_len_ok(f) || (f->flags & CAN_FRAME_FD) != 0u) {
        return; /* socketcand's "frame" carries classic frames only */
    }
    char msg[64];
    int n = 0;
    const unsigned long long us = (unsigned long long)(t_ns / 1000u);
    if (extended) {
        n = snprintf(msg, sizeof(msg), "< frame %08X %llu.%06llu ", (unsigned)(f->id & 0x1FFFFFFFu),
                     us / 1000000ull, us % 1000000ull);
    } else {
        n = snprintf(msg, sizeof(msg), "< frame %03X %llu.%06llu ", (unsigned)(f->id & 0x7FFu),
                     us / 1000000ull, us % 1000000ull);
    }
    static const char hex[] = "0123456789ABCDEF";
    for (uint8_t i = 0; i < f->len; i++) {
        msg[n++] = hex[f->data[i] >> 4];
        msg[n++] = hex[f->data[i] & 0xFu];
    }
    msg[n++] = ' ';
    msg[n++] = '>';
    for (unsigned i = 0; i < SCAND_MAX_CLIENTS; i++) {
        scand_client_t *c = &s->clients[i];
        if (c->fd < 0 || c->state != SCAND_RAW || (int)i == skip_client) {
            continue;
        }
        if (c->out_len + (uint32_t)n > SCAND_OUT_BUF) {
            c->dropped++;
            continue;
        }
        for (int k = 0; k < n; k++) {
            c->out[(c->out_head + c->out_len + (uint32_t)k) % SCAND_OUT_BUF] = msg[k];
        }
        c->out_len += (uint32_t)n;
        c->frames_out++;
    }
}

void scand_flush(scand_t *s, uint64_t now_ms)
{
    for (unsigned i = 0; i < SCAND_MAX_CLIENTS; i++) {
        scand_client_t *c = &s->clients[i];
        if (c->hold && now_ms >= c->frames_from_ms) {
            c->hold = false;
        }
        if (s->clients[i].fd >= 0 && s->clients[i].out_len > 0u) {
            write_client(s, &s->clients[i]);
        }
    }
}

unsigned scand_clients(const scand_t *s)
{
    unsigned n = 0u;
    for (unsigned i = 0; i < SCAND_MAX_CLIENTS; i++) {
        n += s->clients[i].fd >= 0 ? 1u : 0u;
    }
    return n;
}

void scand_close(scand_t *s)
{
    for (unsigned i = 0; i < SCAND_MAX_CLIENTS; i++) {
        if (s->clients[i].fd >= 0) {
            close(s->clients[i].fd);
            s->clients[i].fd = -1;
        }
    }
    if (s->listen_fd >= 0) {
        close(s->listen_fd);
        s->listen_fd = -1;
    }
}
