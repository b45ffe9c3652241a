// The protocol's messages (docs/PROTOCOL.md) over a secure WebSocket, or over
// HTTPS requests with long polling where the WebSocket cannot connect: iOS
// Safari refuses wss:// to a self-signed certificate even after the page's
// own certificate was accepted. Both give the same interface:
//   const t = await connect(hello, {prefer, onMessage, onClose});
//   t.welcome; t.send(message); t.close(); t.kind === 'ws' | 'http'
// connect() rejects with an Error whose `code` is 'token-rejected',
// 'unreachable' or 'protocol'.

const WS_OPEN_TIMEOUT_MS = 4000;
const HTTP_TIMEOUT_MS = 10000;

export class TransportError extends Error {
  constructor(code, message) {
    super(message);
    this.code = code;
  }
}

function refusal(errorMessage) {
  const code = errorMessage.code === 'unauthorized' ? 'token-rejected' : 'protocol';
  return new TransportError(code, errorMessage.message || errorMessage.code);
}

function connectWebSocket(hello, { onMessage, onClose }) {
  return new Promise((resolve, reject) => {
    let ws;
    try {
      ws = new WebSocket(`${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}/ws`);
    } catch (e) {
      reject(new TransportError('unreachable', String(e)));
      return;
    }
    let welcomed = false;
    const timer = setTimeout(() => {
      ws.close();
      reject(new TransportError('unreachable', 'the WebSocket did not open'));
    }, WS_OPEN_TIMEOUT_MS);
    ws.onopen = () => ws.send(JSON.stringify(hello));
    ws.onerror = () => {};
    ws.onclose = (event) => {
      clearTimeout(timer);
      if (!welcomed) reject(new TransportError('unreachable', `the WebSocket closed (${event.code})`));
      else onClose?.(event.code, event.reason);
    };
    ws.onmessage = (event) => {
      let message;
      try {
        message = JSON.parse(event.data);
      } catch {
        return;
      }
      if (!welcomed) {
        clearTimeout(timer);
        if (message.type === 'welcome') {
          welcomed = true;
          resolve({
            kind: 'ws',
            welcome: message,
            send: (m) => ws.readyState === WebSocket.OPEN && ws.send(JSON.stringify(m)),
            close: () => ws.close(1000),
          });
        } else if (message.type === 'error') {
          welcomed = true;  // what follows is the provider's close, not a failure to connect
          reject(refusal(message));
        }
        return;
      }
      onMessage?.(message);
    };
  });
}

async function post(path, body) {
  const controller = new AbortController();
  const timer = setTimeout(() => controller.abort(), HTTP_TIMEOUT_MS);
  try {
    const response = await fetch(path, {
      method: 'POST',
      headers: { 'Content-Type': 'application/json' },
      body: JSON.stringify(body),
      cache: 'no-store',
      signal: controller.signal,
    });
    const answer = await response.json().catch(() => ({ messages: [] }));
    return { status: response.status, ...answer };
  } catch (e) {
    throw new TransportError('unreachable', `the provider did not answer (${e.message || e})`);
  } finally {
    clearTimeout(timer);
  }
}

async function connectHttp(hello, { onMessage, onClose }) {
  const first = await post('/api/hello', hello);
  const messages = first.messages || [];
  const welcome = messages.find((m) => m.type === 'welcome');
  if (!welcome || !first.session) {
    const error = messages.find((m) => m.type === 'error');
    if (error) throw refusal(error);
    throw new TransportError(first.status === 404 ? 'unreachable' : 'protocol',
                             `the provider answered ${first.status} without a welcome`);
  }
  const base = `/api/session/${first.session}`;
  let open = true;
  const end = (code) => {
    if (!open) return;
    open = false;
    onClose?.(code, '');
  };
  const deliver = (answer) => {
    for (const m of answer.messages || []) onMessage?.(m);
    if (answer.closed !== undefined || answer.status === 404) end(answer.closed ?? 1008);
  };
  // Long polling for what the provider pushes; a poll is also what keeps
  // the session from expiring.
  (async () => {
    while (open) {
      try {
        const response = await fetch(`${base}/events`, { cache: 'no-store' });
        deliver({ status: response.status, ...(await response.json().catch(() => ({}))) });
      } catch {
        if (open) await new Promise((r) => setTimeout(r, 1000));
      }
    }
  })();
  return {
    kind: 'http',
    welcome,
    send: (m) => {
      if (!open) return;
      post(base, m).then(deliver, () => {});
    },
    close: () => {
      if (!open) return;
      post(`${base}/close`, {}).catch(() => {});
      open = false;
    },
  };
}

// prefer: 'ws', 'http' or undefined (WebSocket first, then HTTPS).
export async function connect(hello, { prefer, onMessage, onClose } = {}) {
  const handlers = { onMessage, onClose };
  if (prefer === 'http') return connectHttp(hello, handlers);
  try {
    return await connectWebSocket(hello, handlers);
  } catch (e) {
    if (prefer === 'ws' || e.code === 'token-rejected' || e.code === 'protocol') throw e;
    return connectHttp(hello, handlers);
  }
}
