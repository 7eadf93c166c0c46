/* C tests of the wire codec and the board link; argv[1]: the shared test
 * vectors (tests/bridge/vectors/wire_vectors.txt), also read by pytest. */
#include "unit.h"
#include "wire_tests.h"

unit_tally_t unit_tally;

int main(int argc, char **argv)
{
    suite_codec();
    suite_board_link();
    if (argc > 1) {
        suite_vectors(argv[1]);
    } else {
        printf("wire: no vectors file given, vector suite skipped\n");
    }
    printf("wire: %d passed, %d failed\n", unit_tally.passed, unit_tally.failed);
    return unit_tally.failed == 0 ? 0 : 1;
}
