/*
 * The shared test vectors (tests/bridge/vectors/wire_vectors.txt), written
 * by the Python codec and checked here against the C codec; pytest checks
 * the Python codec against the same file. One vector per line:
 *   crc HEX CRC | cobs RAW ENC | frame MSG FRAME | msg MSG
 *   can MSG ID:DATA,... | canfd MSG ID:DATA,... | bad FRAME STATUS
 */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "ffr_codec.h"
#include "unit.h"
#include "wire_tests.h"

#define MAXB 2048

static size_t unhex(const char *s, size_t n, uint8_t *out)
{
    size_t i;
    for (i = 0; 2u * i + 1u < n && i < MAXB; ++i) {
        char b[3];
        b[0] = s[2u * i];
        b[1] = s[2u * i + 1u];
        b[2] = 0;
        out[i] = (uint8_t)strtoul(b, NULL, 16);
    }
    return i;
}

static char *field(char **p)
{
    char *s = *p, *e;
    while (*s == ' ') {
        ++s;
    }
    e = s;
    while (*e != '\0' && *e != ' ' && *e != '\n') {
        ++e;
    }
    *p = *e != '\0' ? e + 1 : e;
    *e = '\0';
    return s;
}

static int check_can(const uint8_t *msg, size_t n, int fd, char *frames)
{
    uint8_t data[64], want[64], out[FFR_MSG_MAX];
    uint32_t id, k = 0;
    uint8_t dlen;
    size_t ol = 0;
    int r = 0, ok = 1;
    ffr_can_rx_t rx;
    char *tok = strtok(frames, ",");
    ffr_can_rx_init(&rx);
    while (tok != NULL) {
        char *colon = strchr(tok, ':');
        size_t wl;
        if (colon == NULL || ffr_can_frame(msg, n, fd, k, &id, data, &dlen) != 1) {
            return 0;
        }
        wl = unhex(colon + 1, strlen(colon + 1), want);
        ok &= id == (uint32_t)strtoul(tok, NULL, 16) && wl == dlen && memcmp(data, want, wl) == 0;
        r = ffr_can_rx_push(&rx, id, want, (uint8_t)wl, out, sizeof(out), &ol);
        ++k;
        tok = strtok(NULL, ",");
    }
    return ok && ffr_can_frame(msg, n, fd, k, &id, data, &dlen) == 0 && r == 1 && ol == n && memcmp(out, msg, n) == 0;
}

void suite_vectors(const char *path)
{
    static char line[16384];
    static uint8_t a[MAXB], b[MAXB], c[MAXB + 64];
    static ffr_msg_t m;
    int count = 0;
    FILE *f = fopen(path, "r");
    CHECK(f != NULL);
    if (f == NULL) {
        printf("cannot open %s\n", path);
        return;
    }
    while (fgets(line, sizeof(line), f) != NULL) {
        char *p = line;
        char *kind, *x, *y;
        size_t na, nb, nc = 0;
        int ok = 0;
        if (line[0] == '#' || line[0] == '\n') {
            continue;
        }
        kind = field(&p);
        x = field(&p);
        y = field(&p);
        na = unhex(x, strlen(x), a);
        nb = unhex(y, strlen(y), b);
        if (strcmp(kind, "crc") == 0) {
            ok = nb == 2u && ffr_crc16(a, na) == (uint16_t)(b[0] << 8 | b[1]);
        } else if (strcmp(kind, "cobs") == 0) {
            nc = ffr_cobs_encode(a, na, c, sizeof(c));
            ok = nc == nb && memcmp(c, b, nb) == 0;
            ok &= ffr_cobs_decode(b, nb, c, sizeof(c), &nc) == FFR_OK && nc == na && memcmp(c, a, na) == 0;
        } else if (strcmp(kind, "frame") == 0) {
            nc = ffr_frame_encode(a, na, c, sizeof(c));
            ok = nc == nb && memcmp(c, b, nb) == 0;
            ok &= ffr_frame_decode(b, nb - 1u, c, sizeof(c), &nc) == FFR_OK && nc == na && memcmp(c, a, na) == 0;
        } else if (strcmp(kind, "msg") == 0) {
            ok = ffr_msg_decode(a, na, &m) == FFR_OK;
            nc = ffr_msg_encode(&m, c, sizeof(c));
            ok &= nc == na && memcmp(c, a, na) == 0;
        } else if (strcmp(kind, "can") == 0 || strcmp(kind, "canfd") == 0) {
            ok = check_can(a, na, strcmp(kind, "canfd") == 0, y);
        } else if (strcmp(kind, "bad") == 0) {
            int st = ffr_frame_decode(a, na, c, sizeof(c), &nc);
            if (st == FFR_OK) {
                st = ffr_msg_decode(c, nc, &m);
            }
            ok = st == atoi(y);
        }
        if (!ok) {
            printf("vector %d (%s) failed\n", count + 1, kind);
        }
        CHECK(ok);
        ++count;
    }
    fclose(f);
    CHECK(count >= 20);
    printf("wire: %d shared vectors checked\n", count);
}
