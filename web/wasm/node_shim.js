// Put before umf-detector.js (em++ --extern-pre-js): emscripten 3.1.6's ES6
// output still uses CommonJS's require() and __dirname when it runs under
// node, which an ES module does not have. Browsers and workers skip this.
const umfUnderNode = typeof process == 'object' && typeof process.versions == 'object' &&
                     typeof process.versions.node == 'string';
const require = umfUnderNode ? (await import('module')).createRequire(import.meta.url) : undefined;
const __dirname = umfUnderNode ? require('path').dirname(require('url').fileURLToPath(import.meta.url)) : undefined;
