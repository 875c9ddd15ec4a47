// `rover drive` in Foxglove's live protocol (docs/VIEW.md), with the
// protocol's own client (@foxglove/ws-protocol over `ws`): it connects
// under the subprotocol foxglove.websocket.v1, finds the channels with
// their schemas, subscribes to the transforms and the row, publishes a
// speed command on a channel of its own, and receives a transform for
// every step of the loop while the rover moves. Then the bad input: text
// that is no operation, a subscription to a channel that does not exist
// and a message on a channel never advertised are each answered with an
// error status, and the transforms keep coming; a foreign page's Origin
// and a client without the token are refused at the handshake.
//
// node foxglove.mjs <rover binary>
import wsProtocol from '@foxglove/ws-protocol';
import WebSocket from 'ws';
import { startRover } from './serve.mjs';

const { FoxgloveClient } = wsProtocol;

const [rover] = process.argv.slice(2);
let failures = 0, checks = 0;
const check = (ok, msg) => { checks++; if (!ok) { failures++; console.error(`FAIL: ${msg}`); } };
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

const RATE = 500;
const TOKEN = 'foxglove-test-token-0123456789';
const { server, port } = await startRover(rover, ['drive', 'swing4', '--port', '0', '--rate', String(RATE), '--token', TOKEN]);
const url = `ws://127.0.0.1:${port}/?token=${TOKEN}`;

// The handshake's answer to a WebSocket with `headers`: 'open' or the HTTP status.
function handshake(target, headers) {
  return new Promise((resolve) => {
    const ws = new WebSocket(target, [FoxgloveClient.SUPPORTED_SUBPROTOCOL], { headers });
    ws.on('open', () => { ws.close(); resolve('open'); });
    ws.on('unexpected-response', (_req, res) => resolve(res.statusCode));
    ws.on('error', () => resolve('error'));
  });
}

