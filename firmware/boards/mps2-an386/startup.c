/*
 * Start-up for the Cortex-M4 on QEMU's mps2-an386: vector table, reset
 * handler (copy .data, zero .bss, enable the FPU), SysTick millisecond clock.
 *
 * SysTick interrupts every TICK_MS (10 ms), not every millisecond: the
 * milliseconds in between come from its down-counter. Its interrupt is the
 * link watchdog's only wake-up while the board sleeps, and under QEMU each one
 * wakes the emulator's threads (docs/pil.md, "Speed": at 1 kHz that was about
 * half of QEMU's thread switches a tick over the Ethernet link). The watchdog
 * then trips up to 10 ms after its deadline.
 */
#include <stdint.h>

#include "board.h"

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
int main(void);
void reset_handler(void);
void default_handler(void);
void systick_handler(void);

#define SCB_CPACR (*(volatile uint32_t *)0xE000ED88u)
#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)

#define TICK_MS 10u
#define COUNTS_PER_MS (BOARD_CPU_HZ / 1000u)

/* the one piece of board state an interrupt must reach: SysTick periods so far */
static volatile uint32_t g_ticks;

/* initial stack pointer, the 15 system exception handlers, the external interrupts */
typedef struct {
    uint32_t *sp;
    void (*handler[15])(void);
    void (*irq[32])(void);
} vector_table_t;

__attribute__((section(".vectors"), used)) static const vector_table_t vectors = {
    &_estack,
    {reset_handler, default_handler, default_handler, default_handler, default_handler, default_handler, 0, 0, 0,
     0, default_handler, default_handler, 0, default_handler, systick_handler},
    /* IRQ 0: UART0 receive; IRQ 13: Ethernet; the others are never enabled */
    {uart0_rx_handler, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, eth_irq_handler},
};

void reset_handler(void)
{
    uint32_t *src = &_sidata;
    uint32_t *dst;
    for (dst = &_sdata; dst < &_edata;) {
        *dst++ = *src++;
    }
    for (dst = &_sbss; dst < &_ebss;) {
        *dst++ = 0u;
    }
    SCB_CPACR |= 0xFu << 20; /* CP10, CP11: the FPU, before any float code runs */
    __asm__ volatile("dsb\n isb");
    (void)main();
    board_exit(0);
}

void default_handler(void)
{
    board_exit(99);
}

void systick_handler(void) { g_ticks++; }

void board_clock_init(void)
{
    SYST_RVR = COUNTS_PER_MS * TICK_MS - 1u;
    SYST_CVR = 0u;
    SYST_CSR = 7u; /* processor clock, interrupt, enable */
}

/* the last value board_millis returned (main loop only: the only caller) */
static uint32_t g_last_ms;

/* periods * TICK_MS + the counts gone in this period. The count and the period belong
 * together unless the counter has reloaded while its interrupt is not yet taken (an emulator
 * runs its timer callbacks between blocks of instructions): then the sum is up to one period
 * behind, or ahead. So the reads are repeated while the period count moves under them, and
 * the result never goes back: a clock that stepped back would make the link watchdog see an
 * age of four billion milliseconds (seen once in a UART mission, a WATCHDOG report). Ahead by
 * up to 10 ms, it waits until the true time catches up. */
uint32_t board_millis(void)
{
    uint32_t ticks, left, now;
    do {
        ticks = g_ticks;
        left = SYST_CVR;
    } while (ticks != g_ticks);
    now = ticks * TICK_MS + (SYST_RVR - left) / COUNTS_PER_MS;
    if ((int32_t)(now - g_last_ms) > 0) {
        g_last_ms = now;
    }
    return g_last_ms;
}

void board_idle(void)
{
    /* masked, test, sleep: an interrupt that arrives after the test still
     * wakes the wfi, and is taken once unmasked (the Ethernet's wake-up is
     * armed here, masked: eth_lan9118.c) */
    __asm__ volatile("cpsid i" ::: "memory");
    if (uart_rx_empty() && eth_idle_arm() != 0u) {
        __asm__ volatile("wfi");
    }
    __asm__ volatile("cpsie i" ::: "memory");
}

/* ARM semihosting SYS_EXIT: QEMU (-semihosting) ends with this status. */
void board_exit(int status)
{
    register uint32_t r0 __asm__("r0") = 0x18u;
    register uint32_t r1 __asm__("r1") = status == 0 ? 0x20026u : 0x20024u; /* ApplicationExit / RunTimeError */
    for (;;) {
        __asm__ volatile("bkpt 0xAB" : : "r"(r0), "r"(r1) : "memory");
    }
}
