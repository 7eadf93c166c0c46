/*
 * Start-up for the nRF51822 (Cortex-M0, no FPU: soft float) on QEMU's
 * microbit: vector table, reset handler (copy .data, zero .bss), TIMER1 as
 * the millisecond clock (the nRF51's M0 has no SysTick), wfi idle,
 * semihosting output and exit.
 */
#include <stdint.h>

#include "board.h"

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
int main(void);
void reset_handler(void);
void default_handler(void);

#define REG(base, off) (*(volatile uint32_t *)((base) + (off)))
#define TIMER1_BASE 0x40009000u
#define TIMER_START 0x000u
#define TIMER_CLEAR 0x00Cu
#define TIMER_COMPARE0 0x140u
#define TIMER_SHORTS 0x200u
#define TIMER_INTENSET 0x304u
#define TIMER_MODE 0x504u
#define TIMER_BITMODE 0x508u
#define TIMER_PRESCALER 0x510u
#define TIMER_CC0 0x540u
#define NVIC_ISER0 (*(volatile uint32_t *)0xE000E100u)
#define UART0_IRQ 2
#define TIMER1_IRQ 9

static volatile uint32_t g_ms;

/* initial stack pointer, the 15 system exception handlers, the 32 interrupts */
typedef struct {
    uint32_t *sp;
    void (*handler[15])(void);
    void (*irq[32])(void);
} vector_table_t;

__attribute__((section(".vectors"), used)) static const vector_table_t vectors = {
    &_estack,
    {reset_handler, default_handler, default_handler, 0, 0, 0, 0, 0, 0, 0, default_handler, 0, 0, default_handler,
     default_handler},
    {[UART0_IRQ] = uart0_irq_handler, [TIMER1_IRQ] = timer1_irq_handler}, /* the others are never enabled */
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
    (void)main();
    board_exit(0);
}

void default_handler(void) { board_exit(99); }

/* TIMER1 compare 0 every 1,000 counts of 1 MHz; the short clears the counter */
void timer1_irq_handler(void)
{
    REG(TIMER1_BASE, TIMER_COMPARE0) = 0u;
    g_ms++;
}

void board_clock_init(void)
{
    REG(TIMER1_BASE, TIMER_MODE) = 0u;      /* timer */
    REG(TIMER1_BASE, TIMER_BITMODE) = 0u;   /* 16 bits */
    REG(TIMER1_BASE, TIMER_PRESCALER) = 4u; /* 16 MHz / 2^4 = 1 MHz */
    REG(TIMER1_BASE, TIMER_CC0) = 1000u;
    REG(TIMER1_BASE, TIMER_SHORTS) = 1u;        /* COMPARE0 -> CLEAR */
    REG(TIMER1_BASE, TIMER_INTENSET) = 1u << 16; /* COMPARE0 */
    REG(TIMER1_BASE, TIMER_CLEAR) = 1u;
    REG(TIMER1_BASE, TIMER_START) = 1u;
    NVIC_ISER0 = 1u << TIMER1_IRQ;
}

uint32_t board_millis(void) { return g_ms; }

void board_idle(void)
{
    /* masked, test, sleep: an interrupt that arrives after the test still
     * wakes the wfi, and is taken once unmasked */
    __asm__ volatile("cpsid i" ::: "memory");
    if (uart_rx_empty()) {
        __asm__ volatile("wfi");
    }
    __asm__ volatile("cpsie i" ::: "memory");
}

static void semihost(uint32_t op, uint32_t arg)
{
    register uint32_t r0 __asm__("r0") = op;
    register uint32_t r1 __asm__("r1") = arg;
    __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
}

/* SYS_WRITE0: a NUL-terminated string to the debugger's console */
void board_log_puts(const char *s) { semihost(0x04u, (uint32_t)(uintptr_t)s); }

/* SYS_EXIT: QEMU (-semihosting) ends with this status. */
void board_exit(int status)
{
    for (;;) {
        semihost(0x18u, status == 0 ? 0x20026u : 0x20024u); /* ApplicationExit / RunTimeError */
    }
}
