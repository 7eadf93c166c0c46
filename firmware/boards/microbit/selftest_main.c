/*
 * Self-test image for the micro:bit (Cortex-M0, soft float): run the
 * synthetic mission, print the checksum and the instruction profile of
 * ffr_step by semihosting, exit. Equal to the host's checksum means libgcc's
 * soft float gave the same IEEE float32 bits as the host's FPU, 20,000 ticks
 * long. Under QEMU with -icount shift=0 one TIMER0 count (16 MHz) is 62.5
 * instructions.
 */
#include "board.h"
#include "selftest.h"

#define TIMER0_START (*(volatile uint32_t *)0x40008000u)
#define TIMER0_CAPTURE0 (*(volatile uint32_t *)0x40008040u)
#define TIMER0_BITMODE (*(volatile uint32_t *)0x40008508u)
#define TIMER0_CC0 (*(volatile uint32_t *)0x40008540u)

static uint32_t timer0(void)
{
    TIMER0_CAPTURE0 = 1u;
    return TIMER0_CC0;
}

static char *put_u32(char *p, uint32_t v)
{
    char b[12];
    int n = 0;
    do {
        b[n++] = (char)('0' + (int)(v % 10u));
        v /= 10u;
    } while (v != 0u);
    while (n > 0) {
        *p++ = b[--n];
    }
    return p;
}

static char *put_s(char *p, const char *s)
{
    while (*s != '\0') {
        *p++ = *s++;
    }
    return p;
}

int main(void)
{
    static ffr_selftest_result_t res;
    static char line[96];
    char *p = line;
    TIMER0_BITMODE = 3u; /* 32 bits, 16 MHz */
    TIMER0_START = 1u;
    board_log_puts("ffr microbit up\n");
    ffr_selftest_run(20000u, timer0, &res);
    ffr_selftest_format(&res, line);
    board_log_puts(line);
    /* instructions = counts * 62.5 = counts * 125 / 2 */
    p = put_s(p, "ffr-profile steps=");
    p = put_u32(p, res.ticks);
    p = put_s(p, " mean_insn=");
    p = put_u32(p, res.clock_sum / res.ticks * 125u / 2u);
    p = put_s(p, " max_insn=");
    p = put_u32(p, res.clock_max * 125u / 2u);
    p = put_s(p, "\n");
    *p = '\0';
    board_log_puts(line);
    return 0;
}
