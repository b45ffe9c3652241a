// The umf browser companion's background: keeps the running umf provider
// told (through the native-messaging host, org.umf.browser) which page each
// normal window shows and where that window is on the screen, and answers the
// provider's questions about a point on a window: what lies there, or a tab to
// open. Private windows are never reported or answered for, and nothing but
// http(s) URLs is sent.
"use strict";

const api = globalThis.browser ?? globalThis.chrome;
const HOST = "org.umf.browser";
const MAX_TITLE = 512;
const MAX_TEXT = 300;
const RETRY_MS = 5000;

let port = null;
let retryTimer = null;
let reportTimer = null;
let providerConnected = false;

function shareable(url) {
  return typeof url === "string" && /^https?:\/\/[^\s]/i.test(url) && url.length <= 8192;
}

function clip(text, max) {
  const s = typeof text === "string" ? text.replace(/\s+/g, " ").trim() : "";
  return s.length > max ? s.slice(0, max) : s;
}

function browserName() {
  if (api.runtime.getBrowserInfo) return "firefox";
  const ua = navigator.userAgent;
  if (/Edg\//.test(ua)) return "edge";
  if (/Chrome\//.test(ua) && navigator.userAgentData?.brands?.some((b) => b.brand === "Google Chrome")) return "chrome";
  return "chromium";
}

function browserVersion() {
  const m = navigator.userAgent.match(/(?:Firefox|Chrome|Edg)\/([\d.]+)/);
  return m ? m[1] : "";
}

function connect() {
  if (port) return;
  try {
    port = api.runtime.connectNative(HOST);
  } catch (e) {
    port = null;
    scheduleRetry();
    return;
  }
  port.onMessage.addListener(onMessage);
  port.onDisconnect.addListener(() => {
    port = null;
    providerConnected = false;
    scheduleRetry();
  });
  port.postMessage({ type: "hello", browser: browserName(), version: browserVersion() });
  scheduleReport();
}

function scheduleRetry() {
  if (retryTimer) return;
  retryTimer = setTimeout(() => {
    retryTimer = null;
    connect();
  }, RETRY_MS);
}

function scheduleReport() {
  if (reportTimer) return;
  reportTimer = setTimeout(() => {
    reportTimer = null;
    report().catch(() => {});
  }, 50);
}

async function tabReport(tab) {
  if (!tab || tab.incognito) return null;
  let zoom = 1;
  try {
    zoom = await api.tabs.getZoom(tab.id);
  } catch (e) {
    // a tab that went away meanwhile: 1
  }
  return { id: tab.id, url: shareable(tab.url) ? tab.url : "", title: clip(tab.title, MAX_TITLE), zoom };
}

async function report() {
  if (!port) return;
  const all = await api.windows.getAll({ populate: true, windowTypes: ["normal"] });
  const windows = [];
  for (const w of all) {
    if (w.incognito) continue;
    const active = (w.tabs || []).find((t) => t.active);
    windows.push({
      id: w.id,
      left: w.left ?? 0,
      top: w.top ?? 0,
      width: w.width ?? 0,
      height: w.height ?? 0,
      focused: !!w.focused,
      tab: await tabReport(active),
    });
  }
  if (port) port.postMessage({ type: "windows", windows });
}

function answer(req, body) {
  if (port) port.postMessage(Object.assign({ type: "answer", req }, body));
}

// Runs in the page: what lies at a screen point, in the page's terms. Given
// the point in screen pixels and the tab's zoom.
function elementAtScreenPoint(screenX, screenY, zoom, maxText) {
  const clipText = (t, max) => {
    const s = typeof t === "string" ? t.replace(/\s+/g, " ").trim() : "";
    return s.length > max ? s.slice(0, max) : s;
  };
  const dpr = window.devicePixelRatio || 1;
  // Viewport (CSS pixels) to screen pixels and back: the viewport's origin
  // on the screen and the CSS pixel's size there.
  let originX;
  let originY;
  let scale;
  if (typeof window.mozInnerScreenX === "number") {
    // Firefox: the viewport's origin on the screen, in CSS pixels.
    originX = window.mozInnerScreenX * dpr;
    originY = window.mozInnerScreenY * dpr;
    scale = dpr;
  } else {
    // Chromium: window geometry in screen DIPs, the viewport in CSS pixels.
    const dip = dpr / (zoom || 1);
    const border = Math.max(0, (window.outerWidth - window.innerWidth * zoom) / 2);
    const top = Math.max(0, window.outerHeight - window.innerHeight * zoom - border);
    originX = (window.screenX + border) * dip;
    originY = (window.screenY + top) * dip;
    scale = dip * zoom;
  }
  const x = (screenX - originX) / scale;
  const y = (screenY - originY) / scale;
  // Where an element lies on the screen, so the provider may give this
  // answer again to an aim inside it that the page answers too late.
  const onScreen = (e) => {
    const r = e.getBoundingClientRect();
    return { screen_rect: [originX + r.left * scale, originY + r.top * scale, r.width * scale, r.height * scale] };
  };
  const base = { x, y, page: location.href, title: clipText(document.title, 512) };
  if (x < 0 || y < 0 || x >= window.innerWidth || y >= window.innerHeight) return Object.assign(base, { kind: "outside" });
  const element = document.elementFromPoint(x, y);
  for (let e = element; e && e !== document.documentElement; e = e.parentElement) {
    const tag = e.tagName;
    if (tag === "A" && e.href)
      return Object.assign(base, onScreen(e), { kind: "link", url: String(e.href), text: clipText(e.innerText || e.title, maxText) });
    if (tag === "IMG") return Object.assign(base, onScreen(e), { kind: "image", url: e.currentSrc || e.src, text: clipText(e.alt, maxText) });
    if (tag === "VIDEO" || tag === "AUDIO")
      return Object.assign(base, onScreen(e), { kind: tag === "VIDEO" ? "video" : "audio", url: e.currentSrc || e.src, time: e.currentTime || 0 });
  }
  // The passage under the point: its block's first and last words.
  let block = element;
  while (block && block !== document.body && getComputedStyle(block).display.startsWith("inline")) block = block.parentElement;
  const words = clipText(block ? block.innerText : "", 4000).split(" ").filter((w) => w);
  return Object.assign(base, block ? onScreen(block) : {},
                       { kind: "text", start: words.slice(0, 5).join(" "), end: words.length > 10 ? words.slice(-5).join(" ") : "" });
}

async function elementAt(question) {
  const tab = await api.tabs.get(question.tab);
  if (!tab || tab.incognito || !tab.active || tab.windowId !== question.window) return { error: "not-shown" };
  if (!shareable(tab.url)) return { error: "not-shareable" };
  const zoom = await api.tabs.getZoom(tab.id).catch(() => 1);
  const [result] = await api.scripting.executeScript({
    target: { tabId: tab.id },
    func: elementAtScreenPoint,
    args: [question.screen_x, question.screen_y, zoom, MAX_TEXT],
  });
  return result && result.result ? { element: result.result } : { error: "no-answer" };
}

function toBase64(bytes) {
  let text = "";
  for (let i = 0; i < bytes.length; i += 0x8000) text += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
  return btoa(text);
}

// An image's bytes, fetched as the page would (its cookies), never more than
// the provider takes: a larger one is stopped as soon as it shows.
async function imageBytes(question) {
  if (!shareable(question.url)) return { error: "not-shareable" };
  const tab = await api.tabs.get(question.tab);
  if (!tab || tab.incognito) return { error: "not-shown" };
  const max = Number(question.max_bytes) || 0;
  const response = await fetch(question.url, { credentials: "include" });
  if (!response.ok) return { error: "http-" + response.status };
  if (Number(response.headers.get("content-length") || 0) > max) return { error: "too-large" };
  const reader = response.body.getReader();
  const chunks = [];
  let total = 0;
  for (;;) {
    const { done, value } = await reader.read();
    if (done) break;
    total += value.length;
    if (total > max) {
      reader.cancel();
      return { error: "too-large" };
    }
    chunks.push(value);
  }
  const bytes = new Uint8Array(total);
  let at = 0;
  for (const chunk of chunks) {
    bytes.set(chunk, at);
    at += chunk.length;
  }
  return { mime: clip(response.headers.get("content-type") || "", 100), base64: toBase64(bytes) };
}

async function openTab(question) {
  if (!shareable(question.url)) return { error: "not-shareable" };
  const w = await api.windows.get(question.window);
  if (!w || w.incognito) return { error: "not-shown" };
  const tab = await api.tabs.create({ windowId: w.id, url: question.url, active: true });
  return { opened: true, tab: tab.id };
}

function onMessage(message) {
  if (!message || typeof message.type !== "string") return;
  if (message.type === "status") {
    providerConnected = !!message.provider;
    if (providerConnected) scheduleReport();
    return;
  }
  if (message.type === "error") {
    console.warn("umf provider:", message.message);
    return;
  }
  const req = message.req;
  const handlers = { element_at: elementAt, image_bytes: imageBytes, open_tab: openTab };
  const handler = handlers[message.type];
  if (!handler) return answer(req, { error: "unknown-question" });
  handler(message)
    .then((body) => answer(req, body))
    .catch((e) => answer(req, { error: "failed", message: clip(String(e && e.message), MAX_TEXT) }));
}

for (const event of [
  api.tabs.onActivated,
  api.tabs.onUpdated,
  api.tabs.onRemoved,
  api.tabs.onZoomChange,
  api.windows.onCreated,
  api.windows.onRemoved,
  api.windows.onFocusChanged,
  api.windows.onBoundsChanged,
]) {
  if (event) event.addListener(() => {
    connect();
    scheduleReport();
  });
}
// Firefox tells no window moves: ask again now and then while connected.
setInterval(() => {
  if (port && providerConnected) scheduleReport();
}, 2000);
api.runtime.onStartup.addListener(connect);
api.runtime.onInstalled.addListener(connect);
connect();
