//! The page's entry point: the explorer window on the canvas `#texplore` of `web/index.html`,
//! or, in a Web Worker (`web/worker.js`), one of the page's render workers.
//! Built for wasm32 only, by `scripts/build-web.sh` (cargo with `--features web`, then
//! wasm-bindgen).

#[cfg(not(target_arch = "wasm32"))]
compile_error!(
    "texplore-web is the browser build: scripts/build-web.sh builds it for wasm32-unknown-unknown"
);

#[cfg(target_arch = "wasm32")]
fn main() {
    // Warnings and errors go to the browser's console.
    let _ = eframe::WebLogger::init(log::LevelFilter::Warn);
    // The same module runs the page's render workers (`web/worker.js`): there it renders.
    if texplore::gui::web::workers::in_worker() {
        if let Err(e) = texplore::gui::web::workers::run_worker() {
            log::error!("texplore worker: {e}");
        }
        return;
    }
    wasm_bindgen_futures::spawn_local(async {
        if let Err(e) = texplore::gui::web::start("texplore").await {
            log::error!("texplore: {e}");
            texplore::gui::web::show_failure(&e);
        }
    });
}
