#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

void suite_openings(void)
{
    ffr_config_t cfg;
    ffr_openings_t op;
    float ir[FFR_IR_COUNT];
    float d = 0.0f;
    int i;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    /* open from the start: no wall seen, so no opening (a corridor behind
     * a junction is not a door) */
    ffr_openings_reset(&op);
    rig_travel(&op, &cfg, ir, &d, 50);
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
    /* a wall for 150 mm, then open */
    ffr_openings_reset(&op);
    d = 0.0f;
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
    /* no reading at all (a dropout) counts half: 30 mm of it is not an
     * opening, 42 mm is */
    {
        ffr_openings_t op2;
        float ir2[FFR_IR_COUNT];
        float d2 = 0.0f;
        rig_no_walls(&cfg, ir2);
        ffr_openings_reset(&op2);
        ir2[FFR_IR_LF] = 226.0f;
        rig_travel(&op2, &cfg, ir2, &d2, 50);
        ir2[FFR_IR_LF] = FFR_IR_NONE(&cfg);
        rig_travel(&op2, &cfg, ir2, &d2, 10);
        CHECK(!ffr_opening(&op2, FFR_SIDE_LEFT));
        rig_travel(&op2, &cfg, ir2, &d2, 4);
        CHECK(ffr_opening(&op2, FFR_SIDE_LEFT));
    }
    /* the front hit jumping out 100 mm to the side (through a door, still
     * inside open_mm) is past the wall's end */
    {
        ffr_openings_t op3;
        float ir3[FFR_IR_COUNT];
        float d3 = 0.0f;
        rig_no_walls(&cfg, ir3);
        ffr_openings_reset(&op3);
        ir3[FFR_IR_LF] = 226.0f;
        rig_travel(&op3, &cfg, ir3, &d3, 50);
        ir3[FFR_IR_LF] = 226.0f + 100.0f / 0.70710678f;
        {
            ffr_ir_geom_t g;
            float px, py;
            CHECK(ffr_hit_beside(&cfg, rig_geom(&g, &cfg, ir3), ir3, FFR_IR_LF, &px, &py));
        }
        rig_travel(&op3, &cfg, ir3, &d3, 8);
        CHECK(ffr_opening(&op3, FFR_SIDE_LEFT));
        /* and the wall's end is the last hit on the wall, not the far one */
        CHECK_NEAR(op3.open_at_mm[FFR_SIDE_LEFT], 147.0f + 80.0f + 226.0f * 0.70710678f, 0.5);
        /* a slow drift out is followed, not taken for an opening */
        ffr_openings_reset(&op3);
        for (i = 0; i < 100; ++i, d3 += 3.0f) {
            ir3[FFR_IR_LF] = 226.0f + (float)i * 1.5f;
            ffr_ir_geom_t g;
            ffr_openings_update(&op3, &cfg, rig_geom(&g, &cfg, ir3), ir3, d3, 3.0f);
        }
        CHECK(op3.seen[FFR_SIDE_LEFT] && !ffr_opening(&op3, FFR_SIDE_LEFT));
    }
    /* latched: a wall seen again (the far side of a junction) does not undo it */
    ir[FFR_IR_LF] = 200.0f;
    rig_travel(&op, &cfg, ir, &d, 40);
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
}
