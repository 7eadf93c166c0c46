/*
 * The explorer: the contest's arbitrary start mode (placed anywhere in a
 * hallway, any heading; cfg->start_area == FFR_START_HALLWAY). No map and no
 * start pose: the robot squares up to the walls where it stands
 * (home_orient.c, facing open with a wall close on the followed side), then
 * walks the hallways by one wall (the right one, or the left one when
 * home_wall_side says so):
 *
 *   FOLLOW the wall (steered by the far one where there is one); a wall
 *          ahead: turn by the wall case (away from it, or round if a dead
 *          end), then PROBE; the wall ends (or an opening that was open
 *          since the leg began is seen whole): WRAP on to the opening's
 *          middle, TURN into it, PROBE straight in.
 *   PROBE  a line within EX_PROBE_MM: a doorway: the room task (room.c)
 *          searches the room; out again, TURN the followed side's way (the
 *          walk goes on as before the door). No line: a hallway, FOLLOW on.
 *   a line crossed, a second one within FFR_HOME_CHORD_MM: the home circle
 *          (its two sides; a doorway's line is alone). With the flame out:
 *          HOME, on to the chord's middle and stop. Before: the walk has
 *          come round the loop it is on, and if it searched rooms on the
 *          way it changes walls (a room whose walls
 *          stand free of the outer wall, an island, is on the other wall's
 *          loop; home is in a hallway between both); every room searched
 *          from then on is searched harder (a candle hidden by furniture:
 *          room.c, search_harder).
 *   after the flame is out a doorway is not entered again: a line alone at
 *          a probe turns the robot round (BACK) out to the hallway.
 *
 * Every step ends on a sensed event or a distance from one, as the route
 * program's (route.c); the heading reference is route.heading_ref_rad, the
 * one drive.c keeps true by the walls.
 */
#include "ffr_internal.h"

enum { EX_FOLLOW = 0, EX_WRAP, EX_TURN, EX_PROBE, EX_ROOM, EX_HOME, EX_BACK, EX_DONE };

/* chosen: turned into an opening on the followed side from the hallway's
 * middle, a doorway's line lies in the wall's plane, about half a hallway
 * ahead of the origin (hallway_half_mm - line_sensor_x_mm: ~120 mm for the
 * default robot); one met within this much travel (the wrap's and the turn's
 * errors allowed for) makes the opening a door,
 * none a hallway (the walk follows on in it) */
#ifndef EX_PROBE_MM
#define EX_PROBE_MM 300.0f
#endif
#define EX_NO_EDGE (-1.0e9f)
/* The wrap after a wall's end goes half a contest hallway past it
 * (hallway_half_mm), the middle of a 46 cm opening. An arena's tolerance
 * makes openings as narrow as 41 cm (+-2.5 cm) or 36 cm (+-5 cm): there that
 * point lies past the middle, and with the wall's end put late the probe in
 * puts the body's far side on the far jamb (+-2.5 cm hallway start seed 371:
 * the end put ~100 mm late, the turn ~130 mm past the middle of a 414 mm
 * opening). The front corner ranger sees the far edge during the wrap
 * (openings.c, gap_end_mm), so the turn comes no later than the half width
 * and EX_FAR_CLEAR_MM short of it: the body's far side that far from the far
 * edge, short of the two edges' middle in gaps under 2 * (half width +
 * EX_FAR_CLEAR_MM), 400 mm for the default robot (chosen: on the +-2.5 cm
 * hallway row 40, 60 and 120 measured worse, 80 and 90 about the same). Only for a
 * gap wider than the body by EX_GAP_MIN_MM (chosen: narrower is hardly an
 * opening it fits; realistic robot 1 saw two faces 200 mm apart), and only
 * where that moves the turn by EX_CAP_MIN_MM or more (chosen: fewer moved
 * walks; without it the rows measured about the same). docs/robustness.md,
 * "The explorer's turn into a narrow opening". */
