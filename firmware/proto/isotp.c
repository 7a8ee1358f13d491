/* ISO-TP (ISO 15765-2:2016), classic CAN or CAN FD, normal addressing (see isotp.h). */
#include "isotp.h"

#include <string.h>

#define PCI_SF 0x0u
#define PCI_FF 0x1u
#define PCI_CF 0x2u
#define PCI_FC 0x3u
#define FC_CTS 0x0u
#define FC_WAIT 0x1u
#define FC_OVFLW 0x2u
#define SF_MAX 7u                       /* single frame with the 4-bit length */
#define FD_SF_MAX (CAN_FD_MAX_LEN - 2u) /* single frame with the escape length byte */

void isotp_config_default(isotp_config_t *cfg, uint32_t tx_id, uint32_t rx_id)
{
    cfg->tx_id = tx_id;
    cfg->rx_id = rx_id;
    cfg->block_size = 0u;
    cfg->st_min = 0u;
    cfg->n_bs_us = ISOTP_DEFAULT_N_BS_US;
    cfg->n_cr_us = ISOTP_DEFAULT_N_CR_US;
    cfg->wft_max = ISOTP_DEFAULT_WFT_MAX;
    cfg->tx_dl = CAN_CLASSIC_MAX_LEN;
    cfg->brs = false;
}

void isotp_init(isotp_link_t *link, const isotp_config_t *cfg, isotp_send_fn send, void *send_ctx)
{
    memset(link, 0, sizeof(*link));
    link->cfg = *cfg;
    if (cfg->tx_dl != CAN_FD_MAX_LEN || CAN_FRAME_MAX_LEN < CAN_FD_MAX_LEN) {
        link->cfg.tx_dl = CAN_CLASSIC_MAX_LEN;
        link->cfg.brs = false;
    }
    link->send = send;
    link->send_ctx = send_ctx;
}

uint32_t isotp_stmin_to_us(uint8_t st_min)
{
    if (st_min <= 0x7Fu) {
        return (uint32_t)st_min * 1000u;
    }
    if (st_min >= 0xF1u && st_min <= 0xF9u) {
        return (uint32_t)(st_min - 0xF0u) * 100u;
    }
    return 127000u;
}

static void fail(isotp_link_t *link, proto_status_t err)
{
    link->last_error = err;
    link->error_count++;
}

static bool fd(const isotp_link_t *link)
{
    return link->cfg.tx_dl > CAN_CLASSIC_MAX_LEN;
}

/* A frame of n bytes' id, length and flags: classic padded to 8; FD padded to 8 or the next FD
 * length. */
static void frame_head(const isotp_link_t *link, can_frame_t *f, uint8_t n)
{
    f->id = link->cfg.tx_id;
    f->len = n <= CAN_CLASSIC_MAX_LEN ? CAN_CLASSIC_MAX_LEN : can_fd_round_len(n);
    f->flags = 0u;
    if (fd(link)) {
        f->flags = (uint8_t)(CAN_FRAME_FD | (link->cfg.brs ? CAN_FRAME_BRS : 0u));
    }
}

/* One frame of n PCI + data bytes (frame_head's length, the rest padding). */
static bool emit(isotp_link_t *link, const uint8_t *payload, uint8_t n)
{
    can_frame_t f;
    frame_head(link, &f, n);
    memset(f.data, ISOTP_PADDING, sizeof(f.data));
    memcpy(f.data, payload, n);
    return link->send(link->send_ctx, &f);
}

/* A consecutive frame of n data bytes from tx_buf at tx_pos, built in place: a classic frame's
 * seven bytes by one fixed-size copy (a few loads and stores; the frame of a long response's
 * bulk, ~100 instructions less than a staging buffer, a fill and two copies). */
static bool emit_cf(isotp_link_t *link, uint8_t n)
{
    can_frame_t f;
    frame_head(link, &f, (uint8_t)(n + 1u));
    f.data[0] = (uint8_t)((PCI_CF << 4) | link->tx_sn);
    const uint8_t *src = &link->tx_buf[link->tx_pos];
    if (n == CAN_CLASSIC_MAX_LEN - 1u) {
        memcpy(&f.data[1], src, CAN_CLASSIC_MAX_LEN - 1u);
    } else {
        memset(&f.data[1], ISOTP_PADDING, (uint32_t)f.len - 1u);
        memcpy(&f.data[1], src, n);
    }
    return link->send(link->send_ctx, &f);
}

