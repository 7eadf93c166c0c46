#include "ffr_internal.h"
#include "unit.h"

TEST(two_lines_two_edges)
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
}

TEST(a_flicker_inside_the_hold_off_is_the_same_line)
{
    ffr_config_t cfg;
    ffr_line_counter_t l;
    int i;
    ffr_config_default(&cfg);
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
}

TEST(a_misread_is_no_line_the_third_white_tick_is_the_edge)
{
    ffr_config_t cfg;
    ffr_line_counter_t l;
    ffr_config_default(&cfg);
    ffr_lines_reset(&l);
    /* a misread of one or two ticks is no line at all */
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
}

TEST(standing_on_a_line_one_edge_only)
{
    ffr_config_t cfg;
    ffr_line_counter_t l;
    int i;
    ffr_config_default(&cfg);
    ffr_lines_reset(&l);
    for (i = 0; i < 10; ++i) {
        ffr_lines_update(&l, &cfg, 1, 0.0f);
    }
    CHECK(l.count == 1);
}

SUITE(line_counter,
      TEST_REF(two_lines_two_edges),
      TEST_REF(a_flicker_inside_the_hold_off_is_the_same_line),
      TEST_REF(a_misread_is_no_line_the_third_white_tick_is_the_edge),
      TEST_REF(standing_on_a_line_one_edge_only));
