/*
 * ffr_contract_hash.h - the contract's layout hash, for any firmware (docs/contract.md,
 * "Layout hash"). A firmware's ffr_layout_hash() may simply return ffr_contract_hash():
 *
 *   #include "ffr_contract_hash.h"
 *   uint32_t ffr_layout_hash(void) { return ffr_contract_hash(); }
 *
 * FNV-1a, 32 bits, over
 *   1. every layout row: the name's bytes, then struct id, type, offset, count (2 bytes each, LE);
 *   2. ffr_sizeof of inputs, outputs, config (4 bytes each), then of the sub-struct each
 *      FFR_T_STRUCT_OF row names (4 bytes each, in row order);
 *   3. every name table of kind 0..255 that has names: kind, count (2 bytes each), then
 *      each name's bytes and a 0 byte;
 *   4. the firmware's name and a 0 byte.
 * The harness computes the same from what the library describes (ffr_link/abi.py
 * contract_hash) and compares a board's hash with the host library's.
 */
#ifndef FFR_CONTRACT_HASH_H
#define FFR_CONTRACT_HASH_H

#include "ffr_contract.h"

static inline uint32_t ffr_contract_fnv(uint32_t h, uint32_t v, uint32_t bytes)
{
    uint32_t i;
    for (i = 0; i < bytes; ++i) {
        h ^= (v >> (8u * i)) & 0xFFu;
        h *= 16777619u;
    }
    return h;
}

static inline uint32_t ffr_contract_fnv_str(uint32_t h, const char *s)
{
    if (s != NULL) {
        for (; *s != '\0'; ++s) {
            h = ffr_contract_fnv(h, (uint32_t)(uint8_t)*s, 1u);
        }
    }
    return ffr_contract_fnv(h, 0u, 1u);
}

static inline uint32_t ffr_contract_hash(void)
{
    uint32_t h = 2166136261u;
    uint32_t n = 0u;
    uint32_t i;
    uint32_t kind;
    const ffr_field_t *f = ffr_layout(&n);
    for (i = 0; i < n; ++i) {
        const char *c;
        for (c = f[i].name; *c != '\0'; ++c) {
            h = ffr_contract_fnv(h, (uint32_t)(uint8_t)*c, 1u);
        }
        h = ffr_contract_fnv(h, f[i].struct_id, 2u);
        h = ffr_contract_fnv(h, f[i].type, 2u);
        h = ffr_contract_fnv(h, f[i].offset, 2u);
        h = ffr_contract_fnv(h, f[i].count, 2u);
    }
    for (i = 0; i < 3u; ++i) {
        h = ffr_contract_fnv(h, ffr_sizeof(i), 4u);
    }
    for (i = 0; i < n; ++i) {
        if (FFR_T_BASE(f[i].type) == FFR_T_STRUCT) {
            h = ffr_contract_fnv(h, ffr_sizeof(FFR_T_SUBSTRUCT(f[i].type)), 4u);
        }
    }
    for (kind = 0u; kind < 256u; ++kind) {
        uint32_t count = 0u;
        const char *const *names = ffr_names(kind, &count);
        if (names == NULL || count == 0u) {
            continue;
        }
        h = ffr_contract_fnv(h, kind, 2u);
        h = ffr_contract_fnv(h, count, 2u);
        for (i = 0; i < count; ++i) {
            h = ffr_contract_fnv_str(h, names[i]);
        }
    }
    return ffr_contract_fnv_str(h, ffr_firmware_name());
}

#endif /* FFR_CONTRACT_HASH_H */
