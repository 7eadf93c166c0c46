/*
 * The route program: a short list of steps in the configuration that takes
 * the robot from home through the rooms by what its sensors see ("follow the
 * right wall until the left one ends, turn left, search the room"), never by
 * stored arena coordinates. Each step ends on a sensed event or an odometry
 * distance measured from one (FORWARD, a distance of the map: the default
 * program has one left, docs/firmware.md "Route program").
 */
#include "ffr_internal.h"

enum { PH_DRIVE = 0, PH_WRAP = 1 };
/* HOME: a hallway read on both sides no wider than this times two
 * wall_target_mm (the contest hallway, 46 cm: up to 62 cm; wider is a
 * junction or a room's door beside), and the share of each tick's middle
 * taken into the running one (chosen: the rangers' noise at 20-30 cm is
 * ~1 cm a reading) */
#define HOME_HALL_MAX 1.35f
#define HOME_MIDDLE_GAIN 0.1f

static const ffr_step_t *cur(const ffr_state_t *st) { return &st->cfg.route[st->route.pc]; }

int ffr_route_open_side(const ffr_state_t *st)
{
    const ffr_step_t *s;
    if (st->cfg.start_area == FFR_START_HALLWAY || st->state != FFR_ST_FOLLOW || st->route.pc >= st->cfg.route_len) {
        return -1;
    }
    s = cur(st);
    if (s->op != FFR_OP_FOLLOW) {
        return -1;
    }
    if (s->event == FFR_EV_OPEN_L) {
        return FFR_SIDE_LEFT;
    }
    return s->event == FFR_EV_OPEN_R ? FFR_SIDE_RIGHT : -1;
}

/* The furniture mode's pieces may hide the candle from a room's scan points;
 * the last room's is looked for harder, at no cost to the rooms before it
 * (room.c, ASIDE). */
int ffr_route_last_room(const ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    uint8_t pc;
    if (cfg->start_area == FFR_START_HALLWAY || st->returning || st->route.pc >= cfg->route_len
        || cur(st)->op != FFR_OP_ROOM) {
        return 0;
    }
    for (pc = (uint8_t)(st->route.pc + 1u); pc < cfg->route_len && pc < FFR_ROUTE_MAX; ++pc) {
        if (cfg->route[pc].op == FFR_OP_ROOM) {
            return 0;
        }
        if (cfg->route[pc].op == FFR_OP_END) {
            return 1;
        }
    }
    return 0;
}

static void begin_current(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    const ffr_step_t *s;
    if (st->route.pc >= cfg->route_len || st->route.pc >= FFR_ROUTE_MAX) {
        ffr_fail(st, st->returning ? FFR_FAIL_BAD_ROUTE : FFR_FAIL_NO_FLAME);
        return;
    }
    s = cur(st);
    st->route.phase = PH_DRIVE;
    st->route.start_mm = st->odo.dist_mm;
    st->route.follow_mm = 0.0f;
    ffr_wall_cal_restart(&st->wall_cal);
    ffr_wall_dir_reset(&st->wall_cal);
    if (s->op == FFR_OP_TURN && s->param == 0) {
        /* decided by the wall case, from what the last leg saw: before the reset */
        st->route.case_turn_deg = ffr_wall_case_turn(ffr_wall_case_sensed(cfg, st->ir_mm, &st->open), s->side);
    }
    ffr_openings_reset(&st->open);
    switch (s->op) {
    case FFR_OP_FOLLOW:
        st->state = FFR_ST_FOLLOW;
        break;
    case FFR_OP_TURN: {
        int16_t deg = s->param != 0 ? s->param : st->route.case_turn_deg;
        st->route.target_rad = st->route.heading_ref_rad + (float)deg * FFR_DEG;
        st->state = FFR_ST_TURN;
        break;
    }
    case FFR_OP_FORWARD:
        st->route.goal_mm = st->odo.dist_mm + (float)s->param;
        st->state = FFR_ST_FORWARD;
        break;
    case FFR_OP_ROOM:
        if (s->arg < 1 || s->arg > FFR_ROOMS_MAX) {
            ffr_fail(st, FFR_FAIL_BAD_ROUTE);
            return;
        }
        ffr_room_begin(st, s->arg, st->route.heading_ref_rad);
        break;
    case FFR_OP_HOME:
        st->state = FFR_ST_HOMING;
        break;
    case FFR_OP_END:
    default:
        ffr_fail(st, st->returning ? FFR_FAIL_BAD_ROUTE : FFR_FAIL_NO_FLAME);
        break;
    }
}

