//! The page's render workers, both sides of the glue: the page starts Web Workers (`worker.js`,
//! beside the page) on the same compiled WebAssembly module, and each worker's instance runs
//! [`run_worker`] instead of the window. Messages are byte arrays ([`crate::render`]'s
//! protocol), their buffers transferred, not copied.

use std::cell::{Cell, RefCell};
use wasm_bindgen::closure::Closure;
use wasm_bindgen::{JsCast as _, JsValue};

/// The most workers a page starts (`?workers=N` asks for a number).
pub const MAX_WORKERS: usize = 16;

/// `bytes` as a JavaScript array, and its buffer to transfer.
fn to_js(bytes: &[u8]) -> (js_sys::Uint8Array, js_sys::Array) {
    let array = js_sys::Uint8Array::from(bytes);
    let transfer = js_sys::Array::of1(&array.buffer());
    (array, transfer)
}

/// The page's end of one worker.
struct Port(web_sys::Worker);

impl crate::render::WorkerPort for Port {
    fn post(&self, message: Vec<u8>) {
        let (array, transfer) = to_js(&message);
        if let Err(e) = self.0.post_message_with_transfer(&array, &transfer) {
            log::error!("texplore: a render worker refused a message: {e:?}");
        }
    }
}

/// How many workers the page starts: `?workers=N` in its address, else one per core but one
/// (the page's own thread draws the window), at least one.
#[must_use]
pub fn count() -> usize {
    let window = web_sys::window();
    let asked = window
        .as_ref()
        .and_then(|w| w.location().search().ok())
        .and_then(|q| {
            q.trim_start_matches('?')
                .split('&')
                .find_map(|kv| kv.strip_prefix("workers=").map(str::to_owned))
        })
        .and_then(|n| n.parse::<usize>().ok());
    let cores = window.map_or(2.0, |w| w.navigator().hardware_concurrency());
    let cores = if cores.is_finite() && cores >= 1.0 {
        cores as usize
    } else {
        2
    };
    asked
        .unwrap_or(cores.saturating_sub(1))
        .clamp(0, MAX_WORKERS)
        .max(usize::from(asked.is_none()))
}

/// Starts `n` workers on the compiled module the page left in `globalThis.texploreModule`
/// (`index.html`); returns how many started. Without the module (an old page) or without
/// workers, renders stay on the page's thread.
#[must_use]
pub fn start(n: usize) -> usize {
    let module = js_sys::Reflect::get(&js_sys::global(), &"texploreModule".into())
        .ok()
        .filter(|m| !m.is_undefined() && !m.is_null());
    let Some(module) = module else {
        log::info!("texplore: no compiled module to share: rendering on the page's thread");
        return 0;
    };
    let mut started = 0;
    for _ in 0..n {
        let options = web_sys::WorkerOptions::new();
        options.set_type(web_sys::WorkerType::Module);
        let worker = match web_sys::Worker::new_with_options("./worker.js", &options) {
            Ok(w) => w,
            Err(e) => {
                log::info!("texplore: no render workers ({e:?}): rendering on the page's thread");
                break;
            }
        };
        let hello = js_sys::Object::new();
        let _ = js_sys::Reflect::set(&hello, &"module".into(), &module);
        if worker.post_message(&hello).is_err() {
            break;
        }
        let index = crate::render::add_worker(Box::new(Port(worker.clone())));
        let on_message =
            Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |e: web_sys::MessageEvent| {
                let bytes = js_sys::Uint8Array::new(&e.data()).to_vec();
                if let Err(why) = crate::render::worker_message(index, &bytes) {
                    log::error!("texplore: render worker {index}: {why}");
                }
                for why in crate::render::worker_errors() {
                    log::error!("texplore: {why}");
                }
                super::repaint();
            });
        worker.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
        on_message.forget();
        let on_error = Closure::<dyn FnMut(web_sys::Event)>::new(move |e: web_sys::Event| {
            e.prevent_default();
            log::error!("texplore: render worker {index} stopped; its tiles go to the others");
            crate::render::worker_lost(index);
            super::repaint();
        });
        worker.set_onerror(Some(on_error.as_ref().unchecked_ref()));
        on_error.forget();
        started += 1;
    }
    started
}

