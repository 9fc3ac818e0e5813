// Runs before `npm test`: the browser tests drive Debian's Chromium
// (Playwright cannot download its own browser here). Installs it with apt
// when it is missing and we are root; otherwise says what to do.
import { execFileSync } from 'node:child_process';
import { existsSync } from 'node:fs';

const CHROMIUM = '/usr/bin/chromium';
if (!existsSync(CHROMIUM)) {
  const root = typeof process.getuid === 'function' && process.getuid() === 0;
  if (!root) {
    process.stderr.write(
      `pathwise tests need Chromium at ${CHROMIUM}: run \`sudo apt-get install -y chromium\`\n`,
    );
    process.exit(1);
  }
  process.stderr.write('installing Debian chromium for the browser tests…\n');
  const env = { ...process.env, DEBIAN_FRONTEND: 'noninteractive' };
  execFileSync('apt-get', ['update'], { stdio: 'inherit', env });
  execFileSync('apt-get', ['install', '-y', '--no-install-recommends', 'chromium'], {
    stdio: 'inherit',
    env,
  });
}