static bool send_fc(isotp_link_t *link, uint8_t status)
{
    const uint8_t fc[3] = {(uint8_t)((PCI_FC << 4) | status), link->cfg.block_size,
                           link->cfg.st_min};
    return emit(link, fc, 3u);
}

/* ---- reception ---- */

static void rx_single(isotp_link_t *link, const can_frame_t *f, uint64_t now_us)
{
    uint8_t len = (uint8_t)(f->data[0] & 0x0Fu);
    uint8_t off = 1u;
    if (len == 0u && f->len > CAN_CLASSIC_MAX_LEN) {
        len = f->len >= 2u ? f->data[1] : 0u; /* escape: SF_DL in the second byte */
        off = 2u;
        if (len <= SF_MAX) {
            len = 0u; /* would have fitted the 4-bit length */
        }
    }
    if (len == 0u || (off == 1u && len > SF_MAX) || (uint16_t)(len + off) > f->len) {
        fail(link, PROTO_ERR_ISOTP_FORMAT);
        return;
    }
    if (link->rx_state == ISOTP_RX_RECEIVING) {
        fail(link, PROTO_ERR_ISOTP_UNEXPECTED); /* ISO 15765-2: a new SF aborts a reception */
    }
    memcpy(link->rx_buf, &f->data[off], len);
    link->rx_len = len;
    link->rx_pos = len;
    link->rx_start_us = now_us;
    link->rx_state = ISOTP_RX_DONE;
}

static void rx_first(isotp_link_t *link, const can_frame_t *f, uint64_t now_us)
{
    if (f->len < CAN_CLASSIC_MAX_LEN) {
        fail(link, PROTO_ERR_ISOTP_FORMAT);
        return;
    }
    const uint8_t ff_data = (uint8_t)(f->len - 2u); /* RX_DL - 2 */
    const uint16_t len = (uint16_t)(((uint16_t)(f->data[0] & 0x0Fu) << 8) | f->data[1]);
    if (len == 0u) {
        /* 32-bit escape length: longer than any buffer here */
        fail(link, PROTO_ERR_ISOTP_OVERFLOW);
        link->rx_state = ISOTP_RX_IDLE;
        (void)send_fc(link, FC_OVFLW);
        return;
    }
    if (len <= (f->len > CAN_CLASSIC_MAX_LEN ? (uint16_t)(f->len - 2u) : SF_MAX)) {
        fail(link, PROTO_ERR_ISOTP_FORMAT); /* would have fitted a single frame */
        return;
    }
    if (len > ISOTP_MAX_PAYLOAD) {
        fail(link, PROTO_ERR_ISOTP_OVERFLOW);
        link->rx_state = ISOTP_RX_IDLE;
        (void)send_fc(link, FC_OVFLW);
        return;
    }
    if (link->rx_state == ISOTP_RX_RECEIVING) {
        fail(link, PROTO_ERR_ISOTP_UNEXPECTED); /* a new FF aborts a reception */
    }
    memcpy(link->rx_buf, &f->data[2], ff_data);
    link->rx_len = len;
    link->rx_pos = ff_data;
    link->rx_dl = f->len;
    link->rx_sn = 1u;
    link->rx_bs_left = link->cfg.block_size;
    link->rx_state = ISOTP_RX_RECEIVING;
    link->rx_start_us = now_us;
    link->rx_deadline_us = now_us + link->cfg.n_cr_us;
    link->rx_fc_status = FC_CTS;
    link->rx_fc_pending = !send_fc(link, FC_CTS);
}

static void rx_consecutive(isotp_link_t *link, const can_frame_t *f, uint64_t now_us)
{
    if (link->rx_state != ISOTP_RX_RECEIVING) {
        return; /* not for a reception in progress: ignore */
    }
    const uint8_t sn = (uint8_t)(f->data[0] & 0x0Fu);
    if (sn != link->rx_sn) {
        fail(link, PROTO_ERR_ISOTP_WRONG_SN);
        link->rx_state = ISOTP_RX_IDLE;
        return;
    }
    const uint16_t remaining = (uint16_t)(link->rx_len - link->rx_pos);
    const uint8_t cf_data = (uint8_t)(link->rx_dl - 1u);
    const uint8_t n = (uint8_t)(remaining < cf_data ? remaining : cf_data);
    if ((uint8_t)(n + 1u) > f->len || (n == cf_data && f->len != link->rx_dl)) {
        fail(link, PROTO_ERR_ISOTP_FORMAT);
        link->rx_state = ISOTP_RX_IDLE;
        return;
    }
    memcpy(&link->rx_buf[link->rx_pos], &f->data[1], n);
    link->rx_pos = (uint16_t)(link->rx_pos + n);
    link->rx_sn = (uint8_t)((link->rx_sn + 1u) & 0x0Fu);
    link->rx_deadline_us = now_us + link->cfg.n_cr_us;
    if (link->rx_pos >= link->rx_len) {
        link->rx_state = ISOTP_RX_DONE;
        return;
    }
    if (link->cfg.block_size != 0u) {
        link->rx_bs_left--;
        if (link->rx_bs_left == 0u) {
            link->rx_bs_left = link->cfg.block_size;
            link->rx_fc_status = FC_CTS;
            link->rx_fc_pending = !send_fc(link, FC_CTS);
        }
    }
}

