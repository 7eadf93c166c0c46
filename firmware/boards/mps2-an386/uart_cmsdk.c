/*
 * ARM CMSDK APB UARTs (UART0 at 0x40004000: the link; UART1 at 0x40005000:
 * the profile log). Receive is interrupt driven into a ring buffer, so the
 * main loop can sleep (wfi) between frames; transmit is polled.
 */
#include "board.h"

#define UART0_BASE 0x40004000u
#define UART1_BASE 0x40005000u
#define REG(base, off) (*(volatile uint32_t *)((base) + (off)))
#define UART_DATA 0x00u
#define UART_STATE 0x04u
#define UART_CTRL 0x08u
#define UART_INT 0x0Cu /* status on read, clear on write */
#define UART_BAUDDIV 0x10u
#define STATE_TX_FULL 0x1u
#define STATE_RX_FULL 0x2u
#define CTRL_TX_EN 0x1u
#define CTRL_RX_EN 0x2u
#define CTRL_RX_IRQ 0x8u
#define INT_RX 0x2u
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define UART0_RX_IRQ 0u /* QEMU mps2-an385/6: UART n receive is IRQ 2n */

#define RING 1024u /* power of two */

/* filled by the interrupt, emptied by the main loop: single producer, single consumer */
static volatile uint8_t g_ring[RING];
static volatile uint32_t g_head, g_tail;

static void drain(void)
{
    while (REG(UART0_BASE, UART_STATE) & STATE_RX_FULL) {
        uint8_t c = (uint8_t)(REG(UART0_BASE, UART_DATA) & 0xFFu);
        if (g_head - g_tail < RING) {
            g_ring[g_head & (RING - 1u)] = c;
            g_head++;
        }
    }
}

void uart0_rx_handler(void)
{
    REG(UART0_BASE, UART_INT) = INT_RX;
    drain();
}

void uart_init(void)
{
    REG(UART0_BASE, UART_BAUDDIV) = BOARD_CPU_HZ / 115200u;
    REG(UART0_BASE, UART_CTRL) = CTRL_TX_EN | CTRL_RX_EN | CTRL_RX_IRQ;
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
    int c;
    if (g_tail == g_head) {
        drain(); /* also works with the interrupt masked */
    }
    if (g_tail == g_head) {
        return -1;
    }
    c = g_ring[g_tail & (RING - 1u)];
    g_tail++;
    return c;
}

int uart_rx_empty(void) { return g_tail == g_head; }
