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
    for (i = 0; i < 50; ++i, d += 3.0f) {
        ffr_openings_update(&op, &cfg, ir, d, 3.0f);
    }
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
    /* a wall for 150 mm, then open */
    ffr_openings_reset(&op);
    d = 0.0f;
    ir[FFR_IR_LF] = 226.0f;
    for (i = 0; i < 50; ++i, d += 3.0f) {
        ffr_openings_update(&op, &cfg, ir, d, 3.0f);
    }
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT));
    {
        float wall_end = op.open_at_mm[FFR_SIDE_LEFT];
        /* the hit point is ahead of the origin by x + d cos(45) */
        CHECK_NEAR(wall_end, (d - 3.0f) + 80.0f + 226.0f * 0.70710678f, 0.5);
    }
    ir[FFR_IR_LF] = FFR_IR_NONE(&cfg);
    for (i = 0; i < 5; ++i, d += 3.0f) {
        ffr_openings_update(&op, &cfg, ir, d, 3.0f);
    }
    CHECK(!ffr_opening(&op, FFR_SIDE_LEFT)); /* 15 mm < confirm */
    for (i = 0; i < 5; ++i, d += 3.0f) {
        ffr_openings_update(&op, &cfg, ir, d, 3.0f);
    }
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
    CHECK(!ffr_opening(&op, FFR_SIDE_RIGHT));
    CHECK_NEAR(op.since_open_mm[FFR_SIDE_LEFT], 0.0, 1e-6);
    CHECK_NEAR(op.since_open_mm[FFR_SIDE_RIGHT], 0.0, 1e-6); /* nothing there reads open */
    /* latched: a wall seen again (the far side of a junction) does not undo it */
    ir[FFR_IR_LF] = 200.0f;
    for (i = 0; i < 40; ++i, d += 3.0f) {
        ffr_openings_update(&op, &cfg, ir, d, 3.0f);
    }
    CHECK(ffr_opening(&op, FFR_SIDE_LEFT));
}
