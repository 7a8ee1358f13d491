/* ISO-TP (ISO 15765-2:2016) on classic CAN or CAN FD, normal addressing, one rx/tx id pair:
 * single frame (SF), first frame (FF), consecutive frames (CF, sequence number 1..15, 0, ...),
 * flow control (FC: continue/wait/overflow, block size, STmin), timeouts N_Bs (sender waits for
 * FC) and N_Cr (receiver waits for CF). Classic (tx_dl 8, the default): every transmitted frame
 * padded to 8 bytes with ISOTP_PADDING (0xCC). CAN FD (tx_dl 64): FD frames (BRS if asked),
 * single frames of 8..62 bytes with the escape length byte (0x00, SF_DL), first frames and
 * consecutive frames of 64 bytes, the last CF and short frames padded to the next valid FD
 * length. Reception takes either: RX_DL is the length of the first frame. Messages up to ISOTP_MAX_PAYLOAD bytes (12-bit FF length; the 32-bit
 * escape is refused with FC overflow). Buffers live in the struct: no heap.
 * Time is passed in (microseconds, monotonic); frames leave through a callback, so the module
 * is pure and testable. Received frames are fed with isotp_on_frame, time with isotp_poll. */
#ifndef ISOTP_H
#define ISOTP_H

#include <stdbool.h>
#include <stdint.h>
#include "can_frame.h"
#include "proto_ids.h"

#ifndef ISOTP_MAX_PAYLOAD
#define ISOTP_MAX_PAYLOAD 4095u
#endif
#define ISOTP_PADDING 0xCCu
#define ISOTP_DEFAULT_N_BS_US 1000000u /* ISO 15765-2 default N_Bs / N_Cr: 1000 ms */
#define ISOTP_DEFAULT_N_CR_US 1000000u
#define ISOTP_DEFAULT_WFT_MAX 10u

/** Send one frame; returns false if the driver cannot take it now (retried on the next poll). */
typedef bool (*isotp_send_fn)(void *ctx, const can_frame_t *frame);

/** Link configuration. block_size/st_min are what this node asks of a sender in its FC. */
typedef struct {
    uint32_t tx_id;
    uint32_t rx_id;
    uint8_t block_size; /* 0: no further FC */
    uint8_t st_min;     /* raw STmin byte: 0x00-0x7F ms, 0xF1-0xF9 100-900 us */
    uint32_t n_bs_us;
    uint32_t n_cr_us;
    uint8_t wft_max; /* FC WAIT frames accepted in a row before aborting */
    uint8_t tx_dl;   /* 8: classic CAN; 64: CAN FD (needs CAN_FRAME_MAX_LEN 64) */
    bool brs;        /* CAN FD: bit-rate switch in the data phase */
} isotp_config_t;

typedef enum {
    ISOTP_RX_IDLE = 0,
    ISOTP_RX_RECEIVING = 1,
    ISOTP_RX_DONE = 2
} isotp_rx_state_t;
typedef enum {
    ISOTP_TX_IDLE = 0,
    ISOTP_TX_SEND_FIRST = 1,
    ISOTP_TX_WAIT_FC = 2,
    ISOTP_TX_SENDING = 3
} isotp_tx_state_t;

/** One ISO-TP link (both directions). */
typedef struct {
    isotp_config_t cfg;
    isotp_send_fn send;
    void *send_ctx;
    /* reception */
    isotp_rx_state_t rx_state;
    uint8_t rx_buf[ISOTP_MAX_PAYLOAD];
    uint16_t rx_len;         /* announced length */
    uint16_t rx_pos;         /* bytes received so far */
    uint8_t rx_sn;           /* expected sequence number */
    uint8_t rx_dl;           /* length of the first frame: every CF but the last has it */
    uint8_t rx_bs_left;      /* CFs until we must send the next FC (0 with BS 0) */
    uint64_t rx_deadline_us; /* N_Cr */
    uint64_t rx_start_us;    /* when the message's SF or FF arrived (the frame's receive time) */
    bool rx_fc_pending;      /* FC to send (driver was busy) */
    uint8_t rx_fc_status;
    /* transmission */
    isotp_tx_state_t tx_state;
    uint8_t tx_buf[ISOTP_MAX_PAYLOAD];
    uint16_t tx_len;
    uint16_t tx_pos;
    uint8_t tx_sn;
    uint8_t tx_bs; /* block size granted by the receiver */
    uint8_t tx_bs_left;
    uint32_t tx_stmin_us;
    uint64_t tx_next_us;     /* earliest time of the next CF */
    uint64_t tx_deadline_us; /* N_Bs */
    uint8_t tx_wft;
    /* diagnostics */
    proto_status_t last_error;
    uint32_t error_count;
} isotp_link_t;

/** Defaults: BS 0, STmin 0, N_Bs = N_Cr = 1000 ms, WFTmax 10, classic CAN (tx_dl 8). */
void isotp_config_default(isotp_config_t *cfg, uint32_t tx_id, uint32_t rx_id);

/** Initialise a link (idle in both directions); a tx_dl other than 8 or 64, or 64 where frames
 *  hold 8 bytes, is taken as 8. */
void isotp_init(isotp_link_t *link, const isotp_config_t *cfg, isotp_send_fn send, void *send_ctx);

/** Feed a received CAN frame; frames with another id are ignored. May send an FC. */
void isotp_on_frame(isotp_link_t *link, const can_frame_t *frame, uint64_t now_us);

/** Advance timers and transmit what is due (CFs after STmin, pending FC). Call every tick. */
void isotp_poll(isotp_link_t *link, uint64_t now_us);

/** Start sending len (1..ISOTP_MAX_PAYLOAD) bytes (copied, unless data is isotp_tx_buffer's);
 *  PROTO_ERR_ISOTP_BUSY while one is in flight. */
proto_status_t isotp_send(isotp_link_t *link, const uint8_t *data, uint16_t len, uint64_t now_us);

/** As isotp_send, but nothing leaves now: the first frame goes at the next isotp_poll (a caller
 *  whose frame share of this moment is used up, so no frame is built to be refused). */
proto_status_t isotp_queue(isotp_link_t *link, const uint8_t *data, uint16_t len);

/** The link's transmit buffer (ISOTP_MAX_PAYLOAD bytes): a message may be built in it while no
 *  transmission is in progress, and isotp_send of it then copies nothing. */
static inline uint8_t *isotp_tx_buffer(isotp_link_t *link)
{
    return link->tx_buf;
}

/** True while a transmission is in progress. */
bool isotp_tx_busy(const isotp_link_t *link);

/** If a complete message was received, return its length and its bytes (valid until the next
 *  isotp_rx_release); 0 otherwise. */
uint16_t isotp_rx_peek(const isotp_link_t *link, const uint8_t **data);

/** True if a complete message waits (isotp_rx_peek would return it). Inline: asked every tick. */
static inline bool isotp_rx_ready(const isotp_link_t *link)
{
    return link->rx_state == ISOTP_RX_DONE;
}

/** True if nothing is in flight or waiting in either direction (isotp_poll has nothing to do).
 *  Inline: asked every tick. */
static inline bool isotp_idle(const isotp_link_t *link)
{
    return ((uint32_t)link->rx_state | (uint32_t)link->tx_state) == 0u;
}

/** Release the received message so the next one can be received. */
void isotp_rx_release(isotp_link_t *link);

/** STmin byte -> microseconds (reserved values -> 127 ms, as ISO 15765-2 requires). */
uint32_t isotp_stmin_to_us(uint8_t st_min);

#endif /* ISOTP_H */
