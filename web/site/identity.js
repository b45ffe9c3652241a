// How this phone names itself to the screen, in every hello.
const DEVICE_KEY = 'umf.device.v1';

// What the screen calls this phone (its console, the put prompt's "from"):
// the model where the browser tells it ("Pixel 7 (umf web, Android)"), else
// the kind of device ("iPhone (umf web, iOS)", "Linux (umf web)").
export async function clientName() {
  const ua = navigator.userAgent;
  let model = '';
  try {
    model = (await navigator.userAgentData?.getHighEntropyValues?.(['model']))?.model || '';
  } catch { /* not told: from the user agent below */ }
  // Android user agents name the model after the version, unless reduced to "K".
  const android = /Android [\d.]+; ([^;)]+)[;)]/.exec(ua);
  if (!model && android && android[1].trim() !== 'K') model = android[1].trim();
  if (!model) model = /iPad/.test(ua) ? 'iPad' : /iPhone/.test(ua) ? 'iPhone' : '';
  const platform = navigator.userAgentData?.platform ||
    (/Android/.test(ua) ? 'Android' : /iPhone|iPad/.test(ua) ? 'iOS' : navigator.platform || '');
  const name = model ? `${model} (umf web${platform ? `, ${platform}` : ''})` : `${platform || 'Browser'} (umf web)`;
  return name.replace(/[^\x20-\x7e]/g, '?').slice(0, 100);
}

// The name this phone gives itself in every hello, so that the person at the
// screen can accept its puts "always": random, made once, kept. Printable
// ASCII, as the protocol asks.
export function deviceName() {
  let name = null;
  try {
    name = localStorage.getItem(DEVICE_KEY);
  } catch { /* no storage: a name for this visit */ }
  if (!name || !/^[\x21-\x7e]{1,64}$/.test(name)) {
    const bytes = crypto.getRandomValues(new Uint8Array(8));
    name = `umf-web-${Array.from(bytes, (b) => b.toString(16).padStart(2, '0')).join('')}`;
    try {
      localStorage.setItem(DEVICE_KEY, name);
    } catch { /* as above */ }
  }
  return name;
}
