// The assembly steps beside the 3D player (issue 35): report.json's `assembly_steps`, the
// same steps as the ZIP's assembly.html and assembly.pdf tell, each a button that shows the
// assembly up to the parts it adds.

/**
 * Fills `list` (an <ol>) with `steps`; `pick(k, n)` shows the first k parts of the order (the
 * parts of the steps so far), the step's own n parts last. `link` (an <a>) opens the
 * instructions' page when the plan has one (`href`), and is hidden otherwise.
 */
export function showSteps(list, steps, link, href, pick) {
  list.replaceChildren();
  let shown = 0;
  for (const step of steps || []) {
    const own = (step.parts || []).length;
    shown += own;
    const upTo = shown;
    const li = document.createElement('li');
    const button = document.createElement('button');
    button.type = 'button';
    button.className = 'step-pick';
    button.dataset.step = String(step.number);
    button.textContent = `Step ${step.number}`;
    button.addEventListener('click', () => pick(upTo, own));
    li.append(button, ` ${(step.lines || []).join(' ')}`);
    list.append(li);
  }
  list.hidden = !list.children.length;
  link.hidden = !href;
  if (href) link.href = href;
}