void ffr_route_begin(ffr_state_t *st, uint8_t pc)
{
    st->route.pc = pc;
    begin_current(st);
}

static void next(ffr_state_t *st)
{
    st->route.pc = (uint8_t)(st->route.pc + 1u);
    begin_current(st);
}

/* HOME follows its wall at the hallway's middle as read, not at
 * wall_target_mm: the home circle lies within the hallway, so no point of
 * it is farther from the middle line than half the hallway less its
 * radius, while a robot at wall_target_mm from one wall of a hallway wider
 * than twice that passes farther from a circle near the other wall. On the
 * 2004 map's way home from room 1 the west wall ends at the middle
 * hallway's mouth and the robot follows the east one: +-5 cm arena jitter
 * put the circle's centre up to 16 cm off that path, beyond its 15 cm
 * radius, and the robot stopped outside it (start seeds 73, 87, 135 of
 * `--arena-jitter 0.05 --seeds 50:150`; docs/robustness.md, "Home in the
 * hallway's middle"). The middle is read while each side's two rangers see
 * a straight wall (the pair's line: not a junction's corner or a far wall
 * across), and kept once one side opens. */
static void home_middle(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_wall_t l = ffr_wall_estimate(cfg, &st->ir_geom, st->ir_mm, FFR_SIDE_LEFT);
    ffr_wall_t r = ffr_wall_estimate(cfg, &st->ir_geom, st->ir_mm, FFR_SIDE_RIGHT);
    float half = 0.5f * (l.dist_mm + r.dist_mm);
    if (!l.angle_valid || !r.angle_valid || half > HOME_HALL_MAX * cfg->wall_target_mm) {
        return;
    }
    st->route.follow_mm =
        st->route.follow_mm > 0.0f ? st->route.follow_mm + HOME_MIDDLE_GAIN * (half - st->route.follow_mm) : half;
}

/* The last stretch of a step (past an opening's wall end, past the home
 * line): straight on the held heading to the goal. 1 when there, or when a
 * wall ahead ends it first. */
static int drive_to_goal(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    float left = st->route.goal_mm - st->odo.dist_mm;
    if (left <= 0.0f || ffr_front_now(cfg, &st->odo, st->ir_mm) < cfg->front_stop_mm) {
        ffr_stop(st);
        return 1;
    }
    ffr_drive_heading(st, st->route.heading_ref_rad, ffr_stopping_speed(left, cfg->cruise_speed_mm_s));
    ffr_corridor_guard(st);
    return 0;
}

/* Out of a room's door the robot faces the corridor's far wall, square to
 * its exit heading (contest walls meet at right angles); the front corner
 * rangers' two hits on that wall give its angle to the body. A scan and
 * the turns out of a room on slipping tracks leave odometry's heading
 * 10-20 degrees off, and the short legs after (to the next junction) have
 * no time for the side walls' fixes: a robot turned into a room's corner
 * or miscounted the openings (docs/firmware.md, "Squared on the wall ahead
 * out of a room"). Two GP2D12 parts at the datasheet's extremes put the two
 * hits' line up to ~9 degrees off: an angle beyond SQUARE_MIN_DEG =
 * SQUARE_KEEP_DEG + 9 is taken, less SQUARE_KEEP_DEG, which never leaves
 * the heading further off than it was for a bias within 9 degrees
 * (chosen). */
