/*
 * Size probe of a Cortex-M4 board with the wire: the firmware, the codec and
 * the board link behind a byte-at-a-time UART, so arm-none-eabi-size reports
 * what talking to the harness costs in flash and RAM. The UART and the
 * millisecond clock are stand-in registers (STM32F4 USART2 and a timer).
 */
#include "ffr_codec.h"
#include "ffr_link.h"

#define UART_SR (*(volatile uint32_t *)0x40004400u)
#define UART_DR (*(volatile uint32_t *)0x40004404u)
#define TIMER_MS (*(volatile uint32_t *)0x40000024u)
#define UART_RXNE 0x20u
#define UART_TXE 0x80u

static ffr_board_link_t g_link;
static ffr_deframer_t g_rx;
static uint8_t g_msg[FFR_MSG_MAX + 2u];
static uint8_t g_reply[FFR_MSG_MAX];
static uint8_t g_frame[FFR_FRAME_MAX];

static void uart_send(size_t len)
{
    size_t i;
    size_t n = len > 0u ? ffr_frame_encode(g_reply, len, g_frame, sizeof(g_frame)) : 0u;
    for (i = 0; i < n; ++i) {
        while ((UART_SR & UART_TXE) == 0u) {
        }
        UART_DR = g_frame[i];
    }
}

int main(void)
{
    ffr_board_link_init(&g_link, FFR_WATCHDOG_DEFAULT_MS, TIMER_MS);
    ffr_deframer_init(&g_rx);
    for (;;) {
        if ((UART_SR & UART_RXNE) != 0u) {
            const uint8_t *f = 0;
            size_t flen = 0, mlen = 0;
            int got = ffr_deframer_push(&g_rx, (uint8_t)UART_DR, &f, &flen);
            if (got < 0) {
                uart_send(ffr_board_link_on_bad_frame(&g_link, got, g_reply, sizeof(g_reply)));
            } else if (got > 0) {
                int st = ffr_frame_decode(f, flen, g_msg, sizeof(g_msg), &mlen);
                uart_send(st != FFR_OK ? ffr_board_link_on_bad_frame(&g_link, st, g_reply, sizeof(g_reply))
                                       : ffr_board_link_on_msg(&g_link, g_msg, mlen, TIMER_MS, g_reply,
                                                               sizeof(g_reply)));
            }
        }
        uart_send(ffr_board_link_poll(&g_link, TIMER_MS, g_reply, sizeof(g_reply)));
    }
}
