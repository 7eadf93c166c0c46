#include "selftest.h"

#include "ffr.h"

static uint32_t fnv_bytes(uint32_t h, const uint8_t *p, uint32_t n)
{
    uint32_t i;
    for (i = 0; i < n; ++i) {
        h ^= p[i];
        h *= 16777619u;
    }
    return h;
}

static uint32_t lcg(uint32_t *s)
{
    *s = *s * 1664525u + 1013904223u;
    return *s >> 8;
}

void ffr_selftest_run(uint32_t ticks, uint32_t (*clock)(void), ffr_selftest_result_t *res)
{
    /* static: board RAM, not stack; reset on every run below */
    static ffr_state_t st;
    static ffr_config_t cfg;
    ffr_inputs_t in;
    ffr_outputs_t out;
    uint32_t seed = 12345u;
    uint32_t h = 2166136261u;
    float enc[2] = {0.0f, 0.0f};
    uint32_t k;
    int i;
    ffr_config_default(&cfg);
    ffr_init(&st, &cfg);
    in.t_ms = 0u;
    in.seq = 0u;
    in.enc[0] = 0;
    in.enc[1] = 0;
    in.line = 0u;
    in.start = 1u;
    res->clock_sum = 0u;
    res->clock_max = 0u;
    for (k = 0; k < ticks; ++k) {
        for (i = 0; i < FFR_IR_COUNT; ++i) {
            in.ir_mv[i] = (uint16_t)(300u + lcg(&seed) % 2200u);
        }
        in.flame[0] = (uint16_t)(40u + lcg(&seed) % 900u);
        in.flame[1] = (uint16_t)(40u + lcg(&seed) % 900u);
        in.line = (uint8_t)((lcg(&seed) % 97u) == 0u);
        if (clock != 0) {
            uint32_t c0 = clock();
            uint32_t dc;
            ffr_step(&st, &in, &out);
            dc = (clock() - c0) & 0xFFFFFFu;
            res->clock_sum += dc;
            res->clock_max = dc > res->clock_max ? dc : res->clock_max;
        } else {
            ffr_step(&st, &in, &out);
        }
        h = fnv_bytes(h, (const uint8_t *)&out, (uint32_t)sizeof(out));
        for (i = 0; i < 2; ++i) {
            enc[i] += (float)out.pwm[i] * 0.012f;
            in.enc[i] = (int32_t)enc[i];
        }
        in.t_ms += 10u;
        in.seq += 1u;
    }
    res->ticks = ticks;
    res->checksum = h;
    res->last_pwm[0] = out.pwm[0];
    res->last_pwm[1] = out.pwm[1];
    res->last_state = out.state;
}

static char *put_u32(char *p, uint32_t v, int hex)
{
    char tmp[12];
    int n = 0;
    uint32_t base = hex ? 16u : 10u;
    do {
        uint32_t d = v % base;
        tmp[n++] = (char)(d < 10u ? '0' + (int)d : 'a' + (int)(d - 10u));
        v /= base;
    } while (v != 0u || (hex && n < 8));
    while (n > 0) {
        *p++ = tmp[--n];
    }
    return p;
}

static char *put_s(char *p, const char *s)
{
    while (*s != '\0') {
        *p++ = *s++;
    }
    return p;
}

void ffr_selftest_format(const ffr_selftest_result_t *res, char *buf)
{
    char *p = buf;
    p = put_s(p, "ffr-selftest ticks=");
    p = put_u32(p, res->ticks, 0);
    p = put_s(p, " checksum=");
    p = put_u32(p, res->checksum, 1);
    p = put_s(p, " state=");
    p = put_u32(p, res->last_state, 0);
    *p++ = '\n';
    *p = '\0';
}
