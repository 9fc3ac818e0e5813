// bench/ceiling.c's loop in JavaScript: V8's optimised code against the C compiler's on the
// same machine. node bench/alu.mjs [ITERATIONS]
const n = Number(process.argv[2] ?? 400000000);
const t0 = performance.now();
let x = 1.000001,
  y = 0.5,
  s = 0;
for (let i = 0; i < n; i++) {
  x = x * 1.0000001 + 1e-9;
  y = Math.sqrt(y * y + x) * 0.5;
  s += y;
}
console.log(((performance.now() - t0) / 1000).toFixed(4), s);
