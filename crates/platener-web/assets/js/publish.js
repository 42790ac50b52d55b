// Publishing the user's own conversion to the gallery, and taking it out again. Publishing shows
// a model to everyone, so it asks first (publish-dialog); Unpublish undoes it with the same
// delete token (kept in localStorage for the user's own conversions, see api.tokens).

import * as api from './api.js';

const $ = (id) => document.getElementById(id);

/** Shows Publish or Unpublish for conversion `c` (null: neither): only for a conversion with a
 * plan whose delete token this browser holds. */
export function showPublishing(c) {
  const own = !!(c && c.best && api.tokens.get(c.id));
  $('publish').hidden = !own || !!c.published;
  $('unpublish').hidden = !own || !c.published;
  $('publish').disabled = false;
  $('unpublish').disabled = false;
}

/**
 * Binds the two buttons and the dialog: `conversion()` is the open conversion, `onChange()`
 * runs after it entered or left the gallery, `onError(message)` says what failed.
 */
export function bindPublishing({ conversion, onChange, onError }) {
  $('publish').addEventListener('click', () => {
    const c = conversion();
    if (!c) return;
    $('publish-question').textContent =
      `Everyone will see ${c.model.name} in the gallery and can download its plan.`;
    $('publish-dialog').returnValue = '';
    $('publish-dialog').showModal();
  });
  $('publish-dialog').addEventListener('close', () => {
    if ($('publish-dialog').returnValue === 'publish') change(true);
  });
  $('unpublish').addEventListener('click', () => change(false));

  /** Publishes (`on`) or unpublishes the open conversion. */
  async function change(on) {
    const c = conversion();
    const token = c && api.tokens.get(c.id);
    if (!token) return;
    const button = on ? $('publish') : $('unpublish');
    button.disabled = true;
    try {
      if (on) await api.publish(c.id, token);
      else await api.unpublish(c.id, token);
      c.published = on;
      showPublishing(c);
      onChange();
    } catch (e) {
      button.disabled = false;
      onError(`${on ? 'Publishing' : 'Unpublishing'} failed: ${e.message}`);
    }
  }
}
