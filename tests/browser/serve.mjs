// What both browser tests start: a `rover` server (its port read from the
// URL it prints) and headless Chromium with software WebGL.
import { spawn } from 'node:child_process';
import { chromium } from 'playwright-core';

// Start `rover args…` and wait for the port it prints; `{ server, port }`.
export async function startRover(rover, args) {
  const server = spawn(rover, args, { stdio: ['ignore', 'ignore', 'pipe'] });
  const port = await new Promise((resolve, reject) => {
    let err = '';
    const timer = setTimeout(() => reject(new Error(`no port printed: ${err}`)), 60000);
    server.stderr.on('data', (d) => {
      err += d;
      const m = /127\.0\.0\.1:(\d+)/.exec(err);
      if (m) { clearTimeout(timer); resolve(Number(m[1])); }
    });
    server.on('exit', (code) => reject(new Error(`rover ${args[0]} exited (${code}): ${err}`)));
  });
  return { server, port };
}

// Headless Chromium; a headless machine has no GPU: software WebGL.
export function launchBrowser(browserPath) {
  return chromium.launch({
    executablePath: browserPath,
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'],
  });
}
