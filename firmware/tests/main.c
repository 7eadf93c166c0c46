#include "unit.h"

unit_tally_t unit_tally;

int main(void)
{
    suite_fmath();
    suite_ir_calibration();
    suite_odometry();
    suite_speed_control();
    suite_wall_follow();
    suite_wall_cases();
    suite_wall_calibration();
    suite_wall_direction();
    suite_line_counter();
    suite_openings();
    suite_mission();
    suite_layout();
    suite_robustness();
    suite_home_orient();
    suite_turn_calibration();
    suite_turn_room();
    printf("firmware: %d passed, %d failed\n", unit_tally.passed, unit_tally.failed);
    return unit_tally.failed == 0 ? 0 : 1;
}
