/* Board services for the micro:bit build (nRF51822, Cortex-M0, no FPU): UART, millisecond clock, exit. */
#ifndef FFR_BOARD_H
#define FFR_BOARD_H
#include <stdint.h>

#define BOARD_CPU_HZ 16000000u

void board_clock_init(void);
uint32_t board_millis(void);
void board_exit(int status);
/* sleep until an interrupt (a byte, the millisecond tick) unless one is already due */
void board_idle(void);
/* the profile line: semihosting SYS_WRITE0 (QEMU -semihosting, or a probe that serves it) */
void board_log_puts(const char *s);

/* UART0: the link. Receive by interrupt into a ring, transmit polled. */
void uart_init(void);
void uart_write(const uint8_t *p, uint32_t n);
/* -1 when nothing has arrived */
int uart_getc(void);
int uart_rx_empty(void);
/* 1 once the UART has lost a received byte (its sticky overrun error flag) */
uint32_t uart_rx_overruns(void);
void uart0_irq_handler(void);
void timer1_irq_handler(void);
#endif
