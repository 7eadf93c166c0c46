/* Self-test image for mps2-an386: run the synthetic mission, print the checksum, exit. */
#include "board.h"
#include "selftest.h"

int main(void)
{
    ffr_selftest_result_t res;
    char line[80];
    uart_init();
    board_clock_init();
    uart_puts("ffr mps2-an386 up\n");
    ffr_selftest_run(20000u, &res);
    ffr_selftest_format(&res, line);
    uart_puts(line);
    return 0;
}
