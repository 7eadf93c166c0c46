/*
 * Self-test image for mps2-an386: run the synthetic mission, print the
 * checksum and the instruction profile of ffr_step, exit. Under QEMU with
 * -icount shift=0 every instruction advances the virtual clock by 1 ns, and
 * SysTick counts the 25 MHz CPU clock: one count is exactly 40 instructions.
 */
#include "board.h"
#include "selftest.h"

#define SYST_CSR (*(volatile uint32_t *)0xE000E010u)
#define SYST_RVR (*(volatile uint32_t *)0xE000E014u)
#define SYST_CVR (*(volatile uint32_t *)0xE000E018u)
#define INSN_PER_COUNT 40u

/* SysTick counts down; the profile wants an up-counter */
static uint32_t systick_up(void) { return 0xFFFFFFu - SYST_CVR; }

static void put_u32(uint32_t v)
{
    char b[12];
    int n = 0;
    do {
        b[n++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v != 0u);
    while (n > 0) {
        uart_putc((uint8_t)b[--n]);
    }
}

int main(void)
{
    ffr_selftest_result_t res;
    char line[80];
    uart_init();
    /* free-running, no interrupt: nothing but ffr_step between two readings */
    SYST_RVR = 0xFFFFFFu;
    SYST_CVR = 0u;
    SYST_CSR = 5u;
    uart_puts("ffr mps2-an386 up\n");
    ffr_selftest_run(20000u, systick_up, &res);
    ffr_selftest_format(&res, line);
    uart_puts(line);
    uart_puts("ffr-profile steps=");
    put_u32(res.ticks);
    uart_puts(" mean_insn=");
    put_u32(res.clock_sum / res.ticks * INSN_PER_COUNT);
    uart_puts(" max_insn=");
    put_u32(res.clock_max * INSN_PER_COUNT);
    uart_puts("\n");
    return 0;
}