thread_local! {
    static WORKER: RefCell<Option<crate::render::Worker>> = const { RefCell::new(None) };
    /// Whether a turn to render the next chunk is already asked for.
    static TURN_ASKED: Cell<bool> = const { Cell::new(false) };
    /// The channel a worker asks itself for its next turn through: the page's messages that
    /// arrived meanwhile (a cancellation) are read first.
    static TURNS: RefCell<Option<web_sys::MessageChannel>> = const { RefCell::new(None) };
}

/// The worker's WebAssembly memory in bytes.
fn memory() -> u64 {
    wasm_bindgen::memory()
        .dyn_into::<js_sys::WebAssembly::Memory>()
        .ok()
        .and_then(|m| m.buffer().dyn_into::<js_sys::ArrayBuffer>().ok())
        .map_or(0, |b| u64::from(b.byte_length()))
}

fn post_to_page(scope: &web_sys::DedicatedWorkerGlobalScope, bytes: &[u8]) {
    let (array, transfer) = to_js(bytes);
    if let Err(e) = scope.post_message_with_transfer(&array, &transfer) {
        log::error!("texplore worker: cannot answer the page: {e:?}");
    }
}

fn ask_turn() {
    if TURN_ASKED.with(|t| t.replace(true)) {
        return;
    }
    TURNS.with(|t| {
        if let Some(c) = t.borrow().as_ref() {
            let _ = c.port2().post_message(&JsValue::NULL);
        }
    });
}

/// Whether this instance runs in a Web Worker (then it renders; the window is the page's).
#[must_use]
pub fn in_worker() -> bool {
    js_sys::global()
        .dyn_into::<web_sys::DedicatedWorkerGlobalScope>()
        .is_ok()
}

/// A worker's life: takes the page's messages (and those that came while the module started,
/// which `worker.js` kept in `texploreQueue`), builds scenes and renders chunks one turn each.
///
/// # Errors
/// Not in a worker, or the worker's channel cannot be made.
pub fn run_worker() -> Result<(), String> {
    let scope = js_sys::global()
        .dyn_into::<web_sys::DedicatedWorkerGlobalScope>()
        .map_err(|_| "not in a worker")?;
    // The worker's one pool is its own thread (see `render::thread_pool`).
    crate::render::thread_pool(0).map_err(|e| e.to_string())?;
    WORKER.with(|w| *w.borrow_mut() = Some(crate::render::Worker::new(memory)));
    let channel = web_sys::MessageChannel::new().map_err(|e| format!("{e:?}"))?;
    let turn_scope = scope.clone();
    let on_turn = Closure::<dyn FnMut(JsValue)>::new(move |_: JsValue| {
        TURN_ASKED.with(|t| t.set(false));
        let (answer, more) = WORKER.with(|w| {
            let mut w = w.borrow_mut();
            let Some(w) = w.as_mut() else {
                return (None, false);
            };
            (w.work(), w.has_work())
        });
        if let Some(a) = answer {
            post_to_page(&turn_scope, &a);
        }
        if more {
            ask_turn();
        }
    });
    channel
        .port1()
        .set_onmessage(Some(on_turn.as_ref().unchecked_ref()));
    on_turn.forget();
    TURNS.with(|t| *t.borrow_mut() = Some(channel));
    let page_scope = scope.clone();
    let take = move |data: &JsValue| {
        let bytes = js_sys::Uint8Array::new(data).to_vec();
        let answers = WORKER.with(|w| {
            w.borrow_mut()
                .as_mut()
                .map(|w| (w.receive(&bytes), w.has_work()))
        });
        match answers {
            Some((Ok(answers), more)) => {
                for a in answers {
                    post_to_page(&page_scope, &a);
                }
                if more {
                    ask_turn();
                }
            }
            Some((Err(e), _)) => log::error!("texplore worker: {e}"),
            None => {}
        }
    };
    let take_event = take.clone();
    let on_message =
        Closure::<dyn FnMut(web_sys::MessageEvent)>::new(move |e: web_sys::MessageEvent| {
            take_event(&e.data());
        });
    scope.set_onmessage(Some(on_message.as_ref().unchecked_ref()));
    on_message.forget();
    // What arrived while the module started.
    if let Ok(queue) = js_sys::Reflect::get(&scope, &"texploreQueue".into())
        && let Ok(queue) = queue.dyn_into::<js_sys::Array>()
    {
        for m in queue.iter() {
            take(&m);
        }
        queue.set_length(0);
    }
    Ok(())
}
