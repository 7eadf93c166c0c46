/*
 * The shared test vectors (tests/bridge/vectors/wire_vectors.txt), written
 * by the Python codec and checked here against the C codec; pytest checks
 * the Python codec against the same file. One vector per line:
 *   crc HEX CRC | cobs RAW ENC | frame MSG FRAME | msg MSG
 *   can MSG ID:DATA,... | canfd MSG ID:DATA,... | bad FRAME STATUS
 * One test a kind, each reading the file on its own; a failed vector names
 * its line. The file is wire_vectors_path (main.c: --vectors FILE).
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

/* One vector line: its kind, fields x and y (the first two after it). */
typedef struct {
    char line[16384];
    char *kind, *x, *y;
    int lineno;
} vector_t;

/* Reads the next vector of the file (comments and blank lines skipped); 0 at the end. */
static int next_vector(FILE *f, vector_t *v)
{
    while (fgets(v->line, sizeof(v->line), f) != NULL) {
        char *p = v->line;
        ++v->lineno;
        if (v->line[0] == '#' || v->line[0] == '\n') {
            continue;
        }
        v->kind = field(&p);
        v->x = field(&p);
        v->y = field(&p);
        return 1;
    }
    return 0;
}

/* Does the vector hold (1, else 0)? -1 for a kind it does not know. y: its second field (CAN: parsed in place). */
static int vector_holds(const vector_t *v, char *y)
{
    uint8_t a[MAXB], b[MAXB], c[MAXB + 64];
    ffr_msg_t m;
    const char *kind = v->kind;
    size_t na = unhex(v->x, strlen(v->x), a), nb = unhex(y, strlen(y), b), nc = 0;
    int ok;
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
    } else {
        ok = -1;
    }
    return ok;
}

/* Checks every vector of one kind in the file; there must be at least `least` of them. */
static void check_kind(const char *kind, int least)
{
    vector_t v;
    int count = 0;
    FILE *f = fopen(wire_vectors_path, "r");
    CHECK(f != NULL);
    if (f == NULL) {
        printf("cannot open %s\n", wire_vectors_path);
        return;
    }
    v.lineno = 0;
    while (next_vector(f, &v)) {
        int ok;
        if (strcmp(v.kind, kind) != 0) {
            continue;
        }
        ok = vector_holds(&v, v.y) == 1;
        if (!ok) {
            printf("%s:%d: %s vector failed\n", wire_vectors_path, v.lineno, kind);
        }
        CHECK(ok);
        ++count;
    }
    fclose(f);
    CHECK(count >= least);
}

TEST(every_crc_vector_matches) { check_kind("crc", 1); }
TEST(every_cobs_vector_encodes_and_decodes) { check_kind("cobs", 1); }
TEST(every_frame_vector_encodes_and_decodes) { check_kind("frame", 1); }
TEST(every_msg_vector_decodes_and_encodes_back) { check_kind("msg", 1); }
TEST(every_can_vector_segments_and_reassembles) { check_kind("can", 1); }
TEST(every_canfd_vector_segments_and_reassembles) { check_kind("canfd", 1); }
TEST(every_bad_frame_vector_gets_its_status) { check_kind("bad", 1); }

/* Every line is of a kind checked above, and there are enough of them (the count is printed). */
TEST(every_vector_is_of_a_known_kind)
{
    static const char *const kinds[] = {"crc", "cobs", "frame", "msg", "can", "canfd", "bad"};
    vector_t v;
    int count = 0;
    size_t k;
    FILE *f = fopen(wire_vectors_path, "r");
    CHECK(f != NULL);
    if (f == NULL) {
        printf("cannot open %s\n", wire_vectors_path);
        return;
    }
    v.lineno = 0;
    while (next_vector(f, &v)) {
        int known = 0;
        for (k = 0; k < sizeof(kinds) / sizeof(kinds[0]); ++k) {
            known |= strcmp(v.kind, kinds[k]) == 0;
        }
        if (!known) {
            printf("%s:%d: unknown vector kind %s\n", wire_vectors_path, v.lineno, v.kind);
        }
        CHECK(known);
        ++count;
    }
    fclose(f);
    CHECK(count >= 20);
    printf("wire: %d shared vectors checked\n", count);
}

SUITE(vectors,
      TEST_REF(every_crc_vector_matches),
      TEST_REF(every_cobs_vector_encodes_and_decodes),
      TEST_REF(every_frame_vector_encodes_and_decodes),
      TEST_REF(every_msg_vector_decodes_and_encodes_back),
      TEST_REF(every_can_vector_segments_and_reassembles),
      TEST_REF(every_canfd_vector_segments_and_reassembles),
      TEST_REF(every_bad_frame_vector_gets_its_status),
      TEST_REF(every_vector_is_of_a_known_kind));
