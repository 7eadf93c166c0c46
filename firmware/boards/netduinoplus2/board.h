/* Board services for the netduinoplus2 build (STM32F405, Cortex-M4F): USART, millisecond clock, exit. */
#ifndef FFR_BOARD_H
#define FFR_BOARD_H
#include <stdint.h>

/* QEMU's netduinoplus2 fixes SYSCLK at 168 MHz and does not model the RCC.
 * A real board reaches these after the PLL set-up (docs/boards.md). */
#define BOARD_CPU_HZ 168000000u
#define BOARD_APB1_HZ 42000000u /* USART2..5, TIM2..7 (the timers run at 2 x APB1) */
#define BOARD_APB2_HZ 84000000u /* USART1, USART6 */
#define BOARD_BAUD 115200u

void board_clock_init(void);
uint32_t board_millis(void);
void board_exit(int status);
/* sleep until an interrupt (a byte, the millisecond tick) unless one is already due */
void board_idle(void);

/* USART1: the link. Receive by interrupt into a ring, transmit polled. */
void uart_init(void);
void uart_write(const uint8_t *p, uint32_t n);
/* -1 when nothing has arrived */
int uart_getc(void);
int uart_rx_empty(void);
/* bytes the USART lost before the driver read them (overrun errors seen) */
uint32_t uart_rx_overruns(void);
void usart1_irq_handler(void);
/* USART2: the profile log, transmit only */
void uart_log_puts(const char *s);
#endif
