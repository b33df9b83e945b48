/* semihost.h -- ARM semihosting (the debugger or QEMU does the I/O): print a
 * string, and end the program with a pass/fail status. No C library stdio. */
#ifndef RTB_EMBEDDED_SEMIHOST_H
#define RTB_EMBEDDED_SEMIHOST_H

void semihost_puts(const char *s);               /* SYS_WRITE0 */
void semihost_exit(int failed) __attribute__((noreturn)); /* SYS_EXIT */

/* Small formatters into the console (no printf on the target). */
void print_int(long v);
void print_sci(double v);   /* 3 significant digits, e.g. 1.23e-05 */

#endif
