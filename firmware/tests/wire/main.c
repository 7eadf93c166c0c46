/*
 * C tests of the wire codec and the board link, and the shared test vectors
 * (tests/bridge/vectors/wire_vectors.txt, also read by pytest):
 *   ffr_wire_tests [--vectors FILE] [NAME... | --list | --demo-failure]
 * NAME is a suite or suite.test; FILE defaults to the repository's vectors file
 * (a path relative to the repository root, where make and pytest run it).
 * The runner is firmware/tests/unit_runner.c, the unit tests' own; the last line
 * counts suites, tests and checks (tests/bridge/test_c_wire.py asserts the exact numbers).
 */
#include <string.h>

#include "unit.h"
#include "wire_tests.h"

const char *wire_vectors_path = "tests/bridge/vectors/wire_vectors.txt";

static const unit_suite_t *const k_suites[] = {&suite_codec, &suite_board_link, &suite_vectors};

TEST(a_check_that_fails_on_purpose) { CHECK(1 + 1 == 3); }
SUITE(wire_demo, TEST_REF(a_check_that_fails_on_purpose));

int main(int argc, char **argv)
{
    if (argc >= 3 && strcmp(argv[1], "--vectors") == 0) {
        wire_vectors_path = argv[2];
        argv[2] = argv[0]; /* the rest, as if the program were called without the option */
        argv += 2;
        argc -= 2;
    }
    return unit_run("wire", k_suites, (int)(sizeof(k_suites) / sizeof(k_suites[0])), &suite_wire_demo, argc, argv);
}
