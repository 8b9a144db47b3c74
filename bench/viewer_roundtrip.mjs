// The viewer's relight round trip against a running `radiosity serve`: a spot swung through
// cornell-spot by POST /api/lights, ms from request to colours back (median, 90th percentile),
// the server's own relight ms, and the bytes of colours a frame.
// Usage: node bench/viewer_roundtrip.mjs BINARY [PATCHES] [MOVES]
import { startServer } from '../tests/browser/serve_process.mjs';

const [binary, patches = '10000', moves = '60'] = process.argv.slice(2);
const server = await startServer(binary, ['cornell-spot', '--patches', patches, '--cache-dir', 'none']);
try {
  // The server listens before it solves (503 until then): measure the relights, not refusals.
  while (!(await (await fetch(`${server.url}api/progress`)).json()).ready)
    await new Promise((resolve) => setTimeout(resolve, 200));
  const scene = await (await fetch(`${server.url}api/scene`)).json();
  const roundTrips = [], relights = [];
  let bytes = 0;
  for (let k = 0; k <= Number(moves); ++k) {
    const angle = 0.6 * Math.sin((2 * Math.PI * k) / 120);
    const body = JSON.stringify({ lights: [{ id: 0, direction: [Math.sin(angle), -Math.cos(angle), 0] }] });
    const start = performance.now();
    const response = await fetch(`${server.url}api/lights`, { method: 'POST', body });
    if (!response.ok) throw new Error(`POST /api/lights: HTTP ${response.status}`);
    bytes = (await response.arrayBuffer()).byteLength;
    if (k === 0) continue;  // the first move casts the rows of the nodes the beam refines
    roundTrips.push(performance.now() - start);
    relights.push(Number(response.headers.get('X-Relight-Ms')));
  }
  const at = (values, q) => [...values].sort((a, b) => a - b)[Math.min(values.length - 1, Math.floor(q * values.length))];
  const summary = await (await fetch(`${server.url}api/scene`)).json();
  console.log(JSON.stringify({
    patches: summary.patches, vertices: scene.vertices, moves: roundTrips.length, color_bytes: bytes,
    round_trip_ms: at(roundTrips, 0.5), round_trip_ms_p90: at(roundTrips, 0.9),
    relight_ms: at(relights, 0.5),
  }));
} finally {
  server.stop();
}
