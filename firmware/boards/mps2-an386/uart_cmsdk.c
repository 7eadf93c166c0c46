/*
 * ARM CMSDK APB UARTs (UART0 at 0x40004000: the link; UART1 at 0x40005000:
 * the profile log). Transmit is polled. Receive is interrupt driven into a
 * ring buffer so the main loop can sleep (wfi) between frames.
 *
 * The ring has exactly one producer and one consumer, by construction:
 *   - only the receive interrupt reads the data register and advances g_head;
 *   - only the main loop (uart_getc) advances g_tail.
 * The main loop never touches the receive registers. When the ring is full
 * the interrupt switches itself off and leaves the byte in the UART's
 * holding register: the UART stops accepting (QEMU holds the rest in its
 * chardev; a real line would overrun, which is counted, never hidden). The
 * main loop switches it back on, with interrupts masked, once it has made
 * room. CTRL is written by both, but never at the same time: the interrupt
 * writes it only while it is enabled, the main loop only while it is masked.
 */
#include "board.h"

#define UART0_BASE 0x40004000u
#define UART1_BASE 0x40005000u
#define REG(base, off) (*(volatile uint32_t *)((base) + (off)))
#define UART_DATA 0x00u
#define UART_STATE 0x04u /* status on read; write 1 to clear the overrun bits */
#define UART_CTRL 0x08u
#define UART_INT 0x0Cu /* status on read, clear on write */
#define UART_BAUDDIV 0x10u
#define STATE_TX_FULL 0x1u
#define STATE_RX_OVERRUN 0x8u
#define CTRL_TX_EN 0x1u
#define CTRL_RX_EN 0x2u
#define CTRL_RX_IRQ 0x8u
#define CTRL_RUN (CTRL_TX_EN | CTRL_RX_EN | CTRL_RX_IRQ)
#define CTRL_PAUSED (CTRL_TX_EN | CTRL_RX_EN)
#define INT_RX 0x2u
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define UART0_RX_IRQ 0u /* QEMU mps2-an385/6: UART n receive is IRQ 2n */

#define RING 1024u /* power of two; a longer frame (up to FFR_FRAME_MAX) pauses the interrupt until the loop drains it */

static volatile uint8_t g_ring[RING];
static volatile uint32_t g_head;    /* written by the interrupt only */
static volatile uint32_t g_tail;    /* written by the main loop only */
static volatile uint32_t g_paused; /* 1: the interrupt found the ring full and switched itself off */

#define barrier() __asm__ volatile("" ::: "memory")

/* One interrupt, one byte: the UART holds one received byte and raises RX for
 * it; clearing RX before reading the byte is safe because no new byte can
 * land until the data register has been read. Two register accesses a byte:
 * under an emulator every access is a costly exit, so the status register is
 * not polled here (the overrun flag is sticky: uart_rx_overruns reads it). */
void uart0_rx_handler(void)
{
    uint32_t head = g_head;
    if (head - g_tail >= RING) {
        /* no room: leave the byte where it is, stop being called for it */
        g_paused = 1u;
        REG(UART0_BASE, UART_CTRL) = CTRL_PAUSED;
        return;
    }
    REG(UART0_BASE, UART_INT) = INT_RX;
    g_ring[head & (RING - 1u)] = (uint8_t)(REG(UART0_BASE, UART_DATA) & 0xFFu);
    barrier(); /* the byte is in the ring before the consumer can see it */
    g_head = head + 1u;
}

void uart_init(void)
{
    g_head = g_tail = g_paused = 0u;
    REG(UART0_BASE, UART_BAUDDIV) = BOARD_CPU_HZ / 115200u;
    REG(UART0_BASE, UART_CTRL) = CTRL_RUN;
    REG(UART1_BASE, UART_BAUDDIV) = BOARD_CPU_HZ / 115200u;
    REG(UART1_BASE, UART_CTRL) = CTRL_TX_EN;
    NVIC_ISER0 = 1u << UART0_RX_IRQ;
}

static void putc_at(uint32_t base, uint8_t c)
{
    while (REG(base, UART_STATE) & STATE_TX_FULL) {
    }
    REG(base, UART_DATA) = c;
}

void uart_putc(uint8_t c) { putc_at(UART0_BASE, c); }

void uart_write(const uint8_t *p, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; ++i) {
        putc_at(UART0_BASE, p[i]);
    }
}

void uart_puts(const char *s)
{
    while (*s != '\0') {
        putc_at(UART0_BASE, (uint8_t)*s++);
    }
}

void uart1_puts(const char *s)
{
    while (*s != '\0') {
        putc_at(UART1_BASE, (uint8_t)*s++);
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
        REG(UART0_BASE, UART_CTRL) = CTRL_RUN;
        __asm__ volatile("cpsie i" ::: "memory");
    }
    return c;
}

int uart_rx_empty(void) { return g_tail == g_head; }

/* 1 once the UART has lost a received byte (its sticky overrun flag; never under
 * QEMU's flow control, where a byte waits until the last one was read) */
uint32_t uart_rx_overruns(void) { return (REG(UART0_BASE, UART_STATE) & STATE_RX_OVERRUN) != 0u ? 1u : 0u; }
