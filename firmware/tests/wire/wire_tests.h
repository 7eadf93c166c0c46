#ifndef FFR_WIRE_TESTS_H
#define FFR_WIRE_TESTS_H
#include "unit.h"

/* the shared test vectors file the vectors suite reads (main.c: --vectors FILE) */
extern const char *wire_vectors_path;

extern const unit_suite_t suite_codec;
extern const unit_suite_t suite_board_link;
extern const unit_suite_t suite_vectors;
#endif
