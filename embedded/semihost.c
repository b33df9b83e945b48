/* semihost.c -- ARM semihosting calls (bkpt 0xAB on M-profile) and number
 * formatting for the test firmware. QEMU serves them with
 * `-semihosting-config enable=on,target=native`. */
#include "semihost.h"

enum { SYS_WRITE0 = 0x04, SYS_EXIT = 0x18 };
enum { ADP_STOPPED_APPLICATION_EXIT = 0x20026, ADP_STOPPED_RUN_TIME_ERROR = 0x20023 };

static int semihost_call(int op, const void *arg) {
  register int r0 __asm__("r0") = op;
  register const void *r1 __asm__("r1") = arg;
  __asm__ volatile("bkpt 0xAB" : "+r"(r0) : "r"(r1) : "memory");
  return r0;
}

void semihost_puts(const char *s) { semihost_call(SYS_WRITE0, s); }

void semihost_exit(int failed) {
  /* 32-bit semihosting: the reason code itself is the argument. QEMU exits
   * with status 0 for ApplicationExit and 1 otherwise. */
  semihost_call(SYS_EXIT, (const void *)(failed ? ADP_STOPPED_RUN_TIME_ERROR
                                               : ADP_STOPPED_APPLICATION_EXIT));
  for (;;) {}
}

void print_int(long v) {
  char buf[24];
  int i = sizeof buf - 1;
  buf[i] = '\0';
  unsigned long u = v < 0 ? -(unsigned long)v : (unsigned long)v;
  do { buf[--i] = (char)('0' + u % 10); u /= 10; } while (u && i > 1);
  if (v < 0) buf[--i] = '-';
  semihost_puts(&buf[i]);
}

void print_sci(double v) {
  if (v != v) { semihost_puts("nan"); return; }
  if (v < 0) { semihost_puts("-"); v = -v; }
  if (v == 0.0) { semihost_puts("0"); return; }
  if (v > 1e300) { semihost_puts("inf"); return; }
  int e = 0;
  while (v >= 10.0) { v /= 10.0; ++e; }
  while (v < 1.0) { v *= 10.0; --e; }
  long m = (long)(v * 100.0 + 0.5); /* 3 digits */
  if (m >= 1000) { m /= 10; ++e; }
  char s[8] = {(char)('0' + m / 100), '.', (char)('0' + (m / 10) % 10), (char)('0' + m % 10),
               'e', e < 0 ? '-' : '+', '\0', '\0'};
  semihost_puts(s);
  const int ae = e < 0 ? -e : e;
  if (ae < 10) semihost_puts("0");
  print_int(ae);
}
