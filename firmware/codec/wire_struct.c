/*
 * Struct <-> wire bytes, driven by the firmware's own layout table
 * (layout.c): every field in table order, little-endian, no padding. So the
 * wire format follows the structs without a second hand-written list, works
 * on either byte order, and the layout hash in the handshake covers it.
 */
#include "ffr_codec.h"

typedef union {
    float f;
    uint32_t u;
} f32_bits_t; /* C99 allows reading the other member: the float's bits */

static size_t type_size(uint16_t type)
{
    switch (type) {
    case FFR_T_U8:
        return 1u;
    case FFR_T_I16:
    case FFR_T_U16:
        return 2u;
    case FFR_T_I32:
    case FFR_T_U32:
    case FFR_T_F32:
        return 4u;
    default:
        return 0u;
    }
}

static void put_le(uint8_t *w, uint32_t v, size_t n)
{
    size_t i;
    for (i = 0; i < n; ++i) {
        w[i] = (uint8_t)(v >> (8u * i));
    }
}

static uint32_t get_le(const uint8_t *w, size_t n)
{
    uint32_t v = 0;
    size_t i;
    for (i = 0; i < n; ++i) {
        v |= (uint32_t)w[i] << (8u * i);
    }
    return v;
}

static uint32_t load(const uint8_t *p, uint16_t type)
{
    f32_bits_t fb;
    switch (type) {
    case FFR_T_U8:
        return *p;
    case FFR_T_I16:
    case FFR_T_U16:
        return *(const uint16_t *)(const void *)p;
    case FFR_T_F32:
        fb.f = *(const float *)(const void *)p;
        return fb.u;
    default:
        return *(const uint32_t *)(const void *)p;
    }
}

static void store(uint8_t *p, uint16_t type, uint32_t v)
{
    f32_bits_t fb;
    switch (type) {
    case FFR_T_U8:
        *p = (uint8_t)v;
        break;
    case FFR_T_I16:
    case FFR_T_U16:
        *(uint16_t *)(void *)p = (uint16_t)v;
        break;
    case FFR_T_F32:
        fb.u = v;
        *(float *)(void *)p = fb.f;
        break;
    default:
        *(uint32_t *)(void *)p = v;
        break;
    }
}

/* A struct the table describes: the I/O, the configuration, a firmware-own sub-struct. */
static int known_struct(uint32_t struct_id)
{
    return (struct_id <= FFR_S_CONFIG || (struct_id >= FFR_S_OWN && struct_id <= 255u && struct_id != FFR_S_STATE)) &&
           ffr_sizeof(struct_id) != 0u;
}

size_t ffr_wire_size(uint32_t struct_id)
{
    uint32_t n = 0;
    uint32_t i;
    size_t total = 0;
    const ffr_field_t *f = ffr_layout(&n);
    if (!known_struct(struct_id)) {
        return 0u;
    }
    for (i = 0; i < n; ++i) {
        if (f[i].struct_id != struct_id) {
            continue;
        }
        if (FFR_T_BASE(f[i].type) == FFR_T_STRUCT) {
            uint32_t sub = FFR_T_SUBSTRUCT(f[i].type);
            if (sub < FFR_S_OWN) {
                return 0u; /* only firmware-own sub-structs nest: no loops */
            }
            total += (size_t)f[i].count * ffr_wire_size(sub);
        } else {
            total += (size_t)f[i].count * type_size(f[i].type);
        }
    }
    return total;
}

/* One direction at a time: encode reads st and writes wire, decode the reverse. */
static size_t xfer(uint32_t struct_id, uint8_t *st, const uint8_t *cst, uint8_t *wire, const uint8_t *cwire,
                   size_t cap)
{
    uint32_t n = 0;
    uint32_t i;
    uint16_t k;
    size_t w = 0;
    const ffr_field_t *f = ffr_layout(&n);
    for (i = 0; i < n; ++i) {
        size_t ts = type_size(f[i].type);
        if (f[i].struct_id != struct_id) {
            continue;
        }
        for (k = 0; k < f[i].count; ++k) {
            if (FFR_T_BASE(f[i].type) == FFR_T_STRUCT) { /* an array of a firmware-own sub-struct */
                uint32_t sub = FFR_T_SUBSTRUCT(f[i].type);
                size_t at = (size_t)f[i].offset + (size_t)k * ffr_sizeof(sub);
                size_t got = sub < FFR_S_OWN ? 0u : xfer(sub, st != NULL ? st + at : NULL, cst != NULL ? cst + at : NULL,
                                  wire != NULL ? wire + w : NULL, cwire != NULL ? cwire + w : NULL, cap - w);
                if (got == 0u) {
                    return 0u;
                }
                w += got;
                continue;
            }
            if (ts == 0u || w + ts > cap) {
                return 0u;
            }
            if (wire != NULL) {
                put_le(wire + w, load(cst + f[i].offset + (size_t)k * ts, f[i].type), ts);
            } else {
                store(st + f[i].offset + (size_t)k * ts, f[i].type, get_le(cwire + w, ts));
            }
            w += ts;
        }
    }
    return w;
}

size_t ffr_wire_encode(uint32_t struct_id, const void *s, uint8_t *buf, size_t cap)
{
    if (s == NULL || buf == NULL || !known_struct(struct_id) || cap < ffr_wire_size(struct_id)) {
        return 0u;
    }
    return xfer(struct_id, NULL, (const uint8_t *)s, buf, NULL, cap);
}

size_t ffr_wire_decode(uint32_t struct_id, const uint8_t *buf, size_t len, void *s)
{
    size_t need = ffr_wire_size(struct_id);
    if (s == NULL || buf == NULL || !known_struct(struct_id) || need == 0u || len != need) {
        return 0u;
    }
    return xfer(struct_id, (uint8_t *)s, NULL, NULL, buf, len);
}
