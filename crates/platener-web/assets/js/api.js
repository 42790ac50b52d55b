// Small wrappers over the web API (../shared/spec/api.md), shared by every module of the page.
// Every failure becomes an ApiError carrying the server's sentence, so callers can show it as is.

/** An API failure: `code` from the error body (or "network"), `message` a sentence for people. */
export class ApiError extends Error {
  constructor(status, code, message) {
    super(message);
    this.status = status;
    this.code = code;
  }
}

/** Turns a non-2xx response into an ApiError with the server's message. */
async function failure(response) {
  let code = 'http_' + response.status;
  let message = `The server answered ${response.status}.`;
  try {
    const body = await response.json();
    if (body && body.error) {
      code = body.error.code || code;
      message = body.error.message || message;
    }
  } catch (_) {
    // Not JSON: keep the generic sentence.
  }
  return new ApiError(response.status, code, message);
}

/** fetch() that throws ApiError on network errors and non-2xx answers. */
export async function request(url, options = {}) {
  let response;
  try {
    response = await fetch(url, options);
  } catch (_) {
    throw new ApiError(0, 'network', 'The server cannot be reached. Is `platener serve` running?');
  }
  if (!response.ok) throw await failure(response);
  return response;
}

export async function getJson(url) {
  return (await request(url)).json();
}

export async function getText(url) {
  return (await request(url)).text();
}

export async function getBuffer(url) {
  return (await request(url)).arrayBuffer();
}

/** POST /api/conversions with the model file and settings; the answer holds the delete token. */
export async function upload(file, settings) {
  const form = new FormData();
  for (const [key, value] of Object.entries(settings)) {
    const name = key === 'thicknesses' ? 'thickness' : key;
    if (value == null) continue; // auto: the server's default
    for (const v of Array.isArray(value) ? value : [value]) form.append(name, String(v));
  }
  form.append('model', file, file.name);
  return (await request('/api/conversions', { method: 'POST', body: form })).json();
}

export function conversion(id) {
  return getJson(`/api/conversions/${encodeURIComponent(id)}`);
}

/** POST …/recut with changed settings: a new conversion (with its own delete token). */
export async function recut(id, changes) {
  const r = await request(`/api/conversions/${encodeURIComponent(id)}/recut`, {
    method: 'POST',
    headers: { 'content-type': 'application/json' },
    body: JSON.stringify(changes),
  });
  return r.json();
}

/** POST …/cancel with the delete token: the conversion, now cancelled (the methods that
 * ended before stay). */
export async function cancel(id, token) {
  const r = await request(`/api/conversions/${encodeURIComponent(id)}/cancel`, {
    method: 'POST',
    headers: { authorization: `Bearer ${token}` },
  });
  return r.json();
}

export async function publish(id, token) {
  const r = await request(`/api/conversions/${encodeURIComponent(id)}/publish`, {
    method: 'POST',
    headers: { authorization: `Bearer ${token}` },
  });
  return r.status;
}

/** DELETE …/publish: takes the conversion out of the gallery again (same token). */
export async function unpublish(id, token) {
  const r = await request(`/api/conversions/${encodeURIComponent(id)}/publish`, {
    method: 'DELETE',
    headers: { authorization: `Bearer ${token}` },
  });
  return r.status;
}

export function gallery(page) {
  return getJson(`/api/gallery?page=${page}`);
}

/** The test strip's holes; `kerf` (the plan's, when known) is starred in its table. */
export function stripJson(thickness, material, kerf) {
  return getJson(`/api/test-strip.json?${stripQuery(thickness, material, kerf)}`);
}

export function stripSvgUrl(thickness, material, kerf) {
  return `/api/test-strip.svg?${stripQuery(thickness, material, kerf)}`;
}

function stripQuery(thickness, material, kerf) {
  const q = { thickness: String(thickness), material };
  if (kerf != null) q.kerf = String(kerf);
  return new URLSearchParams(q).toString();
}

/**
 * Follows a conversion's event stream. `on(kind, data)` gets `step`, `model` (the model scene
 * is stored), `method` (a method ended; its files are stored), `retry` (a worker stopped: the
 * job runs again from the start), `done`, `failed` and `cancelled` with their parsed data;
 * the stream closes itself after the last one. Returns a function that closes it early.
 */
export function events(id, on) {
  const source = new EventSource(`/api/conversions/${encodeURIComponent(id)}/events`);
  const last = new Set(['done', 'failed', 'cancelled']);
  for (const kind of ['step', 'model', 'method', 'retry', 'done', 'failed', 'cancelled']) {
    source.addEventListener(kind, (e) => {
      let data = {};
      try {
        data = JSON.parse(e.data);
      } catch (_) {
        // Keep {}: the kind alone still tells the page what happened.
      }
      if (last.has(kind)) source.close();
      on(kind, data);
    });
  }
  source.onerror = () => {
    // The server closes the stream after the last event; reconnecting would replay it.
    if (source.readyState !== EventSource.CLOSED) {
      source.close();
      on('lost', {});
    }
  };
  return () => source.close();
}

/** Delete tokens of the user's own conversions, kept in localStorage (id → token). */
export const tokens = {
  key: 'platener.tokens',
  all() {
    try {
      return JSON.parse(localStorage.getItem(this.key) || '{}') || {};
    } catch (_) {
      return {};
    }
  },
  get(id) {
    return this.all()[id] || null;
  },
  set(id, token) {
    const all = this.all();
    all[id] = token;
    localStorage.setItem(this.key, JSON.stringify(all));
  },
};
