// `radiosity serve` as a child process for the browser test and the viewer benchmark: started on
// a free port, its URL read from what it prints.
import { spawn } from 'node:child_process';

export async function startServer(binary, args) {
  const server = spawn(binary, ['serve', ...args, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  const url = await new Promise((resolve, reject) => {
    let text = '';
    const timer = setTimeout(() => reject(new Error(`no URL printed: ${text}`)), 300000);
    const read = (chunk) => {
      text += chunk;
      const match = text.match(/http:\/\/127\.0\.0\.1:\d+\//);
      if (match) { clearTimeout(timer); resolve(match[0]); }
    };
    server.stdout.on('data', read);
    server.stderr.on('data', read);
    server.on('exit', (code) => reject(new Error(`server exited (${code}): ${text}`)));
  });
  return { url, stop: () => server.kill('SIGINT') };
}
