#include "ffr_internal.h"
#include "unit.h"

void suite_line_counter(void)
{
    ffr_config_t cfg;
    ffr_line_counter_t l;
    float d = 0.0f;
    int i, edges = 0;
    ffr_config_default(&cfg);
    ffr_lines_reset(&l);
    /* two 25 mm lines 300 mm apart, sampled every 3 mm */
    for (i = 0; i < 300; ++i, d += 3.0f) {
        uint8_t white = (d >= 100.0f && d < 125.0f) || (d >= 400.0f && d < 425.0f);
        ffr_lines_update(&l, &cfg, white, d);
        edges += l.edge;
    }
    CHECK(edges == 2);
    CHECK(l.count == 2);
    /* a flicker inside the hold-off is the same line */
    ffr_lines_reset(&l);
    for (i = 0; i < 3; ++i) {
        ffr_lines_update(&l, &cfg, 1, (float)i);
    }
    CHECK(l.count == 1);
    ffr_lines_update(&l, &cfg, 0, 5.0f);
    for (i = 0; i < 3; ++i) {
        ffr_lines_update(&l, &cfg, 1, 10.0f + (float)i);
    }
    CHECK(l.count == 1);
    CHECK(l.edge == 0);
    /* a misread of one or two ticks is no line at all */
    ffr_lines_reset(&l);
    ffr_lines_update(&l, &cfg, 1, 0.0f);
    ffr_lines_update(&l, &cfg, 0, 3.0f);
    ffr_lines_update(&l, &cfg, 1, 100.0f);
    ffr_lines_update(&l, &cfg, 1, 103.0f);
    ffr_lines_update(&l, &cfg, 0, 106.0f);
    CHECK(l.count == 0);
    /* the third white tick in a row is the edge */
    ffr_lines_update(&l, &cfg, 1, 200.0f);
    ffr_lines_update(&l, &cfg, 1, 203.0f);
    CHECK(l.count == 0);
    ffr_lines_update(&l, &cfg, 1, 206.0f);
    CHECK(l.count == 1 && l.edge == 1);
    /* standing on a line: one edge only */
    ffr_lines_reset(&l);
    for (i = 0; i < 10; ++i) {
        ffr_lines_update(&l, &cfg, 1, 0.0f);
    }
    CHECK(l.count == 1);
}