/* ---- transmission ---- */

static void tx_flow_control(isotp_link_t *link, const can_frame_t *f, uint64_t now_us)
{
    if (link->tx_state != ISOTP_TX_WAIT_FC) {
        fail(link, PROTO_ERR_ISOTP_UNEXPECTED); /* unexpected FC: ignored */
        return;
    }
    if (f->len < 3u) {
        fail(link, PROTO_ERR_ISOTP_FORMAT);
        link->tx_state = ISOTP_TX_IDLE;
        return;
    }
    const uint8_t status = (uint8_t)(f->data[0] & 0x0Fu);
    if (status == FC_CTS) {
        link->tx_bs = f->data[1];
        link->tx_bs_left = f->data[1];
        link->tx_stmin_us = isotp_stmin_to_us(f->data[2]);
        link->tx_wft = 0u;
        link->tx_state = ISOTP_TX_SENDING;
        link->tx_next_us = now_us; /* the first CF may follow the FC at once */
    } else if (status == FC_WAIT) {
        link->tx_wft++;
        if (link->tx_wft > link->cfg.wft_max) {
            fail(link, PROTO_ERR_ISOTP_WFT);
            link->tx_state = ISOTP_TX_IDLE;
        } else {
            link->tx_deadline_us = now_us + link->cfg.n_bs_us;
        }
    } else if (status == FC_OVFLW) {
        fail(link, PROTO_ERR_ISOTP_OVERFLOW);
        link->tx_state = ISOTP_TX_IDLE;
    } else {
        fail(link, PROTO_ERR_ISOTP_FORMAT); /* reserved flow status: abort */
        link->tx_state = ISOTP_TX_IDLE;
    }
}

void isotp_on_frame(isotp_link_t *link, const can_frame_t *frame, uint64_t now_us)
{
    if (frame->id != link->cfg.rx_id || frame->len == 0u || !can_frame_len_ok(frame)) {
        return;
    }
    switch ((uint8_t)(frame->data[0] >> 4)) {
    case PCI_SF:
        if (link->rx_state == ISOTP_RX_DONE) {
            fail(link, PROTO_ERR_ISOTP_UNEXPECTED); /* previous message not consumed yet */
        } else {
            rx_single(link, frame, now_us);
        }
        break;
    case PCI_FF:
        if (link->rx_state == ISOTP_RX_DONE) {
            fail(link, PROTO_ERR_ISOTP_UNEXPECTED);
        } else {
            rx_first(link, frame, now_us);
        }
        break;
    case PCI_CF: rx_consecutive(link, frame, now_us); break;
    case PCI_FC: tx_flow_control(link, frame, now_us); break;
    default:
        fail(link, PROTO_ERR_ISOTP_FORMAT); /* reserved PCI type: ignored */
        break;
    }
}