#ifndef EX_FAR_CLEAR_MM
#define EX_FAR_CLEAR_MM 100.0f
#endif
#define EX_GAP_MIN_MM 50.0f
#define EX_CAP_MIN_MM 20.0f

void ffr_explore_reset(ffr_explore_t *e)
{
    e->phase = EX_FOLLOW;
    e->side = FFR_SIDE_RIGHT;
    e->after = EX_FOLLOW;
    e->homes = 0;
    e->bent = 0;
    e->rooms_at_flip = 0;
    e->backing = 0;
    e->flips = 0;
    e->start_mm = 0.0f;
    e->goal_mm = 0.0f;
    e->edge_mm = EX_NO_EDGE;
    e->target_rad = 0.0f;
    e->home_mm = EX_NO_EDGE;
}

int ffr_explore_is_circle(float chord_mm, float line_sensor_x_mm, float *to_middle_mm)
{
    if (chord_mm < 0.0f || chord_mm > FFR_HOME_CHORD_MM) {
        return 0;
    }
    /* at the second edge the line sensor is on the circle's far side and the
     * origin line_sensor_x_mm behind it; the chord's middle is chord/2 behind */
    *to_middle_mm = line_sensor_x_mm - 0.5f * chord_mm;
    return 1;
}

static void phase(ffr_state_t *st, uint8_t p)
{
    static const uint8_t codes[EX_DONE + 1] = {FFR_ST_FOLLOW, FFR_ST_FOLLOW, FFR_ST_TURN,   FFR_ST_FORWARD,
                                               FFR_ST_ENTER,  FFR_ST_HOMING, FFR_ST_FORWARD, FFR_ST_DONE};
    ffr_explore_t *e = &st->explore;
    /* a probe that found a hallway goes on as the follow: what its rangers
     * saw of the walls beside it stays (a short wall's end is an opening),
     * and so does where the leg began (the probe is its first stretch: an
     * opening's far edge is counted from there, as its rangers saw it) */
    int on = p == EX_FOLLOW && e->phase == EX_PROBE;
    int keep = p == EX_ROOM || on;
    if (!on) {
        e->start_mm = st->odo.dist_mm;
    }
    e->phase = p;
    e->backing = 0;
    st->state = codes[p];
    if (!keep) {
        ffr_wall_cal_restart(&st->wall_cal);
        ffr_wall_dir_reset(&st->wall_cal);
        ffr_openings_reset(&st->open);
    }
}

/* degrees of a quarter turn toward the followed wall */
static int toward(const ffr_explore_t *e) { return e->side == FFR_SIDE_LEFT ? 90 : -90; }

/* The nearest multiple of 90 degrees: after the orientation odometry's
 * frame is square to the walls (home_orient.c, and drive.c keeps it so), and
 * every hallway runs along one of its axes; what the held heading has
 * wandered from it following a wall's end does not carry into the next leg. */
float ffr_explore_square(float rad)
{
    float q = rad / (0.5f * FFR_PI);
    int32_t k = (int32_t)(q >= 0.0f ? q + 0.5f : q - 0.5f);
    return (float)k * (0.5f * FFR_PI);
}

static void turn(ffr_state_t *st, int deg, uint8_t after)
{
    ffr_explore_t *e = &st->explore;
    e->target_rad = st->route.heading_ref_rad + (float)deg * FFR_DEG;
    if (st->cfg.home_wall_side != FFR_HOME_AS_PLACED) {
        e->target_rad = ffr_explore_square(e->target_rad);
    }
    e->after = after;
    if (e->edge_mm != EX_NO_EDGE) {
        e->bent = 1; /* a chord across a turn is no straight chord */
    }
    ffr_stop(st);
    phase(st, EX_TURN);
}

void ffr_explore_begin(ffr_state_t *st)
{
    ffr_explore_reset(&st->explore);
    st->explore.side = st->cfg.home_wall_side == FFR_HOME_WALL_LEFT ? FFR_SIDE_LEFT : FFR_SIDE_RIGHT;
    phase(st, EX_FOLLOW);
}

