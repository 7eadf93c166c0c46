/*
 * The firmware as a board on QEMU's netduinoplus2 (STM32F405, Cortex-M4F):
 * frames arrive on USART1, the shared board link (firmware/link/board_link.c:
 * handshake, reset, lockstep, watchdog) answers them with the real firmware,
 * the answer goes back on USART1. Between frames the CPU sleeps.
 *
 * USART2 carries a profile of ffr_step: TIM2 (32-bit, free-running) read
 * around every step. Under QEMU with -icount shift=0 each instruction is 1 ns
 * of virtual time; QEMU clocks its STM32 timers at 1 GHz, so one count is one
 * instruction (a real F405 counts 84 MHz timer ticks: 2 CPU cycles each).
 * The watchdog's milliseconds come from SysTick's interrupt (168 MHz core
 * clock), in virtual time too: sleeping advances it with the host clock.
 */
#include "board.h"
#include "board_loop.h"

/* TIM2: a free-running 32-bit up-counter, prescaler 1, used only to profile
 * ffr_step (SysTick is the millisecond clock; its reload every millisecond
 * would race with the readings). */
#define TIM2_CR1 (*(volatile uint32_t *)0x40000000u)
#define TIM2_EGR (*(volatile uint32_t *)0x40000014u)
#define TIM2_CNT (*(volatile uint32_t *)0x40000024u)
#define TIM2_PSC (*(volatile uint32_t *)0x40000028u)
#define TIM2_ARR (*(volatile uint32_t *)0x4000002Cu)

static void profile_clock_init(void)
{
    TIM2_PSC = 0u;
    TIM2_ARR = 0xFFFFFFFFu;
    TIM2_EGR = 1u; /* UG: load the prescaler */
    TIM2_CR1 = 1u; /* CEN: count up */
}

static uint32_t profile_clock(void) { return TIM2_CNT; }

int main(void)
{
    static const board_loop_hooks_t hooks = {profile_clock, uart_log_puts, 0, 0};
    uart_init();
    board_clock_init();
    profile_clock_init();
    board_loop_run(&hooks);
    return 0;
}
