/*
 * Default configuration: the default robot (sim_plant/data/robot_default.toml)
 * and the default route through the 2004 arena. The harness overwrites the
 * geometry from the robot file it simulates; everything else is a tuning
 * knob documented in ffr.h.
 */
#include "ffr_internal.h"

static void step(ffr_config_t *c, uint8_t op, uint8_t side, uint8_t event, uint8_t arg, int16_t param)
{
    ffr_step_t *s;
    if (c->route_len >= FFR_ROUTE_MAX) {
        return;
    }
    s = &c->route[c->route_len];
    s->op = op;
    s->side = side;
    s->event = event;
    s->arg = arg;
    s->param = param;
    s->reserved = 0;
    c->route_len = (uint8_t)(c->route_len + 1u);
}

#define FOLLOW(side, ev) step(c, FFR_OP_FOLLOW, FFR_SIDE_##side, FFR_EV_##ev, 0, 0)
#define TURN(deg) step(c, FFR_OP_TURN, FFR_SIDE_NONE, 0, 0, (int16_t)(deg))
#define TURN_CASE(prefer) step(c, FFR_OP_TURN, FFR_SIDE_##prefer, 0, 0, 0)
/* follow a wall until the n-th opening (from 1) on open_side, half a hallway before its far edge */
#define FOLLOW_GAP(side, open_side, n) \
    step(c, FFR_OP_FOLLOW, FFR_SIDE_##side, FFR_EV_GAP_##open_side, (uint8_t)(n), 0)
#define ROOM(n) step(c, FFR_OP_ROOM, FFR_SIDE_NONE, 0, (uint8_t)(n), 0)
#define HOME(side) step(c, FFR_OP_HOME, FFR_SIDE_##side, 0, 0, 0)
#define END() step(c, FFR_OP_END, FFR_SIDE_NONE, 0, 0, 0)

/*
 * The default route, from the home circle facing up the east hallway.
 * Rooms are visited 1 (MID), 2 (TL), 3 (BL), 4 (BR). Doors are found by
 * their wall ending ("FOLLOW ... OPEN"), so a door moved along its wall is
 * still found. The four legs across junctions end on the opening they
 * drive to, counted on one side (FOLLOW_GAP), not on a distance of the map
 * (docs/firmware.md, "The four junction legs").
 */
static void default_route(ffr_config_t *c)
{
    c->route_len = 0;
    FOLLOW(RIGHT, FRONT);   /*  0 up the east hallway to the north wall        */
    TURN_CASE(LEFT);        /*  1 corner: left                                 */
    FOLLOW(RIGHT, OPEN_L);  /*  2 west along the north wall to room 1's door   */
    TURN(90);               /*  3                                              */
    ROOM(1);                /*  4                                              */
    TURN(90);               /*  5 out of room 1 facing north: west             */
    FOLLOW(RIGHT, FRONT);   /*  6 to the corridor's north end                  */
    TURN_CASE(LEFT);        /*  7 corner: left, down the corridor              */
    FOLLOW(RIGHT, OPEN_R);  /*  8 until the west hallway opens on the right    */
    TURN(-90);              /*  9                                              */
    FOLLOW(LEFT, OPEN_R);   /* 10 west until room 2's door opens on the right  */
    TURN(-90);              /* 11                                              */
    ROOM(2);                /* 12                                              */
    TURN(90);               /* 13 out of room 2 facing south: east             */
    FOLLOW(RIGHT, OPEN_R);  /* 14 until the corridor opens on the right        */
    TURN(-90);              /* 15 south                                        */
    FOLLOW(RIGHT, OPEN_R);  /* 16 until room 3's door opens on the right       */
    TURN(-90);              /* 17                                              */
    ROOM(3);                /* 18                                              */
    TURN(90);               /* 19 out of room 3 facing east: north             */
    FOLLOW_GAP(LEFT, R, 1); /* 20 up the corridor to room 4's door           */
    TURN(-90);              /* 21                                              */
    ROOM(4);                /* 22                                              */
    END();                  /* 23 no flame anywhere                            */
    /* home from room 1 (leaving it northward) */
    c->return_start[0] = c->route_len;
    TURN(-90);              /* 24 east along the north wall                    */
    FOLLOW(LEFT, FRONT);    /* 25                                              */
    TURN_CASE(RIGHT);       /* 26 corner: right, down the east hallway         */
    HOME(LEFT);             /* 27                                              */
    /* home from room 2 (leaving it southward) */
    c->return_start[1] = c->route_len;
    TURN(90);               /* 28 east                                         */
    FOLLOW(RIGHT, OPEN_R);  /* 29 until the corridor opens on the right        */
    TURN(-90);              /* 30 south                                        */
    FOLLOW_GAP(RIGHT, L, 1); /* 31 to the middle hallway                    */
    TURN(90);               /* 32 east                                         */
    HOME(RIGHT);            /* 33                                              */
    /* home from room 3 (leaving it eastward) */
    c->return_start[2] = c->route_len;
    TURN(90);               /* 34 north                                        */
    FOLLOW_GAP(LEFT, R, 2); /* 35 up the corridor to the middle hallway
                             *    (room 4's door is the first opening)         */
    TURN(-90);              /* 36 east                                         */
    HOME(RIGHT);            /* 37                                              */
    /* home from room 4 (leaving it westward) */
    c->return_start[3] = c->route_len;
    TURN(-90);              /* 38 north                                        */
    FOLLOW_GAP(LEFT, R, 1); /* 39 up the corridor to the middle hallway      */
    TURN(-90);              /* 40 east                                         */
    HOME(RIGHT);            /* 41                                              */
}

void ffr_config_default(ffr_config_t *c)
{
    static const float ir_x[FFR_IR_COUNT] = {100.0f, 80.0f, 80.0f, -80.0f, -80.0f};
    static const float ir_y[FFR_IR_COUNT] = {0.0f, 70.0f, -70.0f, 70.0f, -70.0f};
    static const float ir_a[FFR_IR_COUNT] = {0.0f, 45.0f, -45.0f, 135.0f, -135.0f};
    int i;
    uint8_t *raw = (uint8_t *)c;
    /* zero everything first, padding included: configs compare and hash byte-wise */
    for (i = 0; i < (int)sizeof(*c); ++i) {
        raw[i] = 0u;
    }
    c->wheel_radius_mm = 28.0f;
    c->track_width_mm = 170.0f;
    c->encoder_ticks_per_rev = 360.0f;
    c->body_front_mm = 120.0f;
    c->body_half_width_mm = 100.0f;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        c->ir_x_mm[i] = ir_x[i];
        c->ir_y_mm[i] = ir_y[i];
        c->ir_angle_deg[i] = ir_a[i];
    }
    c->line_sensor_x_mm = 110.0f;

    /* datasheet fit V = 33.2 V cm / (d + 4 cm) + 15 mV, in mV and mm */
    c->ir_k_mv_mm = 332000.0f;
    c->ir_offset_mv = 15.0f;
    c->ir_d0_mm = 40.0f;
    c->ir_min_mm = 100.0f;
    c->ir_max_mm = 800.0f;
    c->ir_min_mv = 0.0f;

    /* from the motor model: 9 V, NXT motor, 28 mm wheel, track friction */
    c->ff_gain_permille_per_mm_s = 2.04f;
    c->ff_offset_permille = 98.0f;
    c->speed_kp = 0.5f;
    c->speed_ki = 4.0f;
    c->accel_mm_s2 = 1500.0f;
    c->pwm_limit = 1000;

    c->cruise_speed_mm_s = 320.0f;
    c->room_speed_mm_s = 220.0f;
    c->approach_speed_mm_s = 180.0f;
    c->turn_rate_deg_s = 200.0f;
    c->scan_rate_deg_s = 150.0f;

    c->wall_target_mm = 230.0f;
    c->wall_kp_deg_per_mm = 0.3f;
    c->wall_max_deg = 20.0f;
    c->heading_kp = 4.0f;
    c->wall_align_gain = 0.05f;
    c->front_stop_mm = 230.0f;
    c->front_slow_mm = 450.0f;
    c->open_mm = 400.0f;
    c->open_confirm_mm = 20.0f;
    c->wall_seen_mm = 60.0f;
    c->hallway_half_mm = 230.0f;
    c->turn_tol_deg = 1.0f;

    c->line_holdoff_mm = 60.0f;
    c->room_line_max_mm = 450.0f;
    c->room_entry_mm = 330.0f;
    c->room_exit_mm = 340.0f;
    c->home_advance_mm = 240.0f;

    c->flame_detect = 170.0f; /* counts, both sensors: dark is ~2 x 40 */
    c->flame_out = 125.0f;
    c->flame_steer_deg = 30.0f;
    c->approach_stop_mm = 200.0f;
    c->guard_side_mm = 70.0f;
    c->guard_stop_mm = 35.0f;
    c->fan_timeout_ms = 8000u;
    c->flame_out_confirm_ms = 300u;
    c->verify_ms = 500u;
    c->fan_attempts = 3u;
    c->scan_dir = 0u;
    /* the 2004 arena's home: open up the east hallway, its outer wall on the right */
    c->home_wall_side = FFR_HOME_WALL_RIGHT;

    default_route(c);
}