/* A line edge this tick (not in a room): 1 if it closes the home circle,
 * then handled (home, or the walk changes walls, or on as it was); else 0,
 * it is recorded as the first of a possible pair. */
static int line_edge(ffr_state_t *st)
{
    ffr_explore_t *e = &st->explore;
    float to_mid = 0.0f;
    int straight = !e->bent;
    if (st->odo.dist_mm - e->home_mm < FFR_HOME_CHORD_MM) {
        /* the circle just recognised, its line met again (a turn on it) */
        return 1;
    }
    if (e->edge_mm == EX_NO_EDGE || !ffr_explore_is_circle(st->odo.dist_mm - e->edge_mm, st->cfg.line_sensor_x_mm,
                                                            &to_mid)) {
        e->edge_mm = st->odo.dist_mm;
        e->bent = 0;
        return 0;
    }
    e->edge_mm = EX_NO_EDGE;
    e->bent = 0;
    e->home_mm = st->odo.dist_mm;
    if (e->homes < 255u) {
        e->homes = (uint8_t)(e->homes + 1u);
    }
    if (st->flags & FFR_FLAG_EXTINGUISHED) {
        e->goal_mm = st->odo.dist_mm + (straight && to_mid > 0.0f ? to_mid : 0.0f);
        phase(st, EX_HOME);
        return 1;
    }
    /* round a loop, rooms searched on it, no flame: the other wall's loop
     * next. What the rangers saw stays: the new side's wall may have ended
     * already (home at a junction), and that opening is the way on. */
    if (st->rooms_searched != e->rooms_at_flip) {
        e->rooms_at_flip = st->rooms_searched;
        if (e->flips < 255u) {
            e->flips = (uint8_t)(e->flips + 1u);
        }
        e->side = (uint8_t)(1u - e->side);
        if (e->phase != EX_TURN) {
            /* a wrap or a probe ends: the follow goes on by the new wall
             * (a turn in the circle goes on to its target first) */
            e->phase = EX_FOLLOW;
            e->backing = 0;
            st->state = FFR_ST_FOLLOW;
        }
    }
    return 1;
}

int ffr_explore_searched_round(const ffr_state_t *st)
{
    return st->explore.flips >= 1u && !(st->flags & FFR_FLAG_EXTINGUISHED);
}

#ifndef EX_YAW_MAX_DEG
#define EX_YAW_MAX_DEG 10.0f
#endif
/* The hallway runs along the held heading (square, kept true by the walls):
 * the wall following swings the body no further off it than
 * EX_YAW_MAX_DEG. A wall line that asks for more is two faces seen across an
 * opening on the steering side (a door's far jamb and the hallway wall
 * behind it), and turning after it yaws the followed side's rangers off
 * their wall (an opening seen early). */
static void hold_hallway(ffr_state_t *st)
{
    float off = ffr_wrap_pi(st->odo.heading_rad - st->route.heading_ref_rad);
    if (ffr_absf(off) > EX_YAW_MAX_DEG * FFR_DEG && off * st->cmd_w_rad_s > 0.0f && ffr_leave_guard(st) == 0.0f) {
        st->cmd_w_rad_s = ffr_heading_hold_yaw(&st->cfg, st->odo.heading_rad, st->route.heading_ref_rad);
    }
}

/* odometry's position along the held heading, mm */
static float along(const ffr_state_t *st)
{
    float h = st->route.heading_ref_rad;
    return st->odo.x_mm * ffr_cosf(h) + st->odo.y_mm * ffr_sinf(h);
}

/* the wrap's goal (odometry's distance) no later than short of the
 * opening's far edge, once that is seen (EX_FAR_CLEAR_MM above) */
static void wrap_short_of_far_edge(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_explore_t *e = &st->explore;
    const ffr_openings_t *op = &st->open;
    float cap;
    if (e->backing || !ffr_opening(op, e->side) || !ffr_gap(op, e->side, 0) ||
        op->gap_end_mm[e->side] - op->open_at_mm[e->side] < 2.0f * cfg->body_half_width_mm + EX_GAP_MIN_MM) {
        return;
    }
    cap = op->gap_end_mm[e->side] - cfg->body_half_width_mm - EX_FAR_CLEAR_MM;
    if (cap < e->goal_mm - EX_CAP_MIN_MM) {
        e->goal_mm = cap;
    }
}

