#include "ffr_internal.h"
#include "unit.h"

TEST(the_reference_ramps_and_a_standing_wheel_gets_more_pwm)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    ffr_speed_ctl_t s;
    int16_t pwm[2];
    int i;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&o);
    ffr_speed_reset(&s);
    /* the reference ramps at accel: after 0.1 s at 1500 mm/s^2 it is 150 */
    for (i = 0; i < 10; ++i) {
        ffr_speed_control(&s, &cfg, &o, 300.0f, 0.0f, 0.01f, pwm);
    }
    CHECK_NEAR(s.v_ref[0], 150.0, 0.5);
    /* wheels not moving: position error grows and the PWM with it */
    CHECK(pwm[0] > (int16_t)(cfg.ff_gain_permille_per_mm_s * 150.0f));
    CHECK(pwm[0] == pwm[1]);
}

TEST(a_pure_yaw_command_drives_the_wheels_opposite)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    ffr_speed_ctl_t s;
    int16_t pwm[2];
    int i;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&o);
    ffr_speed_reset(&s);
    for (i = 0; i < 50; ++i) {
        ffr_speed_control(&s, &cfg, &o, 0.0f, 1.0f, 0.01f, pwm);
    }
    CHECK(pwm[0] < 0 && pwm[1] > 0);
}

TEST(never_beyond_the_pwm_limit)
{
    ffr_config_t cfg;
    ffr_odometry_t o;
    ffr_speed_ctl_t s;
    int16_t pwm[2];
    int i;
    ffr_config_default(&cfg);
    ffr_odometry_reset(&o);
    ffr_speed_reset(&s);
    cfg.pwm_limit = 400;
    for (i = 0; i < 100; ++i) {
        ffr_speed_control(&s, &cfg, &o, 2000.0f, 0.0f, 0.01f, pwm);
    }
    CHECK(pwm[0] == 400 && pwm[1] == 400);
}

SUITE(speed_control,
      TEST_REF(the_reference_ramps_and_a_standing_wheel_gets_more_pwm),
      TEST_REF(a_pure_yaw_command_drives_the_wheels_opposite),
      TEST_REF(never_beyond_the_pwm_limit));
