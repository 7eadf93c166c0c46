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