#ifndef SQUARE_MIN_DEG
#define SQUARE_MIN_DEG 13.0f
#endif
#ifndef SQUARE_KEEP_DEG
#define SQUARE_KEEP_DEG 4.0f
#endif
/* the three hits on one straight wall across: the centre ranger's within
 * this (mm, ahead) of the corner rangers' line (chosen: two parts' errors at
 * ~20 cm) */
#define SQUARE_SAME_WALL_MM 40.0f
/* the readings used: within this (chosen: as the scan's SQ_RANGE_MM,
 * turn_calibration.c; a GP2D12 part's error grows with the range) */
#define SQUARE_RANGE_MM 600.0f
/* a wall further off than this is not the corridor's far wall (a corner) */
#define SQUARE_MAX_DEG 30.0f

/* a heading error less the part kept (keep_rad toward zero): the fixes
 * below take all of a large error but a margin for the measurement's own */
static float trimmed(float off, float keep_rad)
{
    return off > 0.0f ? off - keep_rad : off + keep_rad;
}

/* The wall ahead's angle less odometry's heading off the held one: what
 * odometry's heading is short of the truth (*off, rad); 0 if the three
 * front hits are not one straight wall across. */
static int wall_ahead_off(const ffr_state_t *st, float *off)
{
    const ffr_config_t *cfg = &st->cfg;
    const ffr_ir_geom_t *g = &st->ir_geom;
    float xl, yl, xr, yr, xc, wall, held;
    if (!ffr_ir_valid(cfg, st->ir_mm[FFR_IR_LF]) || !ffr_ir_valid(cfg, st->ir_mm[FFR_IR_RF])
        || !ffr_ir_valid(cfg, st->ir_mm[FFR_IR_CF])) {
        return 0;
    }
    xl = g->hit_x_mm[FFR_IR_LF];
    yl = g->hit_y_mm[FFR_IR_LF];
    xr = g->hit_x_mm[FFR_IR_RF];
    yr = g->hit_y_mm[FFR_IR_RF];
    xc = g->hit_x_mm[FFR_IR_CF];
    /* each reading within SQUARE_RANGE_MM (a far one may be through a door
     * beside the wall ahead, and is the least sure) and the centre ranger's
     * hit on the corner rangers' line */
    if (st->ir_mm[FFR_IR_LF] > SQUARE_RANGE_MM || st->ir_mm[FFR_IR_RF] > SQUARE_RANGE_MM
        || st->ir_mm[FFR_IR_CF] > SQUARE_RANGE_MM || yl <= 0.0f || yr >= 0.0f
        || ffr_absf(xl + (0.0f - yl) * (xr - xl) / (yr - yl) - xc) > SQUARE_SAME_WALL_MM) {
        return 0;
    }
    /* the robot turned by `wall` off the wall's normal (left positive) */
    wall = ffr_atan2f(xl - xr, yl - yr);
    if (ffr_absf(wall) > SQUARE_MAX_DEG * FFR_DEG) {
        return 0;
    }
    held = ffr_wrap_pi(st->odo.heading_rad - st->route.heading_ref_rad);
    *off = wall - held;
    return 1;
}

/* The wall alongside the way out of a room. The 2004 arena's doors (and a
 * contest room's in general: a door at a room's corner) have a wall running
 * on along the way out, and at a corridor's end (room 3's door) the wall
 * ahead is too short for the three front rangers: one of them sees the wall
 * beside or looks through the next door. While the robot drives out on the
 * exit heading, each side ranger's hits over 12 cm of travel
 * (wall_direction.c) give that wall's direction in odometry's frame,
 * whatever the part's offset; off square with the held heading it is
 * odometry's error. Taken at the room's end when the wall ahead could not
 * square it: beyond EXIT_MIN_DEG, all of it but EXIT_KEEP_DEG (chosen: a
 * window's direction is good to ~2 degrees, a jittered arena's wall a few
 * more); beyond EXIT_MAX_DEG (drive.c's SNAP_MAX_DEG) it is not such a wall. */
