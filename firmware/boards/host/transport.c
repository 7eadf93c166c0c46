/*
 * The host board's transports. A pty looks like a serial port to the host
 * (pyserial opens its slave path); TCP listens on 127.0.0.1 only; stdio is
 * for pipes. The board holds its own copy of the pty slave until the host's
 * first byte arrives (so the line is not hung up before the host opens it),
 * then drops it: from then on a hang-up means the host has gone.
 */
#define _POSIX_C_SOURCE 200809L
#define _XOPEN_SOURCE 600

#include "transport.h"

#include <arpa/inet.h>
#include <errno.h>
#include <fcntl.h>
#include <netinet/in.h>
#include <netinet/tcp.h>
#include <poll.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/socket.h>
#include <termios.h>
#include <unistd.h>

static void make_raw(int fd)
{
    struct termios tio;
    if (tcgetattr(fd, &tio) != 0) {
        return;
    }
    /* what cfmakeraw does, spelled out (cfmakeraw is not POSIX) */
    tio.c_iflag &= (tcflag_t) ~(IGNBRK | BRKINT | PARMRK | ISTRIP | INLCR | IGNCR | ICRNL | IXON | IXOFF);
    tio.c_oflag &= (tcflag_t)~OPOST;
    tio.c_lflag &= (tcflag_t) ~(ECHO | ECHONL | ICANON | ISIG | IEXTEN);
    tio.c_cflag &= (tcflag_t) ~(CSIZE | PARENB);
    tio.c_cflag |= CS8;
    tio.c_cc[VMIN] = 1;
    tio.c_cc[VTIME] = 0;
    (void)tcsetattr(fd, TCSANOW, &tio);
}

static int open_pty(transport_t *t)
{
    const char *slave;
    int m = posix_openpt(O_RDWR | O_NOCTTY);
    if (m < 0 || grantpt(m) != 0 || unlockpt(m) != 0 || (slave = ptsname(m)) == NULL) {
        perror("ffr-host-board: pty");
        return -1;
    }
    snprintf(t->name, sizeof(t->name), "%s", slave);
    t->slave_fd = open(t->name, O_RDWR | O_NOCTTY);
    if (t->slave_fd < 0) {
        perror("ffr-host-board: pty slave");
        return -1;
    }
    make_raw(t->slave_fd);
    t->rfd = t->wfd = m;
    printf("FFR-BOARD pty %s\n", t->name);
    return 0;
}

static int open_tcp(transport_t *t, int port)
{
    struct sockaddr_in a;
    socklen_t alen = sizeof(a);
    int one = 1;
    int s = socket(AF_INET, SOCK_STREAM, 0);
    if (s < 0) {
        perror("ffr-host-board: socket");
        return -1;
    }
    (void)setsockopt(s, SOL_SOCKET, SO_REUSEADDR, &one, sizeof(one));
    memset(&a, 0, sizeof(a));
    a.sin_family = AF_INET;
    a.sin_port = htons((uint16_t)port);
    a.sin_addr.s_addr = htonl(INADDR_LOOPBACK); /* loopback only */
    if (bind(s, (struct sockaddr *)&a, sizeof(a)) != 0 || listen(s, 1) != 0 ||
        getsockname(s, (struct sockaddr *)&a, &alen) != 0) {
        perror("ffr-host-board: tcp");
        close(s);
        return -1;
    }
    t->listen_fd = s;
    snprintf(t->name, sizeof(t->name), "127.0.0.1:%u", (unsigned)ntohs(a.sin_port));
    printf("FFR-BOARD tcp %s\n", t->name);
    return 0;
}

int transport_open(transport_t *t, transport_kind_t kind, int tcp_port)
{
    int rc = 0;
    t->kind = kind;
    t->rfd = t->wfd = t->listen_fd = t->slave_fd = -1;
    t->name[0] = '\0';
    if (kind == TRANSPORT_PTY) {
        rc = open_pty(t);
    } else if (kind == TRANSPORT_TCP) {
        rc = open_tcp(t, tcp_port);
    } else {
        t->rfd = STDIN_FILENO;
        t->wfd = STDOUT_FILENO;
        snprintf(t->name, sizeof(t->name), "stdio");
    }
    fflush(stdout);
    return rc;
}

long transport_read(transport_t *t, uint8_t *buf, size_t cap, int timeout_ms)
{
    struct pollfd p;
    ssize_t n;
    int rc;
    if (t->listen_fd >= 0) { /* TCP: the host has not connected yet */
        p.fd = t->listen_fd;
        p.events = POLLIN;
        rc = poll(&p, 1, timeout_ms);
        if (rc <= 0) {
            return rc < 0 && errno != EINTR ? -1 : 0;
        }
        t->rfd = t->wfd = accept(t->listen_fd, NULL, NULL);
        close(t->listen_fd);
        t->listen_fd = -1;
        if (t->rfd < 0) {
            return -1;
        }
        rc = 1;
        (void)setsockopt(t->rfd, IPPROTO_TCP, TCP_NODELAY, &rc, sizeof(rc)); /* one frame, one segment */
        return 0;
    }
    p.fd = t->rfd;
    p.events = POLLIN;
    p.revents = 0;
    rc = poll(&p, 1, timeout_ms);
    if (rc < 0) {
        return errno == EINTR ? 0 : -1;
    }
    if (rc == 0) {
        return 0;
    }
    n = read(t->rfd, buf, cap);
    if (n > 0) {
        if (t->slave_fd >= 0) { /* the host has opened the line: hang-ups are real from now on */
            close(t->slave_fd);
            t->slave_fd = -1;
        }
        return (long)n;
    }
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) {
        return 0;
    }
    return -1; /* EOF, or EIO on a pty whose slave was closed */
}

int transport_write(transport_t *t, const uint8_t *buf, size_t len)
{
    size_t done = 0;
    while (done < len) {
        ssize_t n = write(t->wfd, buf + done, len - done);
        if (n < 0) {
            if (errno == EINTR || errno == EAGAIN) {
                continue;
            }
            return -1;
        }
        done += (size_t)n;
    }
    return 0;
}

void transport_close(transport_t *t)
{
    if (t->kind != TRANSPORT_STDIO && t->rfd >= 0) {
        close(t->rfd);
    }
    if (t->listen_fd >= 0) {
        close(t->listen_fd);
    }
    if (t->slave_fd >= 0) {
        close(t->slave_fd);
    }
    t->rfd = t->wfd = t->listen_fd = t->slave_fd = -1;
}
