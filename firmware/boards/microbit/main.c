/*
 * The firmware as a board on QEMU's microbit (nRF51822, Cortex-M0, soft
 * float): frames arrive on UART0, the shared board link
 * (firmware/link/board_link.c: handshake, reset, lockstep, watchdog) answers
 * them with the real firmware, the answer goes back on UART0. Between frames
 * the CPU sleeps.
 *
 * The profile of ffr_step goes out by semihosting (the nRF51 has one UART):
 * TIMER0, free-running at 16 MHz, captured around every step. Under QEMU
 * with -icount shift=0 each instruction is 1 ns of virtual time, so one count
 * is 62.5 instructions (on the real chip one count is one CPU cycle).
 * The watchdog's milliseconds come from TIMER1's interrupt, in virtual time
 * too: sleeping advances it with the host clock.
 */
#include "board.h"
#include "board_loop.h"

/* 1: the ready line and the profile by semihosting (QEMU -semihosting, or a probe
 * serving it: without one, the bkpt would fault). The image for a bare micro:bit
 * is built with 0 (make build/arm/microbit-hw.elf). */
#ifndef BOARD_PROFILE_LOG
#define BOARD_PROFILE_LOG 1
#endif

/* TIMER0: a free-running 32-bit up-counter at 16 MHz, read by capturing it
 * into CC[0]; used only to profile ffr_step. */
#define TIMER0_START (*(volatile uint32_t *)0x40008000u)
#define TIMER0_CAPTURE0 (*(volatile uint32_t *)0x40008040u)
#define TIMER0_MODE (*(volatile uint32_t *)0x40008504u)
#define TIMER0_BITMODE (*(volatile uint32_t *)0x40008508u)
#define TIMER0_PRESCALER (*(volatile uint32_t *)0x40008510u)
#define TIMER0_CC0 (*(volatile uint32_t *)0x40008540u)

static void profile_clock_init(void)
{
    TIMER0_MODE = 0u;      /* timer */
    TIMER0_BITMODE = 3u;   /* 32 bits */
    TIMER0_PRESCALER = 0u; /* 16 MHz */
    TIMER0_START = 1u;
}

static uint32_t profile_clock(void)
{
    TIMER0_CAPTURE0 = 1u;
    return TIMER0_CC0;
}

int main(void)
{
    static const board_loop_hooks_t hooks = {profile_clock, BOARD_PROFILE_LOG ? board_log_puts : 0, 0, 0};
    uart_init();
    board_clock_init();
    profile_clock_init();
    board_loop_run(&hooks);
    return 0;
}
