#!/usr/bin/env node
// Opens a `matforge report` page in headless Chromium, from disk, and checks it as a reader would
// see it: every material of the manifest has its card, every finding its row (same code, same
// message, a link whose target exists in rules.html), no JavaScript error or failed load in the
// console, nothing fetched but files beside the page, paging works, the first page works with
// JavaScript off, and the first page's pictures decode. Prints one JSON line (timings included)
// and exits 1 when a check fails.
//
// Chromium is driven over the DevTools protocol on a pipe (scripts/devtools-pipe.mjs): no port,
// no network and no npm package, node and Debian's chromium are all it needs.
//
// node scripts/browser-check.mjs --page out/report/index.html --manifest out/manifest.json
//      [--screenshot docs/report.png] [--width 1280] [--height 1000] [--page-size 50]
//      [--chromium /usr/bin/chromium] [--timeout 120]
import { readFileSync, writeFileSync } from 'node:fs';
import { resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

import { startChromium } from './devtools-pipe.mjs';

const args = { width: 1280, height: 1000, chromium: '/usr/bin/chromium', timeout: 120 };
for (let i = 2; i < process.argv.length; i += 2) {
  const k = process.argv[i].replace(/^--/, ''), v = process.argv[i + 1];
  if (v === undefined) usage(`${process.argv[i]} needs a value`);
  args[k.replace(/-(.)/g, (_, c) => c.toUpperCase())] = v;
}
function usage(msg) {
  console.error(`browser-check: ${msg}\nusage: node scripts/browser-check.mjs --page INDEX.html --manifest MANIFEST.json [--screenshot PNG] [--width N] [--height N] [--chromium PATH] [--timeout S]`);
  process.exit(2);
}
if (!args.page || !args.manifest) usage('--page and --manifest are required');

const manifest = JSON.parse(readFileSync(args.manifest, 'utf8'));
const pageUrl = pathToFileURL(resolve(args.page)).href;
const rulesUrl = new URL('rules.html', pageUrl).href;
const started = performance.now();
const problems = [];

const browser = startChromium({
  name: 'browser-check', binary: args.chromium,
  flags: ['--disable-gpu', '--disable-quic', '--disable-sync', '--disable-default-apps', '--mute-audio', '--hide-scrollbars'],
});
const { send, once } = browser;
browser.child.on('error', (e) => finish(`cannot start ${args.chromium}: ${e.message} (Debian: apt-get install chromium)`));
browser.child.on('exit', (code, signal) => { if (!done) finish(`chromium exited early (${signal || code})`); });
const watchdog = setTimeout(() => finish(`no result within ${args.timeout} s`), Number(args.timeout) * 1000);

let done = false;
function finish(fatal, result = {}) {
  if (done) return;
  done = true;
  clearTimeout(watchdog);
  if (fatal) problems.push(fatal);
  result.wall_ms = Math.round(performance.now() - started);
  result.problems = problems;
  result.ok = problems.length === 0;
  console.log(JSON.stringify(result));
  if (!result.ok) {
    for (const p of problems.slice(0, 50)) console.error(`browser-check: ${p}`);
    if (fatal) console.error(browser.log.join('').split('\n').filter((l) => !/dbus|unexpected operator/.test(l)).slice(-30).join('\n'));
  }
  browser.close().then(() => process.exit(result.ok ? 0 : 1));
}

// ---- the checks ----
async function main() {
  const { targetId } = await send('Target.createTarget', { url: 'about:blank' });
  const { sessionId: s } = await send('Target.attachToTarget', { targetId, flatten: true });
  const consoleErrors = [], requests = [];
  browser.listen((m) => {
    if (m.sessionId !== s) return;
    const p = m.params;
    if (m.method === 'Runtime.consoleAPICalled' && (p.type === 'error' || p.type === 'assert' || p.type === 'warning'))
      consoleErrors.push(`console.${p.type}: ${p.args.map((a) => a.value ?? a.description).join(' ')}`);
    else if (m.method === 'Runtime.exceptionThrown')
      consoleErrors.push(`exception: ${p.exceptionDetails.exception?.description ?? p.exceptionDetails.text}`);
    else if (m.method === 'Log.entryAdded' && (p.entry.level === 'error' || p.entry.level === 'warning'))
      consoleErrors.push(`${p.entry.source} ${p.entry.level}: ${p.entry.text} ${p.entry.url ?? ''}`);
    else if (m.method === 'Network.requestWillBeSent') requests.push(p.request.url);
    else if (m.method === 'Network.loadingFailed') consoleErrors.push(`load failed: ${p.errorText}`);
  });
  for (const d of ['Runtime', 'Log', 'Page', 'Network']) await send(`${d}.enable`, {}, s);
  await send('Emulation.setDeviceMetricsOverride',
    { width: Number(args.width), height: Number(args.height), deviceScaleFactor: 1, mobile: false }, s);
  const evaluate = async (expression) => {
    const r = await send('Runtime.evaluate', { expression, returnByValue: true, awaitPromise: true }, s);
    if (r.exceptionDetails) throw new Error(`evaluate: ${r.exceptionDetails.exception?.description ?? r.exceptionDetails.text}`);
    return r.result.value;
  };
  const open = async (url) => {
    const loaded = once('Page.loadEventFired');
    const nav = await send('Page.navigate', { url }, s);
    if (nav.errorText) throw new Error(`${url}: ${nav.errorText}`);
    await loaded;
  };

  // 1. The page with JavaScript: cards, findings, timings.
  await open(pageUrl);
  const expected = manifest.materials.map((m) => ({
    name: m.name,
    findings: (m.findings || []).map((f) => ({ code: f.code, message: f.message })),
  }));
  const dom = await evaluate(`(() => {
    const nav = performance.getEntriesByType('navigation')[0];
    const cards = [...document.querySelectorAll('section.card')];
    return {
      timing: { dom_content_loaded_ms: nav.domContentLoadedEventEnd, load_ms: nav.loadEventEnd,
                html_bytes: nav.transferSize || nav.encodedBodySize || nav.decodedBodySize },
      elements: document.getElementsByTagName('*').length,
      pageSize: parseInt(document.body.getAttribute('data-page-size'), 10),
      cards: cards.map((c) => ({
        name: c.getAttribute('data-material'), id: c.id, hidden: c.hidden,
        findings: [...c.querySelectorAll('tr.finding')].map((r) => ({
          code: r.getAttribute('data-code'), text: r.textContent,
          href: r.querySelector('a') && r.querySelector('a').getAttribute('href') })),
      })),
      links: [...new Set([...document.querySelectorAll('a[href^="rules.html#"]')].map((a) => a.getAttribute('href').slice(11)))],
      pagerText: (document.querySelector('nav.pager .count') || {}).textContent || '',
    };
  })()`);
  const byName = new Map();
  for (const c of dom.cards) {
    if (byName.has(c.name)) problems.push(`two cards for material ${JSON.stringify(c.name)}`);
    byName.set(c.name, c);
  }
  let findingsChecked = 0;
  for (const m of expected) {
    const card = byName.get(m.name);
    if (!card) { problems.push(`no card for material ${JSON.stringify(m.name)}`); continue; }
    const rows = [...card.findings];
    for (const f of m.findings) {
      const i = rows.findIndex((r) => r.code === f.code && r.text.includes(f.message));
      if (i < 0) { problems.push(`${m.name}: no row for finding ${f.code} "${f.message}"`); continue; }
      if (!rows[i].href || !rows[i].href.startsWith('rules.html#')) problems.push(`${m.name}: ${f.code} does not link into rules.html`);
      rows.splice(i, 1);
      ++findingsChecked;
    }
    for (const r of rows) problems.push(`${m.name}: a finding row the manifest does not have: ${r.code}`);
  }
  if (dom.cards.length !== expected.length) problems.push(`${dom.cards.length} cards for ${expected.length} materials`);
  const per = Number(args.pageSize || dom.pageSize || 50);
  const visible = dom.cards.filter((c) => !c.hidden).length;
  if (visible !== Math.min(per, expected.length)) problems.push(`page 1 shows ${visible} cards, expected ${Math.min(per, expected.length)}`);
  if (expected.length && !dom.pagerText.includes(`${expected.length} of ${expected.length} materials`))
    problems.push(`pager says "${dom.pagerText}"`);

  // 2. The first page's pictures (contact sheet and visible cards) decode.
  const pictures = await evaluate(`(async () => {
    const imgs = [...document.querySelectorAll('img')].filter((i) => !i.closest('section.card[hidden]') &&
      (!i.closest('.sheet') || [...i.closest('.sheet').children].indexOf(i.closest('a')) < ${per}));
    for (const i of imgs) i.loading = 'eager';
    await Promise.all(imgs.map((i) => i.decode().catch(() => null)));
    return { count: imgs.length, broken: imgs.filter((i) => !(i.complete && i.naturalWidth > 0)).map((i) => i.getAttribute('src')) };
  })()`);
  for (const b of pictures.broken.slice(0, 20)) problems.push(`picture does not load: ${b}`);

  // 3. A screenshot of the top of the page, as a reader first sees it.
  if (args.screenshot) {
    await evaluate('window.scrollTo(0, 0)');
    const shot = await send('Page.captureScreenshot', { format: 'png' }, s);
    writeFileSync(args.screenshot, Buffer.from(shot.data, 'base64'));
  }

  // 4. Paging: page 2 holds the next cards; a link to the last material shows its page.
  let paging = 'one page';
  if (expected.length > per) {
    const p2 = await evaluate(`(() => {
      document.querySelector('nav.pager button[data-page="2"]').click();
      return [...document.querySelectorAll('section.card')].map((c, i) => c.hidden ? -1 : i).filter((i) => i >= 0);
    })()`);
    const want = [...Array(Math.min(per, expected.length - per)).keys()].map((i) => i + per);
    if (JSON.stringify(p2) !== JSON.stringify(want)) problems.push(`page 2 shows cards ${p2.slice(0, 5)}…, expected ${want.slice(0, 5)}…`);
    const last = dom.cards[dom.cards.length - 1];
    const shown = await evaluate(`(() => { location.hash = ${JSON.stringify('#' + last.id)};
      return new Promise((ok) => setTimeout(() => ok(!document.getElementById(${JSON.stringify(last.id)}).hidden), 50)); })()`);
    if (!shown) problems.push(`the link #${last.id} does not show its card`);
    paging = `${Math.ceil(expected.length / per)} pages checked`;
  }

  // 5. Every link into rules.html has its target.
  await open(rulesUrl);
  const missing = await evaluate(`${JSON.stringify(dom.links)}.filter((id) => !document.getElementById(decodeURIComponent(id)))`);
  for (const id of missing) problems.push(`rules.html has no #${id}`);

  // 6. JavaScript off: the page still shows its cards (all of them, hence the first page).
  await send('Emulation.setScriptExecutionDisabled', { value: true }, s);
  await open(pageUrl);
  const noJs = await evaluate(`[...document.querySelectorAll('section.card')].filter((c) => c.getClientRects().length > 0).length`);
  if (noJs < Math.min(per, expected.length)) problems.push(`without JavaScript ${noJs} cards are visible`);

  for (const e of consoleErrors) problems.push(e);
  for (const u of requests) if (!/^(file|data|about):/.test(u)) problems.push(`network request: ${u}`);
  finish(null, {
    materials: expected.length, cards: dom.cards.length, findings_checked: findingsChecked,
    rule_links: dom.links.length, pictures_checked: pictures.count, paging, cards_without_js: noJs,
    elements: dom.elements, ...dom.timing,
  });
}
main().catch((e) => finish(e.stack || String(e)));
