// Following a conversion while it runs: its events into the step log (progress.js) and the
// method bars (bars.js), the conversion fetched again whenever something landed (the model
// scene, a method's plan), its place in the queue while it waits, and its end.

import * as api from './api.js';
import * as progress from './progress.js';
import { barStep, barMethod, clearBars, stepPhrase } from './bars.js';

const ENDED = new Set(['done', 'failed', 'cancelled']);
/** How often a queued conversion's place is asked for (the stream says nothing while queued). */
const QUEUE_POLL_MS = 1000;

/** "waiting for a free worker (2 ahead)". */
export function waitingText(c) {
  const ahead = c.queue_ahead;
  return `Waiting for a free worker${ahead != null ? ` (${ahead} ahead)` : ''}…`;
}

/**
 * Follows conversion `c` (its JSON, status queued or running) until it ends. `still()` says
 * whether the page still shows it; `landed(c, method)` gets the conversion fetched again after
 * the model scene (`method` null) or a method landed; `ended(c)` gets it once ended. Answers
 * to fetches older than one already handed on are dropped, so a slow answer never takes back
 * what a newer one showed. Returns a function that stops following.
 */
export function follow(c, { state, still, landed, ended }) {
  const id = c.id;
  let stopped = false;
  let close = () => {};
  let asked = 0;
  let handed = 0;
  let sharedSaid = false; // the status line says a shared step (reading the model)
  const live = () => !stopped && still();

  async function fetchNewest() {
    const n = ++asked;
    const fresh = await api.conversion(id);
    if (!live() || n < handed) return null;
    handed = n;
    return fresh;
  }

  async function land(method) {
    try {
      const fresh = await fetchNewest();
      if (fresh) landed(fresh, method);
    } catch (e) {
      progress.showError(e.message);
    }
  }

  /** After the last event (or a lost stream): the conversion as it is now. A stream lost while
   * the job still runs (a restarting server) is followed again a moment later. */
  async function reload() {
    try {
      const fresh = await fetchNewest();
      if (!fresh) return;
      if (ENDED.has(fresh.status)) return ended(fresh);
      setTimeout(() => live() && listen(), 2000);
    } catch (e) {
      progress.showError(e.message);
    }
  }

  function onEvent(kind, data) {
    if (!live()) return;
    if (kind === 'step') {
      if (state.status === 'queued') state.status = 'running';
      progress.stepEvent(data);
      barStep(data);
      if (!data.method && data.state === 'started') {
        progress.status(`${stepPhrase(data)}…`);
        sharedSaid = true;
      } else if (data.method && sharedSaid) {
        progress.status(`Converting ${c.model.name}…`);
        sharedSaid = false;
      }
    } else if (kind === 'model') {
      land(null);
    } else if (kind === 'method') {
      progress.methodEvent(data);
      barMethod(data);
      land(data.method);
    } else if (kind === 'retry') {
      clearBars();
      progress.status('The worker stopped; converting again from the start…');
    } else if (ENDED.has(kind) || kind === 'lost') {
      reload();
    }
  }

  function listen() {
    close = api.events(id, onEvent);
  }

  async function pollQueue() {
    if (!live() || state.status !== 'queued') return;
    try {
      const fresh = await fetchNewest();
      if (!fresh || state.status !== 'queued') return;
      if (fresh.status === 'queued') progress.status(waitingText(fresh));
      else if (!ENDED.has(fresh.status)) state.status = fresh.status;
    } catch (_) {
      // The stream still follows the job; the place in the queue is only a courtesy.
    }
    setTimeout(pollQueue, QUEUE_POLL_MS);
  }

  listen();
  if (c.status === 'queued') {
    progress.status(waitingText(c));
    setTimeout(pollQueue, QUEUE_POLL_MS);
  }
  return () => {
    stopped = true;
    close();
  };
}