static void follow(ffr_state_t *st)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_explore_t *e = &st->explore;
    if (st->lines.edge && line_edge(st)) {
        return;
    }
    if (e->phase == EX_FOLLOW) {
        if (e->edge_mm != EX_NO_EDGE && (st->flags & FFR_FLAG_EXTINGUISHED)
            && st->odo.dist_mm - e->edge_mm > FFR_HOME_CHORD_MM) {
            /* a line alone crossed on the way home: a doorway ahead, searched
             * already (or never to be); round, back the way the walk came */
            e->edge_mm = EX_NO_EDGE;
            turn(st, 180, EX_FOLLOW);
            return;
        }
        if (ffr_opening(&st->open, e->side)
            && st->open.open_at_mm[e->side] + cfg->hallway_half_mm < e->start_mm) {
            /* a wall end seen by the rear ranger alone, its opening's middle
             * behind where the leg began: the door the robot has just come
             * out of (it stood in it); not taken, the side watched afresh */
            ffr_opening_forget(&st->open, e->side);
            ffr_drive_corridor(st, (uint8_t)(1u - e->side), cfg->cruise_speed_mm_s);
            hold_hallway(st);
            return;
        }
        if (ffr_opening(&st->open, e->side)) {
            /* on until the origin is in the opening's middle */
            e->goal_mm = st->open.open_at_mm[e->side] + cfg->hallway_half_mm;
            e->phase = EX_WRAP;
        } else if (ffr_gap(&st->open, e->side, 0)
                   && st->open.gap_end_mm[e->side] - e->start_mm > 2.0f * cfg->hallway_half_mm) {
            /* an opening open since the leg began (beside the robot when it
             * turned), seen whole: back to half a hallway before its far edge
             * as first seen (not refined as the route's GAP is: a wall's end
             * a few cm thick between two openings, a door's jamb and a
             * hallway beyond, would carry the goal past the door).
             * Not one whose far edge is within a hallway's width of the
             * leg's start: that is the door the robot has just come out of */
            e->goal_mm = ffr_gap_middle_mm(&st->open, cfg, e->side);
            e->phase = EX_WRAP;
            if (e->goal_mm < st->odo.dist_mm) {
                /* its far edge is first seen about as far ahead as half a
                 * hallway: the middle may be passed already; back to it,
                 * measured along the held heading (the path length counts
                 * the stop's coasting on as well as the way back) */
                e->backing = 1;
                e->goal_mm = along(st) - (st->odo.dist_mm - e->goal_mm);
            }
        } else if (ffr_front_distance(cfg, st->ir_mm) < cfg->front_stop_mm) {
            int deg = ffr_wall_case_turn(ffr_wall_case_sensed(cfg, st->ir_mm, &st->open), e->side);
            if (deg == 0) {
                deg = -toward(e); /* away from the followed wall */
            }
            /* a door may stand straight ahead after any corner (a hallway's
             * end beside a door): probed as one beside */
            turn(st, deg, EX_PROBE);
            return;
        } else {
            /* steered by the far wall where there is one: the followed wall's
             * end (a door's jamb) would draw the robot into the opening */
            ffr_drive_corridor(st, (uint8_t)(1u - e->side), cfg->cruise_speed_mm_s);
            hold_hallway(st);
            return;
        }
    }
    /* EX_WRAP: straight on the held heading to the opening's middle */
    {
        float left;
        wrap_short_of_far_edge(st);
        left = e->goal_mm - st->odo.dist_mm;
        if (e->backing) {
            left = along(st) - e->goal_mm;
            if (left <= 0.0f) {
                turn(st, toward(e), EX_PROBE);
                return;
            }
            ffr_drive_heading(st, st->route.heading_ref_rad, -ffr_stopping_speed(left, cfg->room_speed_mm_s));
            return;
        }
        if (left <= 0.0f || ffr_front_now(cfg, &st->odo, st->ir_mm) < cfg->front_stop_mm) {
            turn(st, toward(e), EX_PROBE);
            return;
        }
        ffr_drive_held(st, ffr_stopping_speed(left, cfg->cruise_speed_mm_s));
    }
}

