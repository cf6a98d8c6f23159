// One of the page's render workers: the page's own WebAssembly module, instantiated here from
// the compiled module the page sends first (so it is neither fetched nor compiled again). Its
// main (src/bin/web.rs) sees it runs in a worker and takes over the messages; those that arrive
// while it starts wait in `texploreQueue`.
import init from "./texplore.js";

self.texploreQueue = [];
let started = false;
self.onmessage = async (e) => {
  if (started) {
    self.texploreQueue.push(e.data);
    return;
  }
  started = true;
  await init({ module_or_path: e.data.module });
};
