#ifndef FFR_WIRE_TESTS_H
#define FFR_WIRE_TESTS_H
void suite_codec(void);
void suite_board_link(void);
void suite_vectors(const char *path);
#endif
