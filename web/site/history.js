// What this phone took, newest first: kept in localStorage, shown on its sheet.
import { $, formatSize } from './sheets.js';

const HISTORY_KEY = 'umf.history.v1';
const HISTORY_MAX = 50;

function loadHistory() {
  try {
    return JSON.parse(localStorage.getItem(HISTORY_KEY) || '[]');
  } catch {
    return [];
  }
}

export function remember(entry) {
  const list = [entry, ...loadHistory()].slice(0, HISTORY_MAX);
  try {
    localStorage.setItem(HISTORY_KEY, JSON.stringify(list));
  } catch { /* storage full: the history is a convenience */ }
}

export function clearHistory() {
  localStorage.removeItem(HISTORY_KEY);
}

export function showHistory() {
  const list = loadHistory();
  const ol = $('history-list');
  ol.replaceChildren(...list.map((e) => {
    const li = document.createElement('li');
    if (e.kind === 'url') {
      const a = document.createElement('a');
      a.href = e.url;
      a.target = '_blank';
      a.rel = 'noopener noreferrer';
      a.textContent = e.title || e.url;
      li.append(a);
    } else {
      li.textContent = `${e.title || e.name}${e.size ? ` (${formatSize(e.size)})` : ''}`;
    }
    const when = document.createElement('small');
    when.textContent = ` — ${new Date(e.at).toLocaleString()}`;
    li.append(when);
    return li;
  }));
  $('history-empty').hidden = list.length > 0;
  $('history').hidden = false;
}
