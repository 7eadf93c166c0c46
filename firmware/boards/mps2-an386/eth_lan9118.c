/*
 * The mps2-an386's Ethernet controller (an SMSC LAN9220, which QEMU models as
 * its software-compatible LAN9118; registers at 0x40200000, interrupt 13) as a
 * second, faster link transport for emulation: one Ethernet frame carries one
 * whole serial frame of the link protocol (COBS(message + CRC) + 0x00, exactly
 * the bytes the UART carries) after a 14-byte header with our own EtherType
 * (ETH_TYPE_FFR). Under QEMU a frame in costs one hand-over between its I/O
 * thread and the CPU thread, where the UART costs two per byte (docs/pil.md).
 *
 * The controller keeps received frames in its own FIFOs (data words and one
 * status word per frame). Who touches what, by construction:
 *   - only the main loop (eth_recv, eth_send, eth_idle_arm) reads and writes
 *     the FIFOs, the status registers and INT_STS;
 *   - the interrupt handler does one thing: it writes INT_EN = 0, which drops
 *     the interrupt line; it is a wake-up from wfi, nothing more;
 *   - the main loop writes INT_EN only with interrupts masked (board_idle:
 *     masked, arm, test, wfi), so the two writers never meet.
 * eth_idle_arm clears the "frame received" status bit, enables its interrupt,
 * then looks at the status FIFO's fill: a frame already there is seen by that
 * look (no sleep); a frame that lands after it raises the interrupt, which
 * wakes the wfi even while masked. No frame can be missed and none is read
 * twice: there is one consumer of the FIFOs.
 *
 * The host's address is the source of the last frame received; answers go
 * there. The controller is left promiscuous (its reset state): the only
 * station on this wire is the harness.
 */
#include "board.h"

#define ETH_BASE 0x40200000u
#define ETH(off) (*(volatile uint32_t *)(ETH_BASE + (off)))
#define RX_DATA_FIFO 0x00u
#define TX_DATA_FIFO 0x20u
#define RX_STATUS_FIFO 0x40u
#define IRQ_CFG 0x54u
#define INT_STS 0x58u
#define INT_EN 0x5Cu
#define BYTE_TEST 0x64u
#define TX_CFG 0x70u
#define RX_FIFO_INF 0x7Cu
#define TX_FIFO_INF 0x80u
#define MAC_CSR_CMD 0xA4u
#define MAC_CSR_DATA 0xA8u

#define BYTE_TEST_VALUE 0x87654321u
#define IRQ_CFG_ACTIVE_HIGH 0x111u /* IRQ_EN, IRQ_POL (high), IRQ_TYPE (push-pull) */
#define INT_RSFL 0x8u               /* the RX status FIFO holds more than its level (0): a frame */
#define TX_CFG_ON 0x6u              /* TX_ON, TXSAO: transmit, and let the TX status FIFO overrun */
#define CSR_BUSY 0x80000000u
#define CSR_READ 0x40000000u
#define MAC_CR 1u
#define MAC_CR_RXEN 0x4u
#define MAC_CR_TXEN 0x8u
#define MAC_CR_PRMS 0x40000u
#define RXS_LENGTH(s) (((s) >> 16) & 0x3FFFu) /* frame length with its 4-byte FCS */
#define RXS_ERROR 0x8000u                       /* error summary */
#define TXA_FIRST 0x2000u
#define TXA_LAST 0x1000u
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define ETH_IRQ 13u

#define HDR 14u
#define FCS 4u
#define ETH_TYPE_FFR 0x88B5u /* IEEE 802 "local experimental" EtherType 1 */

static uint32_t g_up;          /* 1: the controller answered and is set up (main loop only) */
static uint8_t g_peer[6];      /* the host's address: source of the last frame (main loop only) */
static const uint8_t g_self[6] = {0x02u, 0x00u, 0x00u, 0x00u, 0x0Fu, 0xF2u}; /* locally administered */

static void mac_write(uint32_t reg, uint32_t value)
{
    uint32_t spin;
    ETH(MAC_CSR_DATA) = value;
    ETH(MAC_CSR_CMD) = CSR_BUSY | reg;
    for (spin = 0u; spin < 1000u && (ETH(MAC_CSR_CMD) & CSR_BUSY) != 0u; ++spin) {
    }
}

