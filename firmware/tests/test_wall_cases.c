#include "ffr_internal.h"
#include "unit.h"

static void set(float *ir, const ffr_config_t *cfg, int front, int left, int right)
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        ir[i] = FFR_IR_NONE(cfg);
    }
    if (front) {
        ir[FFR_IR_CF] = 150.0f;
    }
    if (left) {
        ir[FFR_IR_LF] = 200.0f;
        ir[FFR_IR_LR] = 200.0f;
    }
    if (right) {
        ir[FFR_IR_RF] = 200.0f;
        ir[FFR_IR_RR] = 200.0f;
    }
}

void suite_wall_cases(void)
{
    ffr_config_t cfg;
    float ir[FFR_IR_COUNT];
    ffr_config_default(&cfg);

    set(ir, &cfg, 1, 0, 1);
    CHECK(ffr_wall_case(&cfg, ir) == FFR_CASE_CORNER_LEFT);
    CHECK(ffr_wall_case_turn(FFR_CASE_CORNER_LEFT, FFR_SIDE_RIGHT) == 90);

    set(ir, &cfg, 1, 1, 0);
    CHECK(ffr_wall_case(&cfg, ir) == FFR_CASE_CORNER_RIGHT);
    CHECK(ffr_wall_case_turn(FFR_CASE_CORNER_RIGHT, FFR_SIDE_LEFT) == -90);

    set(ir, &cfg, 1, 0, 0);
    CHECK(ffr_wall_case(&cfg, ir) == FFR_CASE_T);
    CHECK(ffr_wall_case_turn(FFR_CASE_T, FFR_SIDE_LEFT) == 90);
    CHECK(ffr_wall_case_turn(FFR_CASE_T, FFR_SIDE_RIGHT) == -90);

    set(ir, &cfg, 1, 1, 1);
    CHECK(ffr_wall_case(&cfg, ir) == FFR_CASE_DEAD_END);
    CHECK(ffr_wall_case_turn(FFR_CASE_DEAD_END, FFR_SIDE_NONE) == 180);

    set(ir, &cfg, 0, 0, 1);
    CHECK(ffr_wall_case(&cfg, ir) == FFR_CASE_BRANCH_LEFT);
    CHECK(ffr_wall_case_turn(FFR_CASE_BRANCH_LEFT, FFR_SIDE_LEFT) == 90);
    CHECK(ffr_wall_case_turn(FFR_CASE_BRANCH_LEFT, FFR_SIDE_NONE) == 0);

    set(ir, &cfg, 0, 1, 0);
    CHECK(ffr_wall_case(&cfg, ir) == FFR_CASE_BRANCH_RIGHT);
    CHECK(ffr_wall_case_turn(FFR_CASE_BRANCH_RIGHT, FFR_SIDE_RIGHT) == -90);
    CHECK(ffr_wall_case_turn(FFR_CASE_BRANCH_RIGHT, FFR_SIDE_LEFT) == 0);

    set(ir, &cfg, 0, 1, 1);
    CHECK(ffr_wall_case(&cfg, ir) == FFR_CASE_CORRIDOR);
    CHECK(ffr_wall_case_turn(FFR_CASE_CORRIDOR, FFR_SIDE_LEFT) == 0);

    set(ir, &cfg, 0, 0, 0);
    CHECK(ffr_wall_case(&cfg, ir) == FFR_CASE_OPEN);
}
