/*
 * Vector table for the Cortex-M4 build. The core loads the initial stack pointer and the reset
 * vector from address 0; reset goes straight to newlib's rdimon C runtime (_start), which
 * clears .bss, sets up semihosting stdio and calls main(). Faults stop the CPU in a loop the
 * QEMU timeout then ends, rather than running on with corrupt state.
 */
#include <stdint.h>

extern void _start(void);
extern uint32_t __stack_top;

static void fault_handler(void) {
  for (;;) {
  }
}

typedef void (*vector_fn)(void);

__attribute__((section(".vectors"), used)) static const vector_fn vectors[16] = {
    (vector_fn)(uintptr_t)&__stack_top, /* initial main stack pointer */
    _start,                             /* reset */
    fault_handler,                      /* NMI */
    fault_handler,                      /* hard fault */
    fault_handler,                      /* memory management fault */
    fault_handler,                      /* bus fault */
    fault_handler,                      /* usage fault */
    0,
    0,
    0,
    0,
    fault_handler, /* SVCall */
    fault_handler, /* debug monitor */
    0,
    fault_handler, /* PendSV */
    fault_handler, /* SysTick */
};