#ifndef EXIT_MIN_DEG
#define EXIT_MIN_DEG 8.0f
#endif
#ifndef EXIT_KEEP_DEG
#define EXIT_KEEP_DEG 3.0f
#endif
#define EXIT_MAX_DEG 25.0f

void ffr_exit_wall_watch(ffr_state_t *st)
{
    float dir;
    if (ffr_wall_dir_update(&st->wall_cal, &st->cfg, &st->odo, &st->ir_geom, st->ir_mm, &dir)) {
        /* the held heading is the exit heading all the way out */
        st->route.exit_wall_rad = ffr_off_square(ffr_wrap_pi(dir - st->route.heading_ref_rad));
    }
}

/*
 * Out of a room: odometry's heading squared on the wall ahead when that
 * reads it far off (beyond SQUARE_MIN_DEG); else on the wall alongside the
 * way out, unless the wall ahead, read within its parts' bias, says the
 * error runs the other way. A robot whose odometry was 15 degrees short
 * leaving room 2 read the wall ahead 10.5 degrees off (two parts' bias
 * took 4) and the wall beside 11.4: neither alone was taken before, since
 * the wall beside was only asked when the wall ahead could not be read
 * (docs/firmware.md, "Squared on the wall alongside the way out").
 */
void ffr_square_out_of_room(ffr_state_t *st)
{
    float off = 0.0f, e = st->route.exit_wall_rad;
    int ahead = wall_ahead_off(st, &off);
    st->route.exit_wall_rad = FFR_EXIT_WALL_NONE;
    if (ahead && ffr_absf(off) > SQUARE_MIN_DEG * FFR_DEG) {
        st->odo.heading_rad += trimmed(off, SQUARE_KEEP_DEG * FFR_DEG);
        return;
    }
    if (e == FFR_EXIT_WALL_NONE || ffr_absf(e) > EXIT_MAX_DEG * FFR_DEG || ffr_absf(e) < EXIT_MIN_DEG * FFR_DEG) {
        return;
    }
    /* the wall's direction is e off the held heading in odometry's frame:
     * odometry's heading is e too far the same way, i.e. short by -e */
    if (ahead && off * e >= 0.0f) {
        return; /* the wall ahead reads it short the other way, or not at all */
    }
    st->odo.heading_rad -= trimmed(e, EXIT_KEEP_DEG * FFR_DEG);
}

static int event_fired(ffr_state_t *st, const ffr_step_t *s)
{
    const ffr_config_t *cfg = &st->cfg;
    switch (s->event) {
    case FFR_EV_FRONT:
        return ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm;
    case FFR_EV_OPEN_L:
        return ffr_opening(&st->open, FFR_SIDE_LEFT);
    case FFR_EV_OPEN_R:
        return ffr_opening(&st->open, FFR_SIDE_RIGHT);
    case FFR_EV_LINE:
        return st->lines.edge;
    case FFR_EV_GAP_L:
        return ffr_gap(&st->open, FFR_SIDE_LEFT, s->arg);
    case FFR_EV_GAP_R:
        return ffr_gap(&st->open, FFR_SIDE_RIGHT, s->arg);
    default:
        return 1;
    }
}

