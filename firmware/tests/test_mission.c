/*
 * State transitions of the whole firmware with plain inputs: a fake drive
 * (spy on the PWM, encoders advanced in proportion) and hand-set rangers,
 * line and flame readings. No plant.
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

TEST(corridor_route)
{
    ffr_config_t cfg;
    rig_t r;
    int i;
    ffr_config_default(&cfg);
    rig_init(&r, &cfg);

    /* no start signal: idle, motors off */
    for (i = 0; i < 10; ++i) {
        rig_tick(&r);
    }
    CHECK(r.out.state == FFR_ST_IDLE);
    CHECK(r.out.pwm[0] == 0 && r.out.pwm[1] == 0 && r.out.fan == 0);

    /* start: the first route step follows a wall forward */
    r.in.start = 1;
    r.in.ir_mv[FFR_IR_RF] = rig_mv_for_mm(&cfg, 226.0f);
    r.in.ir_mv[FFR_IR_RR] = rig_mv_for_mm(&cfg, 226.0f);
    for (i = 0; i < 30; ++i) {
        rig_tick(&r);
    }
    CHECK(r.out.state == FFR_ST_FOLLOW);
    CHECK(r.out.step == 0);
    CHECK(r.out.pwm[0] > 100 && r.out.pwm[1] > 100);

    /* wall ahead, wall on the right, left open: case "corner left" */
    r.in.ir_mv[FFR_IR_CF] = rig_mv_for_mm(&cfg, 110.0f);
    rig_tick(&r);
    CHECK(r.out.state == FFR_ST_TURN);
    CHECK(r.out.step == 1);
    CHECK(rig_run_until_state(&r, FFR_ST_FOLLOW, 500));
    CHECK(r.out.step == 2);
    CHECK_NEAR(r.st.odo.heading_rad, 0.5 * 3.14159265, 2.0f * FFR_DEG);
    /* the held heading is the turn's target: square to the wall that was followed */
    CHECK_NEAR(r.st.route.heading_ref_rad, r.st.route.target_rad, 1e-6);
    CHECK_NEAR(r.st.route.heading_ref_rad, 0.5 * 3.14159265, 0.5f * FFR_DEG);
}

TEST(room_task)
{
    ffr_config_t cfg;
    rig_t r;
    int i, seen_scan = 0;
    ffr_config_default(&cfg);
    cfg.route_len = 0;
    /* a one-room route: ROOM(1), END; the way home is HOME */
    rig_room_route(&cfg, 1);
    rig_init(&r, &cfg);
    r.in.start = 1;
    rig_tick(&r);
    CHECK(r.out.state == FFR_ST_ENTER);
    CHECK(r.out.room == 1);

    /* the doorway line passes under the sensor */
    rig_line(&r, 20, 4);
    CHECK((r.out.flags & FFR_FLAG_IN_ROOM) != 0);
    CHECK(rig_run_until_state(&r, FFR_ST_SCAN, 400));

    /* scanning: the flame signal rises and falls with the heading */
    for (i = 0; i < 400 && r.out.state == FFR_ST_SCAN; ++i) {
        float deg = r.st.odo.heading_rad / FFR_DEG;
        float s = deg > 60.0f && deg < 100.0f ? 900.0f - 20.0f * (deg - 80.0f) * (deg - 80.0f) / 10.0f : 20.0f;
        if (s < 20.0f) {
            s = 20.0f;
        }
        r.in.flame[0] = r.in.flame[1] = (uint16_t)s;
        seen_scan = 1;
        rig_tick(&r);
    }
    CHECK(seen_scan);
    CHECK((r.out.flags & FFR_FLAG_FLAME_SEEN) != 0);
    /* it turns back to the strongest heading (80 deg) and approaches */
    r.in.flame[0] = r.in.flame[1] = 900;
    CHECK(rig_run_until_state(&r, FFR_ST_APPROACH, 400));
    CHECK_NEAR(r.st.odo.heading_rad / FFR_DEG, 80.0, 6.0);
    /* steering: more on the left sensor turns left */
    r.in.flame[0] = 1200;
    r.in.flame[1] = 600;
    rig_tick(&r);
    CHECK(r.st.cmd_w_rad_s > 0.0f);
    r.in.flame[0] = r.in.flame[1] = 900;
    for (i = 0; i < 30; ++i) {
        rig_tick(&r);
    }
    /* the candle circle: stop, fans on */
    rig_line(&r, 0, 3);
    rig_tick(&r);
    CHECK(r.out.state == FFR_ST_EXTINGUISH);
    CHECK(r.out.fan == 1);
    for (i = 0; i < 100; ++i) {
        rig_tick(&r);
    }
    CHECK(r.out.fan == 1);
    /* the flame goes out: fans off, verify, then back to the door */
    r.in.flame[0] = r.in.flame[1] = 20;
    CHECK(rig_run_until_state(&r, FFR_ST_VERIFY, 100));
    CHECK(r.out.fan == 0);
    CHECK(rig_run_until_state(&r, FFR_ST_TO_DOOR, 200));
    CHECK((r.out.flags & FFR_FLAG_EXTINGUISHED) != 0);
    CHECK(rig_run_until_state(&r, FFR_ST_EXIT, 1500));
    /* out across the doorway line, then the way home starts */
    CHECK(rig_run_until_driving(&r, 400));
    CHECK(r.out.state == FFR_ST_EXIT);
    rig_line(&r, 0, 3);
    CHECK((r.out.flags & FFR_FLAG_IN_ROOM) == 0);
    CHECK(rig_run_until_state(&r, FFR_ST_HOMING, 400));
    CHECK(r.out.rooms_searched == 1);
    /* the home circle: stop just past it */
    rig_line(&r, 40, 3);
    CHECK(rig_run_until_state(&r, FFR_ST_DONE, 400));
    CHECK((r.out.flags & FFR_FLAG_DONE) != 0);
    rig_tick(&r);
    CHECK(r.out.pwm[0] == 0 && r.out.pwm[1] == 0 && r.out.fan == 0);
}

TEST(no_flame_anywhere)
{
    ffr_config_t cfg;
    rig_t r;
    ffr_config_default(&cfg);
    rig_room_route(&cfg, 0);
    rig_init(&r, &cfg);
    r.in.start = 1;
    rig_tick(&r);
    rig_line(&r, 0, 3);
    CHECK(rig_run_until_state(&r, FFR_ST_SCAN, 400));
    /* a full turn with no flame: leave the room */
    CHECK(rig_run_until_state(&r, FFR_ST_EXIT, 2000));
    CHECK((r.out.flags & FFR_FLAG_FLAME_SEEN) == 0);
    CHECK(rig_run_until_driving(&r, 400));
    rig_line(&r, 0, 3);
    CHECK(rig_run_until_state(&r, FFR_ST_FAILED, 400));
    CHECK(r.out.fail_code == FFR_FAIL_NO_FLAME);
    CHECK(r.out.pwm[0] == 0 && r.out.pwm[1] == 0);
}

TEST(bad_room_number)
{
    ffr_config_t cfg;
    rig_t r;
    ffr_config_default(&cfg);
    cfg.route[0].op = FFR_OP_ROOM;
    cfg.route[0].arg = 9;
    rig_init(&r, &cfg);
    r.in.start = 1;
    rig_tick(&r);
    CHECK(r.out.state == FFR_ST_FAILED);
    CHECK(r.out.fail_code == FFR_FAIL_BAD_ROUTE);
}

SUITE(mission,
      TEST_REF(corridor_route),
      TEST_REF(room_task),
      TEST_REF(no_flame_anywhere),
      TEST_REF(bad_room_number));