try {
  const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
  const channels = new Map();
  const statuses = [];
  let serverInfo = null;
  client.on('serverInfo', (info) => { serverInfo = info; });
  client.on('status', (s) => statuses.push(s));
  client.on('advertise', (list) => { for (const c of list) channels.set(c.topic, c); });
  const received = { tf: [], row: [], rover: 0, terrain: 0 };
  const subs = new Map();
  client.on('message', ({ subscriptionId, timestamp, data }) => {
    const topic = subs.get(subscriptionId);
    const wall = performance.now();
    if (topic === '/tf') received.tf.push({ t: timestamp, wall, bytes: data.byteLength, body: Buffer.from(data.buffer, data.byteOffset, data.byteLength).includes('body') });
    else if (topic === '/row') received.row.push({ t: timestamp, row: JSON.parse(new TextDecoder().decode(data)) });
    else if (topic === '/rover') received.rover++;
    else if (topic === '/terrain') received.terrain++;
  });
  const deadline = Date.now() + 30000;
  while (channels.size < 4 && Date.now() < deadline) await sleep(20);
  check(serverInfo && serverInfo.capabilities.includes('clientPublish') && serverInfo.capabilities.includes('time'),
    `serverInfo: ${JSON.stringify(serverInfo)}`);
  const expected = { '/tf': 'foxglove.FrameTransforms', '/row': 'rover.Row', '/rover': 'foxglove.SceneUpdate', '/terrain': 'foxglove.SceneUpdate' };
  for (const [topic, schema] of Object.entries(expected)) {
    const c = channels.get(topic);
    check(c && c.schemaName === schema && c.schema.length > 0, `channel ${topic}: ${JSON.stringify(c && { ...c, schema: c.schema.length })}`);
  }
  for (const topic of Object.keys(expected)) {
    const c = channels.get(topic);
    if (c) subs.set(client.subscribe(c.id), topic);
  }
  // Drive: a speed command on a channel of the client's own.
  const cmd = client.advertise({ topic: '/cmd', encoding: 'json', schemaName: 'rover.Command' });
  await sleep(300);
  client.sendMessage(cmd, new TextEncoder().encode(JSON.stringify({ speed: 0.2 })));
  await sleep(2500);
  const tf = received.tf.slice(received.tf.length > 500 ? received.tf.length - 500 : 0);
  check(received.rover === 1 && received.terrain === 1, `one /rover and one /terrain message, got ${received.rover} and ${received.terrain}`);
  check(tf.length >= 100, `only ${tf.length} transforms`);
  // One transform a step: consecutive stamps one step apart (2 ms at 500 Hz)...
  const step = BigInt(Math.round(1e9 / RATE));
  let oneStep = 0;
  for (let i = 1; i < tf.length; i++) if (tf[i].t - tf[i - 1].t === step) oneStep++;
  check(oneStep >= 0.95 * (tf.length - 1), `${oneStep} of ${tf.length - 1} consecutive transforms one step (${step} ns) apart`);
  // ...and as many a second of wall-clock time as the loop's rate.
  const wallS = (tf[tf.length - 1].wall - tf[0].wall) / 1000;
  const rate = (tf.length - 1) / wallS;
  check(rate > 0.8 * RATE && rate < 1.2 * RATE, `transforms at ${rate.toFixed(0)} per second, the loop at ${RATE}`);
  console.log(`foxglove: ${tf.length} transforms at ${rate.toFixed(0)} per second (loop ${RATE} Hz), ${oneStep} one step apart`);
  check(tf.every((m) => m.body && m.bytes > 100), 'a transform message without the body frame');
  const rows = received.row;
  const first = rows[0].row, last = rows[rows.length - 1].row;
  check(last.X - first.X > 0.05, `the rover did not move: X ${first.X} → ${last.X}`);
  check(last.V_set === 0.2, `the published command is not in force: V_set = ${last.V_set}`);
  check(rows.every((r) => r.t === BigInt(Math.round(r.row.t * 1e9))), 'a row stamped with another time than its t');

  // Bad input on a raw connection of the same protocol: error statuses,
  // and the transforms go on.
  const raw = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  const answers = [];
  raw.on('message', (data, binary) => { if (!binary) answers.push(JSON.parse(data.toString())); });
  await new Promise((r) => raw.on('open', r));
  raw.send('{not json');
  raw.send(JSON.stringify({ op: 'subscribe', subscriptions: [{ id: 7, channelId: 99 }] }));
  raw.send(JSON.stringify({ op: 'fly' }));
  raw.send(Buffer.from([1, 42, 0, 0, 0, 123]));
  const before = received.tf.length;
  await sleep(800);
  const errors = answers.filter((m) => m.op === 'status' && m.level === 2).map((m) => m.message);
  check(errors.length === 4, `error statuses: ${JSON.stringify(errors)}`);
  check(errors.some((m) => m.includes('no channel 99')), `no status naming channel 99: ${JSON.stringify(errors)}`);
  check(errors.some((m) => m.includes('client channel 42')), `no status naming client channel 42: ${JSON.stringify(errors)}`);
  check(received.tf.length - before > 100, `the transforms stopped after the bad input: ${received.tf.length - before} in 0.8 s`);
  raw.close();
  // The client's own bad command: a status, the drive goes on.
  client.sendMessage(cmd, new TextEncoder().encode(JSON.stringify({ speed: 'fast' })));
  await sleep(300);
  check(statuses.some((s) => s.level === 2 && s.message.startsWith('/cmd:')), `no status for a bad command: ${JSON.stringify(statuses)}`);
  client.close();

  // Who may connect: the drive's own rules.
  check(await handshake(url, { Origin: 'http://evil.example' }) === 403, 'a foreign Origin was not refused with 403');
  check(await handshake(`ws://127.0.0.1:${port}/`, {}) === 401, 'a client without the token was not refused with 401');
  check(await handshake(url, { Host: `rebound.example:${port}` }) === 421, 'a foreign Host was not refused with 421');
} catch (e) {
  failures++;
  console.error(`FAIL: ${e.stack || e}`);
} finally {
  server.kill('SIGINT');
}
console.log(`foxglove: ${checks - (failures > checks ? checks : failures)} passed, ${failures} failed`);
process.exitCode = failures ? 1 : 0;