uint32_t eth_init(void)
{
    uint32_t i;
    if (ETH(BYTE_TEST) != BYTE_TEST_VALUE) {
        return 0u; /* no controller: the UART is the only link */
    }
    for (i = 0u; i < 6u; ++i) {
        g_peer[i] = 0xFFu; /* broadcast until the host has spoken */
    }
    ETH(INT_EN) = 0u;
    ETH(INT_STS) = 0xFFFFFFFFu;
    ETH(IRQ_CFG) = IRQ_CFG_ACTIVE_HIGH;
    ETH(TX_CFG) = TX_CFG_ON;
    mac_write(MAC_CR, MAC_CR_RXEN | MAC_CR_TXEN | MAC_CR_PRMS);
    NVIC_ISER0 = 1u << ETH_IRQ;
    g_up = 1u;
    return 1u;
}

/* the wake-up: drop the line; the main loop does the rest */
void eth_irq_handler(void) { ETH(INT_EN) = 0u; }

uint32_t eth_idle_arm(void)
{
    if (g_up == 0u) {
        return 1u;
    }
    ETH(INT_STS) = INT_RSFL;
    ETH(INT_EN) = INT_RSFL;
    return (ETH(RX_FIFO_INF) >> 16 & 0xFFu) == 0u ? 1u : 0u;
}

/* One frame's words out of the data FIFO: the payload (after the header, before the FCS)
 * into buf, at most cap bytes of it; the header's source address and type into hdr. */
static uint32_t read_frame(uint32_t len, uint8_t *hdr, uint8_t *buf, uint32_t cap)
{
    uint32_t words = (len + 3u) / 4u;
    uint32_t payload = len > HDR + FCS ? len - HDR - FCS : 0u;
    uint32_t at = 0u, w, k;
    for (w = 0u; w < words; ++w) {
        uint32_t word = ETH(RX_DATA_FIFO);
        for (k = 0u; k < 4u; ++k, ++at) {
            uint8_t byte = (uint8_t)(word >> (8u * k));
            if (at < HDR) {
                hdr[at] = byte;
            } else if (at - HDR < payload && at - HDR < cap) {
                buf[at - HDR] = byte;
            }
        }
    }
    return payload;
}

uint32_t eth_recv(uint8_t *buf, uint32_t cap)
{
    while (g_up != 0u && (ETH(RX_FIFO_INF) >> 16 & 0xFFu) != 0u) {
        uint32_t status = ETH(RX_STATUS_FIFO);
        uint8_t hdr[HDR];
        uint32_t n = read_frame(RXS_LENGTH(status), hdr, buf, cap);
        uint32_t i;
        if ((status & RXS_ERROR) != 0u || n == 0u || n > cap ||
            ((uint32_t)hdr[12] << 8 | hdr[13]) != ETH_TYPE_FFR) {
            continue; /* not ours, or damaged: the host's retry covers it */
        }
        for (i = 0u; i < 6u; ++i) {
            g_peer[i] = hdr[6u + i];
        }
        return n;
    }
    return 0u;
}

void eth_send(const uint8_t *p, uint32_t n)
{
    uint32_t total = HDR + n, i, word = 0u, spin;
    if (g_up == 0u || total > 1514u) {
        return;
    }
    /* room for the two command words and the frame (the FIFO drains as fast as it is filled
     * under QEMU; a real controller sends at the line's pace) */
    for (spin = 0u; spin < 100000u && (ETH(TX_FIFO_INF) & 0xFFFFu) < total + 8u; ++spin) {
    }
    ETH(TX_DATA_FIFO) = TXA_FIRST | TXA_LAST | total;
    ETH(TX_DATA_FIFO) = total;
    for (i = 0u; i < total; ++i) {
        uint8_t byte;
        if (i < 6u) {
            byte = g_peer[i];
        } else if (i < 12u) {
            byte = g_self[i - 6u];
        } else if (i == 12u) {
            byte = (uint8_t)(ETH_TYPE_FFR >> 8);
        } else if (i == 13u) {
            byte = (uint8_t)(ETH_TYPE_FFR & 0xFFu);
        } else {
            byte = p[i - HDR];
        }
        word |= (uint32_t)byte << (8u * (i & 3u));
        if ((i & 3u) == 3u) {
            ETH(TX_DATA_FIFO) = word;
            word = 0u;
        }
    }
    if ((total & 3u) != 0u) {
        ETH(TX_DATA_FIFO) = word;
    }
}
