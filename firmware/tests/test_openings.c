#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

TEST(open_from_the_start_is_no_opening)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    /* no wall seen, so no opening (a corridor behind a junction is not a door) */
    ffr_openings_reset(&op);
    rig_travel(&op, &cfg, ir, &d, 50);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
}

TEST(a_wall_then_open_is_an_opening_and_stays_one)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    /* a wall for 150 mm, then open */
    ffr_openings_reset(&op);
    ir[FFR_IR_LF] = 226.0f;
    rig_travel(&op, &cfg, ir, &d, 50);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
    {
        float wall_end = op.open_at_mm[FFR_SIDE_LEFT];
        /* the hit point is ahead of the origin by x + d cos(45) */
        CHECK_NEAR(wall_end, (d - 3.0f) + 80.0f + 226.0f * 0.70710678f, 0.5);
    }
    /* the beam through the opening meets a far wall (565 mm to the side) */
    ir[FFR_IR_LF] = 700.0f;
    rig_travel(&op, &cfg, ir, &d, 5);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT)); /* 15 mm < confirm */
    rig_travel(&op, &cfg, ir, &d, 5);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
    CHECK(!ffr_opening(&op, FFR_SIDE_RIGHT));
    CHECK_NEAR(op.since_open_mm[FFR_SIDE_LEFT], 0.0, 1e-6);
    CHECK_NEAR(op.since_open_mm[FFR_SIDE_RIGHT], 0.0, 1e-6); /* nothing there reads open */
    /* latched: a wall seen again (the far side of a junction) does not undo it */
    ir[FFR_IR_LF] = 200.0f;
    rig_travel(&op, &cfg, ir, &d, 40);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
}

TEST(a_dropout_counts_half)
{
    /* no reading at all counts half: 30 mm of it is not an opening, 42 mm is */
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    ffr_openings_reset(&op);
    ir[FFR_IR_LF] = 226.0f;
    rig_travel(&op, &cfg, ir, &d, 50);
    ir[FFR_IR_LF] = FFR_IR_NONE(&cfg);
    rig_travel(&op, &cfg, ir, &d, 10);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
    rig_travel(&op, &cfg, ir, &d, 4);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
}

TEST(a_hit_jumping_out_is_past_the_wall_end_a_drift_is_followed)
{
    /* the front hit jumping out 100 mm to the side (through a door, still
     * inside open_mm) is past the wall's end */
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    int i;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    ffr_openings_reset(&op);
    ir[FFR_IR_LF] = 226.0f;
    rig_travel(&op, &cfg, ir, &d, 50);
    ir[FFR_IR_LF] = 226.0f + 100.0f / 0.70710678f;
    {
        ffr_ir_geom_t g;
        float px, py;
        CHECK(ffr_hit_beside(&cfg, rig_geom(&g, &cfg, ir), ir, FFR_IR_LF, &px, &py));
    }
    rig_travel(&op, &cfg, ir, &d, 8);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
    /* and the wall's end is the last hit on the wall, not the far one */
    CHECK_NEAR(op.open_at_mm[FFR_SIDE_LEFT], 147.0f + 80.0f + 226.0f * 0.70710678f, 0.5);
    /* a slow drift out is followed, not taken for an opening */
    ffr_openings_reset(&op);
    for (i = 0; i < 100; ++i, d += 3.0f) {
        ffr_ir_geom_t g;
        ir[FFR_IR_LF] = 226.0f + (float)i * 1.5f;
        ffr_openings_update(&op, &cfg, rig_geom(&g, &cfg, ir), ir, d, 3.0f);
    }
    CHECK(op.seen[FFR_SIDE_LEFT] && !ffr_opening(&op, FFR_SIDE_LEFT));
}

SUITE(openings,
      TEST_REF(open_from_the_start_is_no_opening),
      TEST_REF(a_wall_then_open_is_an_opening_and_stays_one),
      TEST_REF(a_dropout_counts_half),
      TEST_REF(a_hit_jumping_out_is_past_the_wall_end_a_drift_is_followed));
