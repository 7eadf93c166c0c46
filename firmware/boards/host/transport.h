/* POSIX byte transports for the host board: a pseudo-terminal, TCP on the
 * loopback, or standard input/output. */
#ifndef FFR_HOST_TRANSPORT_H
#define FFR_HOST_TRANSPORT_H

#include <stddef.h>
#include <stdint.h>

typedef enum { TRANSPORT_PTY, TRANSPORT_TCP, TRANSPORT_STDIO } transport_kind_t;

typedef struct {
    transport_kind_t kind;
    int rfd;          /* read from here  */
    int wfd;          /* write here      */
    int listen_fd;    /* TCP: the listening socket until a client connects */
    int slave_fd;     /* PTY: our copy of the slave, held until the host opens it */
    char name[128];   /* pty path or host:port */
} transport_t;

/* Open; announces "FFR-BOARD pty PATH" or "FFR-BOARD tcp HOST:PORT" on stdout. 0 = ok. */
int transport_open(transport_t *t, transport_kind_t kind, int tcp_port);
/* Wait up to timeout_ms for bytes; returns the count read, 0 on timeout, -1
 * when the other side has gone (EOF, hang-up) or on error. */
long transport_read(transport_t *t, uint8_t *buf, size_t cap, int timeout_ms);
/* Write everything; 0 = ok. */
int transport_write(transport_t *t, const uint8_t *buf, size_t len);
void transport_close(transport_t *t);

#endif
