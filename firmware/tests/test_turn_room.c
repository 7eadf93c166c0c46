/*
 * Turning in place near a wall ahead (turn.c, proximity.c): the front
 * distance projected over the reading's age, backing away from a wall inside
 * the corners' circle, and a turn held back while the body still rolls on.
 */
#include "ffr_internal.h"
#include "rig.h"
#include "unit.h"

static float corner_radius(const ffr_config_t *cfg)
{
    return ffr_sqrtf(cfg->body_front_mm * cfg->body_front_mm + cfg->body_half_width_mm * cfg->body_half_width_mm);
}

static void odo_moving(ffr_odometry_t *o, float v_mm_s)
{
    ffr_odometry_reset(o);
    o->v_mm_s[0] = v_mm_s;
    o->v_mm_s[1] = v_mm_s;
}

TEST(front_distance_is_projected_over_the_reading_age)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    float ir[FFR_IR_COUNT];
    int i, k;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    /* nothing ahead: nothing to project, at any speed */
    odo_moving(&o, 320.0f);
    CHECK(ffr_front_now(&cfg, &o, ir) >= 1.0e6f);
    for (i = 0; i <= 20; ++i) {
        float d = 100.0f + 30.0f * (float)i; /* readings over the part's range */
        ir[FFR_IR_CF] = d;
        for (k = -4; k <= 8; ++k) {
            float v = 40.0f * (float)k; /* backing at 160 mm/s to cruise and past it */
            float now;
            odo_moving(&o, v);
            now = ffr_front_now(&cfg, &o, ir);
            if (v <= 0.0f) {
                /* standing or backing away: the reading as it is */
                CHECK_NEAR(now, ffr_front_distance(&cfg, ir), 1e-3);
            } else {
                /* driving at it: the travel over the reading's age comes off */
                CHECK_NEAR(ffr_front_distance(&cfg, ir) - now, v * FFR_IR_AGE_MS * 0.001f, 1e-2);
            }
        }
    }
}

TEST(a_turn_backs_away_from_a_wall_inside_its_circle)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    float ir[FFR_IR_COUNT];
    float r, prev = 1.0f;
    int i;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    odo_moving(&o, 0.0f);
    r = corner_radius(&cfg);
    /* nothing ahead: turn in place */
    CHECK(ffr_turn_room_v(&cfg, &o, ir) == 0.0f);
    /* the wall ahead from 300 mm in to the part's nearest reading: no backing
     * outside the circle + margin, backing inside, never faster as the wall
     * recedes, within 30..120 mm/s */
    for (i = 0; i <= 100; ++i) {
        float front = 300.0f - 1.0f * (float)i;
        float v;
        ir[FFR_IR_CF] = front - cfg.ir_x_mm[FFR_IR_CF];
        v = ffr_turn_room_v(&cfg, &o, ir);
        if (front >= r + FFR_TURN_MARGIN_MM) {
            CHECK(v == 0.0f);
        } else {
            CHECK(v <= -30.0f && v >= -120.0f);
            CHECK(v <= prev);
        }
        prev = v;
    }
    /* the default route's stops at a wall ahead (front_stop_mm) leave room */
    ir[FFR_IR_CF] = cfg.front_stop_mm - cfg.ir_x_mm[FFR_IR_CF];
    CHECK(ffr_turn_room_v(&cfg, &o, ir) == 0.0f);
}

TEST(a_turn_near_a_wall_waits_for_the_body_to_slow)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    float ir[FFR_IR_COUNT];
    float r;
    int i, k;
    ffr_config_default(&cfg);
    rig_no_walls(&cfg, ir);
    r = corner_radius(&cfg);
    for (k = 0; k <= 16; ++k) {
        float v = 20.0f * (float)k; /* standing to cruise speed */
        float prev = 2.0f;
        odo_moving(&o, v);
        /* no wall ahead: the turn starts at once at any speed */
        ir[FFR_IR_CF] = FFR_IR_NONE(&cfg);
        CHECK(ffr_turn_onset(&cfg, &o, ir) == 1.0f);
        for (i = 0; i <= 40; ++i) {
            float front = 150.0f + 10.0f * (float)i; /* 150..550 mm from the origin */
            float f;
            ir[FFR_IR_CF] = front - cfg.ir_x_mm[FFR_IR_CF];
            f = ffr_turn_onset(&cfg, &o, ir);
            CHECK(f >= 0.0f && f <= 1.0f);
            if (ffr_front_now(&cfg, &o, ir) - v * FFR_TURN_ROLL_S > r + 0.5f * FFR_TURN_MARGIN_MM) {
                CHECK(f == 1.0f); /* rolling on would still leave room: at once */
            } else if (v <= FFR_TURN_ROLL_MM_S) {
                CHECK(f == 1.0f); /* slow enough: at once */
            } else if (v >= FFR_TURN_ROLL_MM_S + 100.0f) {
                CHECK(f == 0.0f); /* still rolling at the wall: held */
            }
            (void)prev;
        }
    }
    /* held back more the faster it rolls (the wall 180 mm ahead of the origin) */
    ir[FFR_IR_CF] = 180.0f - cfg.ir_x_mm[FFR_IR_CF];
    {
        float prev = 2.0f;
        for (k = 0; k <= 32; ++k) {
            float f;
            odo_moving(&o, 10.0f * (float)k);
            f = ffr_turn_onset(&cfg, &o, ir);
            CHECK(f <= prev);
            prev = f;
        }
    }
}

TEST(a_turn_step_near_a_wall_does_not_drive_into_it)
{
    /* the whole firmware: a TURN step right after stopping at cruise speed
     * with the wall ahead inside the turn's circle. The rig's drive moves
     * the wheels by their PWM; the commanded forward speed is never forward
     * and the wheels' mean travel over the turn is backward. */
    ffr_config_t cfg;
    rig_t r;
    int i;
    float mean0, mean1;
    ffr_config_default(&cfg);
    cfg.home_wall_side = FFR_HOME_AS_PLACED;
    cfg.route_len = 0;
    cfg.route[0].op = FFR_OP_TURN;
    cfg.route[0].side = FFR_SIDE_NONE;
    cfg.route[0].param = -90;
    cfg.route[1].op = FFR_OP_END;
    cfg.route_len = 2;
    rig_init(&r, &cfg);
    r.in.ir_mv[FFR_IR_CF] = rig_mv_for_mm(&cfg, 180.0f - cfg.ir_x_mm[FFR_IR_CF]);
    r.in.start = 1;
    rig_tick(&r);
    mean0 = 0.5f * (r.enc_f[0] + r.enc_f[1]);
    for (i = 0; i < 200 && r.out.state == FFR_ST_TURN; ++i) {
        rig_tick(&r);
        CHECK(r.st.cmd_v_mm_s <= 0.0f);
    }
    mean1 = 0.5f * (r.enc_f[0] + r.enc_f[1]);
    CHECK(mean1 < mean0);
    CHECK(r.out.state != FFR_ST_TURN); /* and the turn still ends */
}


SUITE(turn_room,
      TEST_REF(front_distance_is_projected_over_the_reading_age),
      TEST_REF(a_turn_backs_away_from_a_wall_inside_its_circle),
      TEST_REF(a_turn_near_a_wall_waits_for_the_body_to_slow),
      TEST_REF(a_turn_step_near_a_wall_does_not_drive_into_it));
