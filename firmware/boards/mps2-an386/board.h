/* Board services for the mps2-an386 build: UART, millisecond clock, exit. */
#ifndef FFR_BOARD_H
#define FFR_BOARD_H
#include <stdint.h>

#define BOARD_CPU_HZ 25000000u

void board_clock_init(void);
uint32_t board_millis(void);
void board_exit(int status);

void uart_init(void);
void uart_putc(uint8_t c);
void uart_write(const uint8_t *p, uint32_t n);
void uart_puts(const char *s);
/* -1 when nothing has arrived */
int uart_getc(void);
int uart_rx_empty(void);
/* 1 once the UART has lost a byte before the driver read it (its sticky overrun flag) */
uint32_t uart_rx_overruns(void);
void uart1_puts(const char *s);
void uart0_rx_handler(void);
/* Ethernet (eth_lan9118.c): a whole link frame per Ethernet frame, the fast link under QEMU */
uint32_t eth_init(void); /* 1: the controller is there and set up */
uint32_t eth_recv(uint8_t *buf, uint32_t cap); /* the next frame's payload length, 0: none */
void eth_send(const uint8_t *p, uint32_t n);
void eth_irq_handler(void);
/* with interrupts masked: arm the receive wake-up; 1 when no frame is waiting */
uint32_t eth_idle_arm(void);
/* sleep until an interrupt (a byte, the millisecond tick) unless one is already due */
void board_idle(void);
#endif
