#include "ffr_internal.h"
#include "unit.h"

/* GP2D12 datasheet typical curve, cm -> V */
static const float k_cm[] = {10, 12, 14, 16, 18, 20, 25, 30, 35, 40, 45, 50, 60, 70, 80};
static const float k_v[] = {2.45f, 2.125f, 1.86f, 1.66f, 1.52f, 1.38f, 1.14f, 0.975f,
                            0.85f, 0.76f, 0.68f, 0.62f, 0.54f, 0.48f, 0.42f};

TEST(the_datasheet_curve_reads_back_within_8_percent)
{
    ffr_config_t cfg;
    unsigned i;
    ffr_config_default(&cfg);
    /* the datasheet's points read back within 8 %: the fit, not the table */
    for (i = 0; i < sizeof(k_cm) / sizeof(k_cm[0]); ++i) {
        float d = ffr_ir_mv_to_mm(&cfg, (uint16_t)(k_v[i] * 1000.0f + 0.5f));
        float want = k_cm[i] * 10.0f;
        CHECK_NEAR(d, want, 0.08f * want + 5.0f);
    }
}

TEST(weak_is_no_wall_strong_is_clamped_more_mv_is_nearer)
{
    ffr_config_t cfg;
    ffr_config_default(&cfg);
    /* too weak a signal: no wall in range */
    CHECK(!ffr_ir_valid(&cfg, ffr_ir_mv_to_mm(&cfg, 300)));
    CHECK(!ffr_ir_valid(&cfg, ffr_ir_mv_to_mm(&cfg, 0)));
    /* very strong: clamped to the minimum range */
    CHECK_NEAR(ffr_ir_mv_to_mm(&cfg, 3000), cfg.ir_min_mm, 0.01);
    /* monotone: more mV, nearer */
    CHECK(ffr_ir_mv_to_mm(&cfg, 1500) < ffr_ir_mv_to_mm(&cfg, 1000));
}

TEST(hit_points_are_the_mounting_pose_plus_the_reading)
{
    /* the hit points worked out once a tick (beam cos/sin kept from the
     * configuration) are bit for bit the mounting pose plus the reading
     * along the beam with the trig done on the spot */
    ffr_config_t cfg;
    ffr_ir_geom_t g;
    float ir[FFR_IR_COUNT];
    int k, r;
    ffr_config_default(&cfg);
    ffr_ir_geom_init(&g, &cfg);
    for (k = 0; k < 40; ++k) {
        for (r = 0; r < FFR_IR_COUNT; ++r) {
            ir[r] = cfg.ir_min_mm + (float)(k * 7 + r * 3) * 3.3f;
        }
        ffr_ir_geom_update(&g, &cfg, ir);
        for (r = 0; r < FFR_IR_COUNT; ++r) {
            float a = cfg.ir_angle_deg[r] * FFR_DEG;
            CHECK(g.hit_x_mm[r] == cfg.ir_x_mm[r] + ir[r] * ffr_cosf(a));
            CHECK(g.hit_y_mm[r] == cfg.ir_y_mm[r] + ir[r] * ffr_sinf(a));
        }
    }
}

SUITE(ir_calibration,
      TEST_REF(the_datasheet_curve_reads_back_within_8_percent),
      TEST_REF(weak_is_no_wall_strong_is_clamped_more_mv_is_nearer),
      TEST_REF(hit_points_are_the_mounting_pose_plus_the_reading));
