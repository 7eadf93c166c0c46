#include <string.h>

#include "ffr.h"
#include "unit.h"

void suite_layout(void)
{
    uint32_t n = 0, i;
    const ffr_field_t *f = ffr_layout(&n);
    int found_pwm = 0;
    CHECK(n > 20u);
    CHECK(ffr_sizeof(FFR_S_INPUTS) == sizeof(ffr_inputs_t));
    CHECK(ffr_sizeof(FFR_S_OUTPUTS) == sizeof(ffr_outputs_t));
    CHECK(ffr_sizeof(FFR_S_CONFIG) == sizeof(ffr_config_t));
    CHECK(ffr_sizeof(77u) == 0u);
    for (i = 0; i < n; ++i) {
        CHECK(f[i].offset < ffr_sizeof(f[i].struct_id));
        if (f[i].struct_id == FFR_S_OUTPUTS && strcmp(f[i].name, "pwm") == 0) {
            found_pwm = 1;
            CHECK(f[i].count == 2 && f[i].type == FFR_T_I16);
        }
    }
    CHECK(found_pwm);
    CHECK(ffr_layout_hash() == ffr_layout_hash());
    CHECK(ffr_layout_hash() != 0u);
    CHECK(ffr_version() == ((FFR_CONTRACT_MAJOR << 16) | FFR_CONTRACT_MINOR));
    {
        uint32_t k = 99u;
        const char *const *names = ffr_names(FFR_NAMES_STATE, &k);
        CHECK(k == FFR_ST_COUNT && strcmp(names[FFR_ST_DONE], "DONE") == 0);
        names = ffr_names(FFR_NAMES_FAIL, &k);
        CHECK(k == FFR_FAIL_LOST_FLAME + 1 && names[FFR_FAIL_NONE][0] == '\0');
        names = ffr_names(FFR_NAMES_OPS, &k);
        CHECK(k == FFR_OP_HOME + 1 && strcmp(names[FFR_OP_ROOM], "ROOM") == 0);
        CHECK(ffr_names(2u, &k) == NULL && k == 0u);
        CHECK(strncmp(ffr_firmware_name(), "ffr-reference", 13) == 0);
        CHECK(ffr_sizeof(FFR_S_ROUTE_STEP) == sizeof(ffr_step_t) && ffr_sizeof(FFR_S_STATE) == sizeof(ffr_state_t));
    }
}
