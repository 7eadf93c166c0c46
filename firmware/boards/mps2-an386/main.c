/*
 * The firmware as a board on QEMU's mps2-an386 (Cortex-M4): frames arrive on
 * UART0 or, one frame per Ethernet frame, on the Ethernet controller
 * (eth_lan9118.c: the fast link under emulation); the shared board link
 * (firmware/link/board_link.c: handshake, reset, lockstep, watchdog) answers
 * them with the real firmware, and the answer goes back the way its request
 * came. Between frames the CPU sleeps.
 *
 * UART1 carries a profile of ffr_step: timer 0 counts read around every
 * step. Under QEMU with -icount shift=0 each instruction is 1 ns of virtual
 * time and the timer counts the 25 MHz clock, so one count is 40 instructions.
 * (The watchdog's milliseconds come from SysTick, every 10 ms, in virtual
 * time too: sleeping advances it with the host clock.)
 */
#include "board.h"
#include "board_loop.h"

/* CMSDK APB timer 0: a free-running 32-bit down-counter on the 25 MHz clock,
 * used only to profile ffr_step (SysTick is the millisecond clock; its
 * reload every millisecond would race with the readings). */
#define TIMER0_CTRL (*(volatile uint32_t *)0x40000000u)
#define TIMER0_VALUE (*(volatile uint32_t *)0x40000004u)
#define TIMER0_RELOAD (*(volatile uint32_t *)0x40000008u)

static void profile_clock_init(void)
{
    TIMER0_RELOAD = 0xFFFFFFFFu;
    TIMER0_VALUE = 0xFFFFFFFFu;
    TIMER0_CTRL = 1u; /* enable, no interrupt */
}

static uint32_t profile_clock(void) { return 0xFFFFFFFFu - TIMER0_VALUE; }

int main(void)
{
    static const board_loop_hooks_t with_eth = {profile_clock, uart1_puts, eth_recv, eth_send};
    static const board_loop_hooks_t uart_only = {profile_clock, uart1_puts, 0, 0};
    uart_init();
    board_clock_init();
    profile_clock_init();
    board_loop_run(eth_init() != 0u ? &with_eth : &uart_only);
    return 0;
}
