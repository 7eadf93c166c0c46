/*
 * Size probe for the Cortex-M4 build: the firmware with a minimal main, so
 * arm-none-eabi-size reports what the navigation code costs in flash and RAM
 * (state, config and I/O structs statically allocated, as on a real board).
 */
#include "ffr.h"

static ffr_state_t g_state;
static ffr_config_t g_cfg;
static ffr_inputs_t g_in;
static ffr_outputs_t g_out;

int main(void)
{
    ffr_config_default(&g_cfg);
    ffr_init(&g_state, &g_cfg);
    for (;;) {
        g_in.t_ms += 10u;
        g_in.seq += 1u;
        g_in.start = 1u;
        ffr_step(&g_state, &g_in, &g_out);
    }
}
