#include "rig.h"

#include "unit.h"

uint16_t rig_mv_for_mm(const ffr_config_t *cfg, float mm)
{
    return (uint16_t)(cfg->ir_k_mv_mm / (mm + cfg->ir_d0_mm) + cfg->ir_offset_mv + 0.5f);
}

void rig_no_walls(const ffr_config_t *cfg, float ir_mm[FFR_IR_COUNT])
{
    int i;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        ir_mm[i] = FFR_IR_NONE(cfg);
    }
}

void rig_init(rig_t *r, const ffr_config_t *cfg)
{
    int i;
    ffr_init(&r->st, cfg);
    /* the rig's hand-set rangers are not a room to orient in: the robot starts
     * as placed (home_orient's own tests set it back after rig_init) */
    r->st.cfg.home_wall_side = FFR_HOME_AS_PLACED;
    r->in.t_ms = 0;
    r->in.seq = 0;
    r->in.enc[0] = r->in.enc[1] = 0;
    r->enc_f[0] = r->enc_f[1] = 0.0f;
    for (i = 0; i < FFR_IR_COUNT; ++i) {
        r->in.ir_mv[i] = 0;
    }
    r->in.flame[0] = r->in.flame[1] = 20;
    r->in.line = 0;
    r->in.start = 0;
    {
        /* no output yet: a loop may test r->out before its first tick */
        static const ffr_outputs_t none;
        r->out = none;
    }
}

void rig_tick(rig_t *r)
{
    int i;
    ffr_step(&r->st, &r->in, &r->out);
    CHECK(r->out.seq == r->in.seq);
    for (i = 0; i < 2; ++i) {
        r->enc_f[i] += (float)r->out.pwm[i] * 0.012f;
        r->in.enc[i] = (int32_t)r->enc_f[i];
    }
    r->in.t_ms += 10u;
    r->in.seq += 1u;
}

void rig_line(rig_t *r, int before, int on)
{
    int i;
    for (i = 0; i < before; ++i) {
        rig_tick(r);
    }
    r->in.line = 1;
    for (i = 0; i < on; ++i) {
        rig_tick(r);
    }
    r->in.line = 0;
}

void rig_room_route(ffr_config_t *cfg, int home)
{
    cfg->route[0].op = FFR_OP_ROOM;
    cfg->route[0].arg = 1;
    cfg->route[1].op = FFR_OP_END;
    cfg->route_len = 2;
    if (home) {
        cfg->route[2].op = FFR_OP_HOME;
        cfg->route[2].side = FFR_SIDE_NONE;
        cfg->route_len = 3;
        cfg->return_start[0] = 2;
    }
}

const ffr_ir_geom_t *rig_geom(ffr_ir_geom_t *g, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT])
{
    ffr_ir_geom_init(g, cfg);
    ffr_ir_geom_update(g, cfg, ir_mm);
    return g;
}

void rig_travel_pend(ffr_openings_t *op, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], float *d,
                     int ticks, int pend_side)
{
    ffr_ir_geom_t g;
    int i;
    rig_geom(&g, cfg, ir_mm);
    for (i = 0; i < ticks; ++i, *d += 3.0f) {
        ffr_openings_update(op, cfg, &g, ir_mm, *d, 3.0f, pend_side);
    }
}

void rig_travel(ffr_openings_t *op, const ffr_config_t *cfg, const float ir_mm[FFR_IR_COUNT], float *d, int ticks)
{
    rig_travel_pend(op, cfg, ir_mm, d, ticks, -1);
}

void rig_ray(const ffr_config_t *cfg, int i, float x, float y, float th, float *mx, float *my, float *ux,
             float *uy)
{
    float c = ffr_cosf(th), s = ffr_sinf(th);
    *mx = x + c * cfg->ir_x_mm[i] - s * cfg->ir_y_mm[i];
    *my = y + s * cfg->ir_x_mm[i] + c * cfg->ir_y_mm[i];
    *ux = ffr_cosf(th + cfg->ir_angle_deg[i] * FFR_DEG);
    *uy = ffr_sinf(th + cfg->ir_angle_deg[i] * FFR_DEG);
}

float rig_beam_mm(const ffr_config_t *cfg, const rig_walls_t *w, int i, float x, float y, float th)
{
    float mx, my, ux, uy;
    float best = FFR_IR_NONE(cfg);
    float d;
    rig_ray(cfg, i, x, y, th, &mx, &my, &ux, &uy);
    if (uy > 1e-3f) {
        d = (w->left_y - my) / uy;
        best = d < best ? d : best;
    }
    if (uy < -1e-3f) {
        d = (w->right_y - my) / uy;
        if (w->jog_x != 0.0f && mx + d * ux > w->jog_x) {
            d = (w->right_y + w->jog_dy - my) / uy;
        }
        best = d < best ? d : best;
    }
    if (w->ahead_x != 0.0f && ux > 1e-3f) {
        d = (w->ahead_x - mx) / ux;
        best = d < best ? d : best;
    }
    if (best > cfg->ir_max_mm) {
        return FFR_IR_NONE(cfg);
    }
    return best + w->part_mm[i];
}

int rig_run_until_state(rig_t *r, uint8_t state, int max_ticks)
{
    int i;
    for (i = 0; i < max_ticks; ++i) {
        rig_tick(r);
        if (r->out.state == state) {
            return 1;
        }
    }
    return 0;
}

int rig_run_until_driving(rig_t *r, int max_ticks)
{
    int i;
    for (i = 0; i < max_ticks; ++i) {
        rig_tick(r);
        if (r->st.cmd_v_mm_s > 0.0f && r->st.cmd_w_rad_s < 0.2f && r->st.cmd_w_rad_s > -0.2f) {
            return 1;
        }
    }
    return 0;
}
