// Image to shapes, off the page's thread: one message {bytes, kind, count, seed} starts a
// fit (bytes null: the built-in landscape); the worker posts the target, each placed
// shape, then the result or a one-line error. The page terminates it to stop.
import init, { fitImage } from './pkg/hodr_web.js';

const ready = init();

self.onmessage = async ({ data }) => {
  try {
    await ready;
    const { bytes, kind, count, seed } = data;
    const out = fitImage(
      bytes ?? undefined, kind, count, seed,
      (rgba, width, height) => self.postMessage({ type: 'target', rgba, width, height }),
      (rgba, [shapes, rmse, evaluations]) => self.postMessage({ type: 'shape', rgba, count: shapes, rmse, evaluations }),
    );
    self.postMessage({ type: 'done', ...out });
  } catch (e) {
    self.postMessage({ type: 'error', message: (e && e.message) ? e.message : String(e) });
  }
};
