/*
 * STM32F4 USARTs: USART1 (0x40011000, PA9 TX / PA10 RX, AF7) is the link,
 * USART2 (0x40004400, PA2 TX / PA3 RX) the profile log. QEMU's netduinoplus2
 * connects -serial 0 to USART1 and -serial 1 to USART2. Transmit is polled.
 * Receive is interrupt driven into a ring buffer so the main loop can sleep
 * (wfi) between frames.
 *
 * The ring has exactly one producer and one consumer, by construction:
 *   - only the receive interrupt reads the data register and advances g_head;
 *   - only the main loop (uart_getc) advances g_tail.
 * The main loop never touches the receive registers. When the ring is full
 * the interrupt switches itself off (RXNEIE) and leaves the byte in the data
 * register: the USART stops accepting (QEMU holds the rest in its chardev; a
 * real line would overrun, which is counted, never hidden). The main loop
 * switches it back on, with interrupts masked, once it has made room. CR1 is
 * written by both, but never at the same time: the interrupt writes it only
 * while it is enabled, the main loop only while it is masked.
 */
#include "board.h"

#define USART1_BASE 0x40011000u
#define USART2_BASE 0x40004400u
#define GPIOA_BASE 0x40020000u
#define REG(base, off) (*(volatile uint32_t *)((base) + (off)))
#define USART_SR 0x00u
#define USART_DR 0x04u
#define USART_BRR 0x08u
#define USART_CR1 0x0Cu
#define SR_ORE 0x08u  /* overrun: a byte arrived while RXNE was still set */
#define SR_RXNE 0x20u /* a byte waits in DR */
#define SR_TXE 0x80u  /* DR can take the next byte */
#define CR1_UE 0x2000u
#define CR1_RXNEIE 0x20u
#define CR1_TE 0x08u
#define CR1_RE 0x04u
#define CR1_RUN (CR1_UE | CR1_TE | CR1_RE | CR1_RXNEIE)
#define CR1_PAUSED (CR1_UE | CR1_TE | CR1_RE)
#define GPIO_MODER 0x00u
#define GPIO_AFRL 0x20u
#define GPIO_AFRH 0x24u
#define NVIC_ISER1 (*(volatile uint32_t *)0xE000E104u)
#define USART1_IRQ 37u

#define RING 1024u /* power of two; a longer frame (up to FFR_FRAME_MAX) pauses the interrupt until the loop drains it */

static volatile uint8_t g_ring[RING];
static volatile uint32_t g_head;     /* written by the interrupt only */
static volatile uint32_t g_tail;     /* written by the main loop only */
static volatile uint32_t g_paused;   /* 1: the interrupt found the ring full and switched itself off */
static volatile uint32_t g_overruns; /* written by the interrupt only */

#define barrier() __asm__ volatile("" ::: "memory")

/* One interrupt, one byte. Reading SR then DR clears RXNE and ORE. */
void usart1_irq_handler(void)
{
    uint32_t head = g_head;
    uint32_t sr = REG(USART1_BASE, USART_SR);
    if ((sr & SR_ORE) != 0u) {
        g_overruns++;
    }
    if ((sr & SR_RXNE) == 0u) {
        return;
    }
    if (head - g_tail >= RING) {
        /* no room: leave the byte where it is, stop being called for it */
        g_paused = 1u;
        REG(USART1_BASE, USART_CR1) = CR1_PAUSED;
        return;
    }
    g_ring[head & (RING - 1u)] = (uint8_t)(REG(USART1_BASE, USART_DR) & 0xFFu);
    barrier(); /* the byte is in the ring before the consumer can see it */
    g_head = head + 1u;
}

void uart_init(void)
{
    g_head = g_tail = g_paused = g_overruns = 0u;
    /* PA2, PA3, PA9, PA10: alternate function 7 (USART1/2) */
    REG(GPIOA_BASE, GPIO_MODER) = (REG(GPIOA_BASE, GPIO_MODER) & ~0x003C00F0u) | 0x002800A0u;
    REG(GPIOA_BASE, GPIO_AFRL) = (REG(GPIOA_BASE, GPIO_AFRL) & ~0x0000FF00u) | 0x00007700u;
    REG(GPIOA_BASE, GPIO_AFRH) = (REG(GPIOA_BASE, GPIO_AFRH) & ~0x00000FF0u) | 0x00000770u;
    REG(USART1_BASE, USART_BRR) = (BOARD_APB2_HZ + BOARD_BAUD / 2u) / BOARD_BAUD;
    REG(USART1_BASE, USART_CR1) = CR1_RUN;
    REG(USART2_BASE, USART_BRR) = (BOARD_APB1_HZ + BOARD_BAUD / 2u) / BOARD_BAUD;
    REG(USART2_BASE, USART_CR1) = CR1_UE | CR1_TE;
    NVIC_ISER1 = 1u << (USART1_IRQ - 32u);
}

static void putc_at(uint32_t base, uint8_t c)
{
    while ((REG(base, USART_SR) & SR_TXE) == 0u) {
    }
    REG(base, USART_DR) = c;
}

void uart_write(const uint8_t *p, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; ++i) {
        putc_at(USART1_BASE, p[i]);
    }
}

void uart_log_puts(const char *s)
{
    while (*s != '\0') {
        putc_at(USART2_BASE, (uint8_t)*s++);
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
        REG(USART1_BASE, USART_CR1) = CR1_RUN;
        __asm__ volatile("cpsie i" ::: "memory");
    }
    return c;
}

int uart_rx_empty(void) { return g_tail == g_head; }

uint32_t uart_rx_overruns(void) { return g_overruns; }