void ffr_route_step(ffr_state_t *st, const ffr_inputs_t *in)
{
    const ffr_config_t *cfg = &st->cfg;
    const ffr_step_t *s = cur(st);
    (void)in;
    switch (s->op) {
    case FFR_OP_FOLLOW:
        if (st->route.phase == PH_DRIVE) {
            if (event_fired(st, s)) {
                if (s->event == FFR_EV_OPEN_L || s->event == FFR_EV_OPEN_R) {
                    /* go on until the origin is in the middle of the opening */
                    int side = s->event == FFR_EV_OPEN_L ? FFR_SIDE_LEFT : FFR_SIDE_RIGHT;
                    st->route.goal_mm = st->open.open_at_mm[side] + cfg->hallway_half_mm;
                    st->route.phase = PH_WRAP;
                } else if (s->event == FFR_EV_GAP_L || s->event == FFR_EV_GAP_R) {
                    /* on to the opening's middle (the far edge is seen ~30 cm ahead;
                     * a robot already past the middle stops where it is) */
                    int side = s->event == FFR_EV_GAP_L ? FFR_SIDE_LEFT : FFR_SIDE_RIGHT;
                    st->route.goal_mm = ffr_gap_middle_mm(&st->open, cfg, side);
                    st->route.phase = PH_WRAP;
                } else {
                    ffr_stop(st);
                    next(st);
                    return;
                }
            } else {
                ffr_drive_corridor(st, s->side, cfg->cruise_speed_mm_s);
                return;
            }
        }
        if (s->event == FFR_EV_OPEN_L || s->event == FFR_EV_OPEN_R) {
            /* the opening's far edge seen before the robot got to its
             * assumed middle: a narrower opening, its middle between the two
             * edges (openings.c) */
            st->route.goal_mm = ffr_open_middle_mm(&st->open, cfg, s->event == FFR_EV_OPEN_L ? FFR_SIDE_LEFT
                                                                                            : FFR_SIDE_RIGHT);
        }
        if (s->event == FFR_EV_GAP_L || s->event == FFR_EV_GAP_R) {
            /* the far edge is refined as the robot nears it (openings.c) */
            st->route.goal_mm = ffr_gap_middle_mm(&st->open, cfg, s->event == FFR_EV_GAP_L ? FFR_SIDE_LEFT
                                                                                            : FFR_SIDE_RIGHT);
        }
        if (drive_to_goal(st)) {
            next(st);
        }
        return;
    case FFR_OP_TURN:
        ffr_turn_toward(st, st->route.target_rad);
        if (ffr_turn_done(cfg, &st->odo, st->route.target_rad)) {
            ffr_turn_finish(st, st->route.target_rad);
            next(st);
        }
        return;
    case FFR_OP_FORWARD: {
        float left = st->route.goal_mm - st->odo.dist_mm;
        if (left <= 0.0f || ffr_front_now(cfg, &st->odo, st->ir_mm) < cfg->front_stop_mm) {
            ffr_stop(st);
            next(st);
            return;
        }
        ffr_drive_corridor(st, s->side, ffr_stopping_speed(left, cfg->cruise_speed_mm_s));
        return;
    }
    case FFR_OP_ROOM:
        /* the room task (room.c) says when the route moves on */
        switch (ffr_room_step(st, in)) {
        case FFR_ROOM_FACING_OUT:
            /* the corridor heading reversed: later turns stay square to the walls */
            st->route.heading_ref_rad = st->room.exit_heading_rad;
            /* the walls alongside the way out, from here on */
            ffr_wall_dir_reset(&st->wall_cal);
            st->route.exit_wall_rad = FFR_EXIT_WALL_NONE;
            break;
        case FFR_ROOM_LEFT:
            ffr_square_out_of_room(st);
            st->rooms_searched = (uint8_t)(st->rooms_searched + 1u);
            if (st->flags & FFR_FLAG_EXTINGUISHED) {
                st->returning = 1;
                ffr_route_begin(st, cfg->return_start[s->arg - 1]);
            } else {
                next(st);
            }
            break;
        case FFR_ROOM_BUSY:
        default:
            break;
        }
        return;
    case FFR_OP_HOME:
        if (st->route.phase == PH_DRIVE) {
            if (st->lines.edge) {
                st->route.goal_mm = st->odo.dist_mm + cfg->home_advance_mm;
                st->route.phase = PH_WRAP;
            } else {
                home_middle(st);
                ffr_drive_corridor(st, s->side, cfg->cruise_speed_mm_s);
                return;
            }
        }
        if (drive_to_goal(st)) {
            st->state = FFR_ST_DONE;
            st->flags |= FFR_FLAG_DONE;
        }
        return;
    default:
        ffr_fail(st, FFR_FAIL_BAD_ROUTE);
        return;
    }
}