static void tx_run(isotp_link_t *link, uint64_t now_us)
{
    const uint16_t sf_max = fd(link) ? FD_SF_MAX : SF_MAX;
    if (link->tx_state == ISOTP_TX_SEND_FIRST && link->tx_len <= sf_max) {
        uint8_t sf[CAN_FRAME_MAX_LEN];
        const uint8_t off = link->tx_len <= SF_MAX ? 1u : 2u; /* 2: the escape length byte */
        sf[0] = (uint8_t)((PCI_SF << 4) | (off == 1u ? link->tx_len : 0u));
        sf[1] = (uint8_t)link->tx_len;
        memcpy(&sf[off], link->tx_buf, link->tx_len);
        if (emit(link, sf, (uint8_t)(link->tx_len + off))) {
            link->tx_state = ISOTP_TX_IDLE; /* else: driver full, retried on the next poll */
        }
        return;
    }
    if (link->tx_state == ISOTP_TX_SEND_FIRST) {
        uint8_t ff[CAN_FRAME_MAX_LEN];
        const uint8_t ff_data = (uint8_t)(link->cfg.tx_dl - 2u);
        ff[0] = (uint8_t)((PCI_FF << 4) | ((link->tx_len >> 8) & 0x0Fu));
        ff[1] = (uint8_t)(link->tx_len & 0xFFu);
        memcpy(&ff[2], link->tx_buf, ff_data);
        if (emit(link, ff, link->cfg.tx_dl)) {
            link->tx_pos = ff_data;
            link->tx_sn = 1u;
            link->tx_wft = 0u;
            link->tx_state = ISOTP_TX_WAIT_FC;
            link->tx_deadline_us = now_us + link->cfg.n_bs_us;
        }
        return;
    }
    /* Consecutive frames: as many as STmin allows now, up to the block size, while the driver
     * accepts them. Bounded by the message length. */
    while (link->tx_state == ISOTP_TX_SENDING && now_us >= link->tx_next_us) {
        const uint16_t remaining = (uint16_t)(link->tx_len - link->tx_pos);
        const uint8_t cf_data = (uint8_t)(link->cfg.tx_dl - 1u);
        const uint8_t n = (uint8_t)(remaining < cf_data ? remaining : cf_data);
        if (!emit_cf(link, n)) {
            return; /* driver full: retry on the next poll */
        }
        link->tx_pos = (uint16_t)(link->tx_pos + n);
        link->tx_sn = (uint8_t)((link->tx_sn + 1u) & 0x0Fu);
        link->tx_next_us = now_us + link->tx_stmin_us;
        if (link->tx_pos >= link->tx_len) {
            link->tx_state = ISOTP_TX_IDLE;
            return;
        }
        if (link->tx_bs != 0u) {
            link->tx_bs_left--;
            if (link->tx_bs_left == 0u) {
                link->tx_state = ISOTP_TX_WAIT_FC;
                link->tx_deadline_us = now_us + link->cfg.n_bs_us;
                return;
            }
        }
        if (link->tx_stmin_us != 0u) {
            return; /* next CF after STmin: a later poll */
        }
    }
}

void isotp_poll(isotp_link_t *link, uint64_t now_us)
{
    if (link->rx_state == ISOTP_RX_RECEIVING) {
        if (link->rx_fc_pending) {
            link->rx_fc_pending = !send_fc(link, link->rx_fc_status);
        }
        if (now_us > link->rx_deadline_us) {
            fail(link, PROTO_ERR_ISOTP_TIMEOUT_CR);
            link->rx_state = ISOTP_RX_IDLE;
        }
    }
    if (link->tx_state == ISOTP_TX_WAIT_FC && now_us > link->tx_deadline_us) {
        fail(link, PROTO_ERR_ISOTP_TIMEOUT_BS);
        link->tx_state = ISOTP_TX_IDLE;
    }
    if (link->tx_state == ISOTP_TX_SEND_FIRST || link->tx_state == ISOTP_TX_SENDING) {
        tx_run(link, now_us);
    }
}

proto_status_t isotp_send(isotp_link_t *link, const uint8_t *data, uint16_t len, uint64_t now_us)
{
    const proto_status_t st = isotp_queue(link, data, len);
    if (st == PROTO_OK) {
        tx_run(link, now_us);
    }
    return st;
}

proto_status_t isotp_queue(isotp_link_t *link, const uint8_t *data, uint16_t len)
{
    if (link->tx_state != ISOTP_TX_IDLE) {
        return PROTO_ERR_ISOTP_BUSY;
    }
    if (len == 0u || len > ISOTP_MAX_PAYLOAD) {
        return PROTO_ERR_ISOTP_OVERFLOW;
    }
    if (data != link->tx_buf) {
        memcpy(link->tx_buf, data, len);
    }
    link->tx_len = len;
    link->tx_state = ISOTP_TX_SEND_FIRST;
    return PROTO_OK;
}

bool isotp_tx_busy(const isotp_link_t *link)
{
    return link->tx_state != ISOTP_TX_IDLE;
}

uint16_t isotp_rx_peek(const isotp_link_t *link, const uint8_t **data)
{
    if (link->rx_state != ISOTP_RX_DONE) {
        return 0u;
    }
    *data = link->rx_buf;
    return link->rx_len;
}

void isotp_rx_release(isotp_link_t *link)
{
    if (link->rx_state == ISOTP_RX_DONE) {
        link->rx_state = ISOTP_RX_IDLE;
    }
}
