/* startup.c -- Cortex-M4F reset and vector table for the test firmware:
 * enable the FPU (CP10/CP11 full access), copy .data, zero .bss, run main,
 * report its status through semihosting. Any fault ends the run as FAIL. */
#include <stdint.h>
#include <string.h>

#include "semihost.h"

extern uint32_t _sidata, _sdata, _edata, _sbss, _ebss, _estack;
int main(void);

static void __attribute__((noinline)) start_c(void) {
  memcpy(&_sdata, &_sidata, (size_t)((char *)&_edata - (char *)&_sdata));
  memset(&_sbss, 0, (size_t)((char *)&_ebss - (char *)&_sbss));
  semihost_exit(main() != 0);
}

/* No floating point before the FPU is on: only integer code here. */
void Reset_Handler(void) {
  volatile uint32_t *cpacr = (volatile uint32_t *)0xE000ED88u;
  *cpacr |= 0xFu << 20;
  __asm__ volatile("dsb\n\tisb" ::: "memory");
  start_c();
}

static void Fault_Handler(void) {
  semihost_puts("FAIL: processor fault\n");
  semihost_exit(1);
}

/* Initial stack pointer, reset, then NMI .. SysTick (15 system exceptions). */
__attribute__((section(".vectors"), used)) static const void *const vectors[16] = {
    &_estack,      (const void *)Reset_Handler, (const void *)Fault_Handler,
    (const void *)Fault_Handler, (const void *)Fault_Handler, (const void *)Fault_Handler,
    (const void *)Fault_Handler, 0, 0, 0, 0,
    (const void *)Fault_Handler, (const void *)Fault_Handler, 0,
    (const void *)Fault_Handler, (const void *)Fault_Handler};
