// How long a page takes to open in headless Chromium, in real time: from the navigation until the previs
// page says it is ready (body data-state), through the DevTools protocol. Prints seconds per run.
//   node --experimental-websocket open_time.mjs CHROMIUM PAGE.html [RUNS]
import { spawn } from 'node:child_process';
import { mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';

const [chromium, page, runs = '3'] = process.argv.slice(2);
const profile = mkdtempSync(join(tmpdir(), 'previs-'));
const browser = spawn(chromium, ['--headless', '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader',
  '--window-size=1600,900', `--user-data-dir=${profile}`, '--remote-debugging-port=0', 'about:blank'],
  { stdio: ['ignore', 'ignore', 'pipe'] });
const endpoint = await new Promise((ok) => {
  let text = '';
  browser.stderr.on('data', (d) => {
    text += d;
    const m = text.match(/DevTools listening on (ws:\/\/\S+)/);
    if (m) ok(m[1]);
  });
});
const socket = new WebSocket(endpoint);
await new Promise((ok) => socket.addEventListener('open', ok));
let next = 0;
const waiting = new Map();
socket.addEventListener('message', (e) => {
  const m = JSON.parse(e.data);
  if (waiting.has(m.id)) { waiting.get(m.id)(m); waiting.delete(m.id); }
});
const send = (method, params = {}, sessionId) => new Promise((ok) => {
  const id = ++next;
  waiting.set(id, ok);
  socket.send(JSON.stringify({ id, method, params, sessionId }));
});
const url = 'file://' + resolve(page);
for (let r = 0; r < Number(runs); ++r) {
  // A new tab each run, as a person opening the file: nothing of the previous run left in the renderer.
  const { result: { targetId } } = await send('Target.createTarget', { url: 'about:blank' });
  const { result: { sessionId } } = await send('Target.attachToTarget', { targetId, flatten: true });
  const start = performance.now();
  await send('Page.navigate', { url }, sessionId);
  let state = '';
  while (state !== 'ready' && state !== 'error' && performance.now() - start < 60000) {
    await new Promise((ok) => setTimeout(ok, 20));
    const m = await send('Runtime.evaluate', { expression: 'document.body ? document.body.dataset.state : ""' },
                         sessionId);
    state = m.result?.result?.value ?? '';
  }
  const timing = await send('Runtime.evaluate', { expression: 'document.body.dataset.timing' }, sessionId);
  console.log(`${((performance.now() - start) / 1000).toFixed(2)} s ${state} (module, mesh, first picture at ` +
              `${timing.result?.result?.value} ms)`);
  await send('Target.closeTarget', { targetId });
}
socket.close();
browser.kill();
await new Promise((ok) => browser.on('exit', ok));
rmSync(profile, { recursive: true, force: true });