static void probe(ffr_state_t *st, const ffr_inputs_t *in)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_explore_t *e = &st->explore;
    float moved = st->odo.dist_mm - e->start_mm;
    if (st->lines.edge) {
        if (line_edge(st)) {
            return;
        }
        if (!(st->flags & FFR_FLAG_EXTINGUISHED)) {
            /* a doorway: the room task, from this tick's line on */
            uint8_t room = (uint8_t)(st->rooms_searched % FFR_ROOMS_MAX + 1u);
            e->edge_mm = EX_NO_EDGE;
            phase(st, EX_ROOM);
            ffr_room_begin(st, room, st->route.heading_ref_rad);
            (void)ffr_room_step(st, in);
            return;
        }
    }
    if (e->edge_mm != EX_NO_EDGE && (st->flags & FFR_FLAG_EXTINGUISHED)
        && st->odo.dist_mm - e->edge_mm > FFR_HOME_CHORD_MM) {
        /* a line alone: a doorway, searched already; round and back out */
        e->goal_mm = moved;
        e->edge_mm = EX_NO_EDGE;
        turn(st, 180, EX_BACK);
        return;
    }
    if ((moved > EX_PROBE_MM && (e->edge_mm == EX_NO_EDGE || !(st->flags & FFR_FLAG_EXTINGUISHED)))
        || ffr_front_now(cfg, &st->odo, st->ir_mm) < cfg->front_stop_mm) {
        phase(st, EX_FOLLOW); /* a hallway (or a wall ahead): the walk goes on */
        return;
    }
    ffr_drive_held(st, cfg->room_speed_mm_s);
}

/* chosen: a wall this near both of one side's corner rangers (45 degrees
 * off the heading, 70 mm to the side of the middle) stands within 0.07 +
 * 0.155 x 0.707 = 0.18 m of the axle, the front corner's turning circle
 * (156 mm for the default body) and a margin; a hallway's walls seen by a
 * robot in its middle read ~210 mm */
#ifndef EX_SHUT_MM
#define EX_SHUT_MM 155.0f
#endif

/* Both rangers on one side see a wall nearer than EX_SHUT_MM: a wall
 * alongside, close. */
static int side_shut(const ffr_state_t *st, uint8_t side)
{
    const ffr_config_t *cfg = &st->cfg;
    int f = side == FFR_SIDE_LEFT ? FFR_IR_LF : FFR_IR_RF;
    int r = side == FFR_SIDE_LEFT ? FFR_IR_LR : FFR_IR_RR;
    return ffr_ir_valid(cfg, st->ir_mm[f]) && st->ir_mm[f] < EX_SHUT_MM && ffr_ir_valid(cfg, st->ir_mm[r])
           && st->ir_mm[r] < EX_SHUT_MM;
}

/* Out of a door the walk goes on toward the followed side. A door in a
 * hallway's end (the 2004 map's rooms 2 and 3: the west hallway's and the
 * corridor's dead ends) leaves the robot with that end wall along the
 * followed side, often nearer than a hallway's half when the exit came out
 * off the door's middle: the quarter turn toward it sweeps that side's front
 * corner (156 mm from the axle) through it, and faces it (the wall case
 * would turn back at once). Turning away sweeps the rear corner (141 mm)
 * instead, and is the way a wall follower goes on after the dead end anyway. */
int ffr_explore_way_out(const ffr_state_t *st)
{
    const ffr_explore_t *e = &st->explore;
    if (side_shut(st, e->side) && !side_shut(st, (uint8_t)(1u - e->side))) {
        return -toward(e);
    }
    return toward(e);
}

