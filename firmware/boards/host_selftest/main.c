/* The self-test on the host: the same synthetic mission, the same checksum line. */
#include <stdio.h>

#include "selftest.h"

int main(void)
{
    ffr_selftest_result_t res;
    char line[80];
    ffr_selftest_run(20000u, 0, &res);
    ffr_selftest_format(&res, line);
    fputs(line, stdout);
    return 0;
}
