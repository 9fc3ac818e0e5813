/* The machine's scaling ceiling for compute-bound code: a dependent chain of
   double-precision multiply-adds and square roots (no memory traffic), timed
   in n independent processes started together. Prints seconds. */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <time.h>
int main(int argc, char **argv) {
  long n = argc > 1 ? atol(argv[1]) : 400000000L;
  struct timespec a, b;
  clock_gettime(CLOCK_MONOTONIC, &a);
  double x = 1.000001, y = 0.5, s = 0;
  for (long i = 0; i < n; i++) {
    x = x * 1.0000001 + 1e-9;
    y = sqrt(y * y + x) * 0.5;
    s += y;
  }
  clock_gettime(CLOCK_MONOTONIC, &b);
  printf("%.4f %g\n", (b.tv_sec - a.tv_sec) + 1e-9 * (b.tv_nsec - a.tv_nsec), s);
  return 0;
}