static void explore_step(ffr_state_t *st, const ffr_inputs_t *in)
{
    const ffr_config_t *cfg = &st->cfg;
    ffr_explore_t *e = &st->explore;
    switch (e->phase) {
    case EX_FOLLOW:
    case EX_WRAP:
        follow(st);
        return;
    case EX_TURN:
        if (st->lines.edge && e->edge_mm != EX_NO_EDGE && st->odo.dist_mm - e->edge_mm <= FFR_HOME_CHORD_MM) {
            /* The home circle's far side met by the line sensor's arc while
             * turning in place inside it: home at a junction (the 2001
             * plan's, at the middle hallway's mouth), the turn into the
             * crossing hallway begun before the far side was crossed, and
             * the sensor on the ring when the turn ends (no edge after it).
             * The circle, as on a straight chord: with the flame out the
             * robot stops there; before, the walls change and the turn goes
             * on (before this, the walk went round the island room's loop
             * until the time ran out: docs/robustness.md, "Options
             * together"). */
            (void)line_edge(st);
            if (e->phase == EX_HOME) {
                return;
            }
        }
        ffr_turn_toward(st, e->target_rad);
        if (ffr_turn_done(cfg, &st->odo, e->target_rad)) {
            ffr_turn_finish(st, e->target_rad);
            phase(st, e->after);
        }
        return;
    case EX_PROBE:
        probe(st, in);
        return;
    case EX_ROOM:
        switch (ffr_room_step(st, in)) {
        case FFR_ROOM_FACING_OUT:
            st->route.heading_ref_rad = st->room.exit_heading_rad;
            break;
        case FFR_ROOM_LEFT:
            st->rooms_searched = (uint8_t)(st->rooms_searched + 1u);
            if (st->flags & FFR_FLAG_EXTINGUISHED) {
                st->returning = 1;
            }
            e->edge_mm = EX_NO_EDGE;
            /* facing out of the door: on the way the walk went before it
             * (away from a hallway's end beside the door) */
            turn(st, ffr_explore_way_out(st), EX_FOLLOW);
            break;
        case FFR_ROOM_BUSY:
        default:
            break;
        }
        return;
    case EX_BACK: {
        /* out to where the probe began, its line crossed again (not counted) */
        float left = e->goal_mm - (st->odo.dist_mm - e->start_mm);
        if (left <= 0.0f || ffr_front_now(cfg, &st->odo, st->ir_mm) < cfg->front_stop_mm) {
            e->edge_mm = EX_NO_EDGE;
            turn(st, toward(e), EX_FOLLOW);
            return;
        }
        ffr_drive_held(st, ffr_stopping_speed(left, cfg->room_speed_mm_s));
        return;
    }
    case EX_HOME: {
        float left = e->goal_mm - st->odo.dist_mm;
        if (left <= 0.0f || ffr_front_now(cfg, &st->odo, st->ir_mm) < cfg->front_stop_mm) {
            ffr_stop(st);
            e->phase = EX_DONE;
            st->state = FFR_ST_DONE;
            st->flags |= FFR_FLAG_DONE;
            return;
        }
        ffr_drive_held(st, ffr_stopping_speed(left, cfg->room_speed_mm_s));
        return;
    }
    case EX_DONE:
    default:
        ffr_stop(st);
        return;
    }
}

/* Driving between the rooms, a front corner that comes near a wall its
 * ranger sees beside the front half (a door's jamb, a wall's end met off the
 * hallway's middle) is steered off it, as a room's exit is (room_guards.c). */
void ffr_explore_step(ffr_state_t *st, const ffr_inputs_t *in)
{
    explore_step(st, in);
    if (st->state != FFR_ST_DONE && st->state != FFR_ST_FAILED && st->explore.phase != EX_ROOM
        && st->explore.phase != EX_TURN && st->cmd_v_mm_s > 0.0f) {
        st->cmd_w_rad_s += ffr_leave_guard(st);
    }
}
