// Headless Chromium driven over the DevTools protocol on a pipe (--remote-debugging-pipe: JSON
// messages separated by NUL on file descriptors 3 and 4), so there is no port, no network and no
// npm package: node and Debian's chromium are all it needs. Used by scripts/browser-check.mjs,
// tests/texture/checkers/mtlx_render.mjs and godot_load.mjs.
//
//   const browser = startChromium({ name, flags, binary });
//   await browser.send(method, params, sessionId)  // the result; rejects naming the method on an error
//   await browser.once(method)                     // the params of the next such event
//   browser.listen((message) => ...)               // every event
//   browser.log                                    // Chromium's stdout and stderr, in chunks
//   await browser.close()                          // see close()
//   const page = await openPage(browser, url)      // a new tab at url: { sessionId, evaluate, waitFor }
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';

// WebGL 2 in headless Chromium without a GPU: SwiftShader, through ANGLE.
export const WEBGL_FLAGS = ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist'];

// `name` prefixes the profile folder and the messages; `flags` come after the common ones.
export function startChromium({ name = 'chromium', flags = [], binary = '/usr/bin/chromium' } = {}) {
  const profile = mkdtempSync(join(tmpdir(), `matforge-${name}-`));
  const child = spawn(binary, [
    '--headless', '--no-sandbox', '--no-first-run', '--disable-background-networking',
    '--disable-component-update', '--disable-extensions', ...flags,
    '--remote-debugging-pipe', `--user-data-dir=${profile}`, 'about:blank',
  ], { stdio: ['ignore', 'pipe', 'pipe', 'pipe', 'pipe'], detached: true });  // its own process group
  const log = [];
  child.stdout.on('data', (d) => log.push(String(d)));
  child.stderr.on('data', (d) => log.push(String(d)));

  const to = child.stdio[3], from = child.stdio[4];
  // A Chromium that failed to start or died closes the pipe: a write then fails (EPIPE), which
  // is the caller's to report (its 'error' and 'exit' handlers on `child`), never a crash here.
  child.on('error', (e) => log.push(`${name}: ${e.message}\n`));
  to.on('error', (e) => log.push(`${name}: pipe: ${e.message}\n`));
  from.on('error', (e) => log.push(`${name}: pipe: ${e.message}\n`));
  let nextId = 0, pending = '';
  const waiting = new Map(), listeners = new Set();
  from.on('data', (chunk) => {
    pending += chunk.toString('utf8');
    for (let end; (end = pending.indexOf('\0')) >= 0;) {
      const msg = JSON.parse(pending.slice(0, end));
      pending = pending.slice(end + 1);
      if (msg.id !== undefined && waiting.has(msg.id)) {
        const { ok, reject, method } = waiting.get(msg.id);
        waiting.delete(msg.id);
        if (msg.error) reject(new Error(`${method}: ${msg.error.message}`));
        else ok(msg.result);
      } else {
        for (const l of listeners) l(msg);
      }
    }
  });
  function send(method, params = {}, sessionId) {
    return new Promise((ok, reject) => {
      const msg = { id: ++nextId, method, params };
      if (sessionId) msg.sessionId = sessionId;
      waiting.set(msg.id, { ok, reject, method });
      to.write(JSON.stringify(msg) + '\0');
    });
  }
  function once(method) {
    return new Promise((ok) => {
      const l = (m) => { if (m.method === method) { listeners.delete(l); ok(m.params); } };
      listeners.add(l);
    });
  }
  // Chromium closed first (Browser.close: it ends its helper processes, which write under the
  // profile as they go), its process group killed when it has not gone within 3 s, then the
  // profile removed, with retries. Resolves once all of that is done.
  function close() {
    return new Promise((done) => {
      let started = false;
      const cleanup = () => {
        if (started) return;
        started = true;
        try { process.kill(-child.pid, 'SIGKILL'); } catch { /* gone */ }
        setTimeout(() => {
          try {
            rmSync(profile, { recursive: true, force: true, maxRetries: 10, retryDelay: 100 });
          } catch (e) {
            console.error(`${name}: ${profile} left behind: ${e.message}`);
          }
          done();
        }, 200);
      };
      if (child.exitCode !== null || child.signalCode !== null) return cleanup();
      child.once('exit', cleanup);
      setTimeout(cleanup, 3000);
      try { to.write(JSON.stringify({ id: ++nextId, method: 'Browser.close' }) + '\0'); } catch { /* gone */ }
    });
  }
  return { child, log, send, once, listen: (fn) => listeners.add(fn), close };
}

// A new tab on `url` with the Runtime domain on: `evaluate(expression)` awaits a promise and returns
// its value by value (throwing what the page threw), `waitFor(expression)` polls it every 100 ms
// until it is true, up to 20 s.
export async function openPage(browser, url) {
  const { targetId } = await browser.send('Target.createTarget', { url: 'about:blank' });
  const { sessionId } = await browser.send('Target.attachToTarget', { targetId, flatten: true });
  await browser.send('Runtime.enable', {}, sessionId);
  await browser.send('Page.navigate', { url }, sessionId);
  const evaluate = async (expression) => {
    const r = await browser.send('Runtime.evaluate', { expression, awaitPromise: true, returnByValue: true }, sessionId);
    if (r.exceptionDetails) throw new Error(JSON.stringify(r.exceptionDetails).slice(0, 600));
    return r.result.value;
  };
  const waitFor = async (expression) => {
    for (let i = 0; i < 200 && !(await evaluate(expression)); ++i) await new Promise((r) => setTimeout(r, 100));
  };
  return { sessionId, evaluate, waitFor };
}
