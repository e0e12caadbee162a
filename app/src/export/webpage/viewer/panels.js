// The page's controls as DOM: the structure list (grouped as the window's model list, show and
// hide per structure and per group), the six views, the variant choice, the removed piece's
// opacity, the metrics table, the footer with the data's attribution. Names from the session are
// inserted as text only. No three.js here: main.js wires these to the scene.

function element(tag, attributes = {}, text) {
  const e = document.createElement(tag);
  for (const [k, v] of Object.entries(attributes)) {
    if (k === 'className') e.className = v;
    else e.setAttribute(k, v);
  }
  if (text !== undefined) e.textContent = text;
  return e;
}

function swatch(color) {
  const s = element('span', { className: 'swatch', 'aria-hidden': 'true' });
  s.style.background = `rgb(${color.map((c) => Math.round(c * 255)).join(',')})`;
  return s;
}

/**
 * The structure list. `onToggle(indices, visible)` is called when the user shows or hides
 * structures; returns `{ setVisible(i, visible), highlight(i) }`.
 */
export function structureList(container, structures, onToggle) {
  container.replaceChildren();
  const boxes = [];
  const groups = new Map();
  const rows = [];
  const groupOf = (name) => {
    if (groups.has(name)) return groups.get(name);
    const details = element('details', { className: 'group', open: '' });
    const summary = element('summary');
    const box = element('input', { type: 'checkbox', 'aria-label': `Show ${name}` });
    box.checked = true;
    const label = element('span', { className: 'group-name' }, name);
    const count = element('span', { className: 'count' });
    summary.append(box, label, count);
    details.append(summary);
    container.append(details);
    const group = { details, box, count, members: [] };
    box.addEventListener('click', (event) => event.stopPropagation());
    box.addEventListener('change', () => {
      for (const i of group.members) boxes[i].checked = box.checked;
      onToggle(group.members, box.checked);
      refreshGroup(group);
    });
    groups.set(name, group);
    return group;
  };
  const refreshGroup = (group) => {
    const shown = group.members.filter((i) => boxes[i].checked).length;
    group.box.checked = shown === group.members.length;
    group.box.indeterminate = shown > 0 && shown < group.members.length;
    group.count.textContent = `${shown}/${group.members.length}`;
  };
  structures.forEach((s, i) => {
    const row = element('label', { className: 'structure', 'data-structure': String(i) });
    const box = element('input', { type: 'checkbox', 'data-structure': String(i) });
    box.checked = true;
    const name = element('span', { className: 'name' }, s.name);
    row.append(box, swatch(s.color), name);
    row.title = s.group ? `${s.group} / ${s.name}` : s.name;
    boxes.push(box);
    rows.push(row);
    const group = s.group ? groupOf(s.group) : null;
    (group ? group.details : container).append(row);
    if (group) group.members.push(i);
    box.addEventListener('change', () => {
      onToggle([i], box.checked);
      if (group) refreshGroup(group);
    });
  });
  // Ungrouped structures first, in list order.
  container.prepend(...rows.filter((row) => row.parentElement === container));
  for (const group of groups.values()) refreshGroup(group);
  let highlighted = -1;
  return {
    setVisible(i, visible) {
      boxes[i].checked = visible;
      for (const group of groups.values()) if (group.members.includes(i)) refreshGroup(group);
    },
    highlight(i) {
      if (highlighted >= 0) rows[highlighted].classList.remove('hover');
      highlighted = i;
      if (i >= 0) rows[i].classList.add('hover');
    },
  };
}

/** Buttons for the session's view and the six standard views. */
export function viewButtons(container, views, onView) {
  container.replaceChildren();
  const add = (label, short, title, index) => {
    const b = element('button', { type: 'button', title, 'data-view': String(index) });
    b.append(element('span', { className: 'long' }, label), element('span', { className: 'short' }, short));
    b.addEventListener('click', () => onView(index));
    container.append(b);
  };
  add('Session', '\u21ba', 'The session\u2019s view (0)', -1);
  views.forEach((v, k) => add(v.name, v.name[0], `${v.name} view (${v.key})`, k));
}

