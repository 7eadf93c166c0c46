/*
 * nRF51 UART0 (0x40002000; on the micro:bit P0.24 TX, P0.25 RX: the
 * interface chip's USB virtual COM port). QEMU's microbit connects -serial 0
 * to it. Transmit is polled. Receive is interrupt driven into a ring buffer
 * so the main loop can sleep (wfi) between frames.
 *
 * The ring has exactly one producer and one consumer, by construction:
 *   - only the receive interrupt reads RXD and advances g_head;
 *   - only the main loop (uart_getc) advances g_tail.
 * The main loop never touches the receive registers. When the ring is full
 * the interrupt switches itself off (INTENCLR) and leaves the byte in the
 * UART's receive FIFO (6 bytes): the UART stops accepting (QEMU holds the
 * rest in its chardev; a real line would overrun, which is flagged, never
 * hidden). The main loop switches it back on (INTENSET), with interrupts
 * masked, once it has made room. INTENSET/INTENCLR are written by both, but
 * never at the same time: the interrupt writes only while it is enabled,
 * the main loop only while it is masked.
 */
#include "board.h"

#define UART0_BASE 0x40002000u
#define REG(off) (*(volatile uint32_t *)(UART0_BASE + (off)))
#define UART_STARTRX 0x000u
#define UART_STARTTX 0x008u
#define UART_RXDRDY 0x108u /* event: a byte waits in RXD */
#define UART_TXDRDY 0x11Cu /* event: the byte written to TXD has gone */
#define UART_INTENSET 0x304u
#define UART_INTENCLR 0x308u
#define UART_ERRORSRC 0x480u
#define UART_ENABLE 0x500u
#define UART_PSELTXD 0x50Cu
#define UART_PSELRXD 0x514u
#define UART_RXD 0x518u
#define UART_TXD 0x51Cu
#define UART_BAUDRATE 0x524u
#define BAUD_115200 0x01D7E000u
#define INT_RXDRDY (1u << 2)
#define ERRORSRC_OVERRUN 1u
#define PIN_TX 24u
#define PIN_RX 25u
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define UART0_IRQ 2u

#define RING 1024u /* power of two; a longer frame (up to FFR_FRAME_MAX) pauses the interrupt until the loop drains it */

static volatile uint8_t g_ring[RING];
static volatile uint32_t g_head;   /* written by the interrupt only */
static volatile uint32_t g_tail;   /* written by the main loop only */
static volatile uint32_t g_paused; /* 1: the interrupt found the ring full and switched itself off */

#define barrier() __asm__ volatile("" ::: "memory")

/* One interrupt, one byte: clear the event, then read RXD; if the FIFO holds
 * more, the UART raises the event again and the interrupt comes back. */
void uart0_irq_handler(void)
{
    uint32_t head = g_head;
    if (head - g_tail >= RING) {
        /* no room: leave the byte where it is, stop being called for it */
        g_paused = 1u;
        REG(UART_INTENCLR) = INT_RXDRDY;
        return;
    }
    REG(UART_RXDRDY) = 0u;
    g_ring[head & (RING - 1u)] = (uint8_t)(REG(UART_RXD) & 0xFFu);
    barrier(); /* the byte is in the ring before the consumer can see it */
    g_head = head + 1u;
}

void uart_init(void)
{
    g_head = g_tail = g_paused = 0u;
    REG(UART_PSELTXD) = PIN_TX;
    REG(UART_PSELRXD) = PIN_RX;
    REG(UART_BAUDRATE) = BAUD_115200;
    REG(UART_ENABLE) = 4u;
    REG(UART_STARTTX) = 1u;
    REG(UART_STARTRX) = 1u;
    REG(UART_INTENSET) = INT_RXDRDY;
    NVIC_ISER0 = 1u << UART0_IRQ;
}

void uart_write(const uint8_t *p, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; ++i) {
        REG(UART_TXD) = p[i];
        while (REG(UART_TXDRDY) == 0u) {
        }
        REG(UART_TXDRDY) = 0u;
    }
}

int uart_getc(void)
{
    uint32_t tail = g_tail;
    int c;
    if (tail == g_head) {
        return -1;
    }
    barrier(); /* read the byte only after seeing the head that covers it */
    c = g_ring[tail & (RING - 1u)];
    g_tail = tail + 1u;
    if (g_paused != 0u) {
        /* there is room again: let the interrupt take the waiting byte */
        __asm__ volatile("cpsid i" ::: "memory");
        g_paused = 0u;
        REG(UART_INTENSET) = INT_RXDRDY;
        __asm__ volatile("cpsie i" ::: "memory");
    }
    return c;
}

int uart_rx_empty(void) { return g_tail == g_head; }

/* 1 once the UART has lost a received byte (ERRORSRC.OVERRUN is sticky until
 * written back; never under QEMU, which holds bytes until the FIFO has room) */
uint32_t uart_rx_overruns(void) { return (REG(UART_ERRORSRC) & ERRORSRC_OVERRUN) != 0u ? 1u : 0u; }