/** The variant choice; hidden when the session has one variant. */
export function variantChoice(select, variants, active, onChange) {
  select.replaceChildren(...variants.map((v, k) => element('option', { value: String(k) }, v.name)));
  select.value = String(active);
  select.closest('.field').hidden = variants.length < 2;
  select.addEventListener('change', () => onChange(Number(select.value)));
}

/**
 * The removed piece's opacity slider: `set(opacity)` shows it at a value (null: this variant
 * has no removed piece, the slider is disabled); `onChange(opacity)` on input.
 */
export function removedSlider(input, output, onChange) {
  const show = (v) => {
    output.textContent = `${Math.round(v * 100)} %`;
  };
  input.addEventListener('input', () => {
    show(Number(input.value));
    onChange(Number(input.value));
  });
  return {
    set(opacity) {
      const field = input.closest('.field');
      field.classList.toggle('disabled', opacity === null);
      input.disabled = opacity === null;
      field.title = opacity === null ? 'This variant shows no removed piece' : '';
      if (opacity !== null) {
        input.value = String(opacity);
        show(opacity);
      } else {
        output.textContent = '\u2013';
      }
    },
  };
}

/** The metrics table: one row per measure, one column per variant; `setActive(k)` marks one. */
export function metricsTable(container, metrics, variants) {
  container.replaceChildren();
  if (metrics.rows.length === 0) {
    container.append(element('p', {}, 'No measures.'));
    return { setActive() {} };
  }
  const table = element('table');
  const head = element('tr');
  head.append(element('th', { scope: 'col' }, ''));
  variants.forEach((v) => head.append(element('th', { scope: 'col' }, v.name)));
  table.append(element('thead'));
  table.tHead.append(head);
  const body = element('tbody');
  for (const row of metrics.rows) {
    const tr = element('tr');
    const label = row.label.trimStart();
    tr.append(element('th', { scope: 'row', className: row.label.startsWith(' ') ? 'sub' : '' }, label));
    row.cells.forEach((c) => tr.append(element('td', {}, c)));
    body.append(tr);
  }
  table.append(body);
  const note = [];
  note.push('Exact cuts, measured as cutaway metrics measures them; lengths in mm.');
  if (metrics.focus) note.push(`Exposure of ${metrics.focus} from the session\u2019s camera, ${metrics.samples} samples.`);
  if (metrics.critical.length) note.push(`Critical: ${metrics.critical.join(', ')}.`);
  container.append(table, element('p', { className: 'note' }, note.join(' ')));
  return {
    setActive(k) {
      for (const tr of table.rows) {
        Array.from(tr.cells).forEach((cell, c) => cell.classList.toggle('active', c === k + 1));
      }
    },
  };
}

/** The footer: the data's attribution (when the scene is the embedded atlas) and the credits. */
export function footer(container, data) {
  container.replaceChildren();
  if (data.attribution) {
    const line = element('p', { className: 'attribution', title: data.attribution.text }, data.attribution.text + ' ');
    // On a phone the line is one line until tapped.
    line.addEventListener('click', () => line.classList.toggle('open'));
    data.attribution.links.forEach(([text, href], k) => {
      if (k) line.append(' \u00b7 ');
      line.append(element('a', { href, target: '_blank', rel: 'noopener noreferrer' }, text));
    });
    container.append(line);
  }
  const credits = element('p', { className: 'credits' });
  credits.append(`Made with ${data.generator} \u00b7 `);
  const licence = element('details', { className: 'licence' });
  licence.append(element('summary', {}, `three.js ${data.three.version} (MIT licence)`));
  licence.append(element('pre', {}, data.three.license));
  credits.append(licence);
  container.append(credits);
}

/** Makes a panel's heading button fold its body. */
export function foldable(panel, open) {
  const button = panel.querySelector('.fold');
  const set = (value) => {
    panel.classList.toggle('folded', !value);
    button.setAttribute('aria-expanded', String(value));
  };
  set(open);
  button.addEventListener('click', () => set(panel.classList.contains('folded')));
}
