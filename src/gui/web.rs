//! The window in a browser (wasm32): the same [`ExplorerApp`] on a canvas through eframe's
//! [`WebRunner`](eframe::WebRunner), with what a page does differently.
//!
//! - **Files.** The page has no file system. Before the window starts, the shipped lessons,
//!   presets and assets are fetched from beside the page (the list is `files.txt`, written by
//!   `scripts/build-web.sh`) and mounted in memory ([`crate::input::mount`]), so every loader
//!   reads them by their usual paths. A file dropped on the page or chosen in the browser's
//!   dialog is read, mounted under `uploads/`, and handed to the window as a drop: presets and
//!   texplore PNGs open, images and meshes go on the selected object, as on the desktop.
//! - **Saves** (a preset, a screenshot PNG with its preset inside) are downloads, and stay
//!   mounted under their name so the page can open them again.
//! - **Threads.** None: renders, scene builds and coverage passes run on the page's thread
//!   between frames ([`crate::render::run_slices`]), a few milliseconds of tiles a frame.
//! - **Persistence.** eframe keeps the preferences and the panels in the browser's local
//!   storage.

use super::files::BrowseFor;
use super::{AppOptions, Browser, DEFAULT_PRESET, ExplorerApp};
use std::cell::RefCell;
use std::future::Future;
use std::path::{Path, PathBuf};
use std::pin::Pin;
use std::sync::Arc;
use std::time::Duration;
use wasm_bindgen::{JsCast as _, JsValue};
use wasm_bindgen_futures::JsFuture;

/// The list of shipped files beside the page, one relative path a line.
pub const MANIFEST: &str = "files.txt";
/// Where files the user drops or chooses are mounted.
pub const UPLOADS: &str = "uploads";
/// The time each frame gives the background work (the render's tiles, queued tasks).
pub const FRAME_BUDGET: Duration = Duration::from_millis(12);

thread_local! {
    /// Files mounted since the last frame, to hand to the window as drops.
    static ARRIVED: RefCell<Vec<PathBuf>> = const { RefCell::new(Vec::new()) };
    /// The window's context, to ask for a frame when a file arrives.
    static CONTEXT: RefCell<Option<egui::Context>> = const { RefCell::new(None) };
}

fn js_error(what: &str, e: &JsValue) -> String {
    format!(
        "{what}: {}",
        e.as_string().unwrap_or_else(|| format!("{e:?}"))
    )
}

/// The bytes at `url` (relative to the page).
async fn fetch_bytes(url: &str) -> Result<Vec<u8>, String> {
    let window = web_sys::window().ok_or("no window")?;
    let response = JsFuture::from(window.fetch_with_str(url))
        .await
        .map_err(|e| js_error(url, &e))?;
    let response: web_sys::Response = response.dyn_into().map_err(|e| js_error(url, &e))?;
    if !response.ok() {
        return Err(format!("{url}: HTTP {}", response.status()));
    }
    let buffer = response.array_buffer().map_err(|e| js_error(url, &e))?;
    let buffer = JsFuture::from(buffer)
        .await
        .map_err(|e| js_error(url, &e))?;
    Ok(js_sys::Uint8Array::new(&buffer).to_vec())
}

/// Fetches [`MANIFEST`] and mounts every file it lists; returns how many.
///
/// # Errors
/// The list or one of its files cannot be fetched.
pub async fn mount_shipped_files() -> Result<usize, String> {
    let list = fetch_bytes(MANIFEST).await?;
    let list = String::from_utf8(list).map_err(|_| format!("{MANIFEST}: not UTF-8"))?;
    let paths: Vec<&str> = list
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    for path in &paths {
        let bytes = fetch_bytes(path).await?;
        crate::input::mount(Path::new(path), bytes);
    }
    Ok(paths.len())
}

/// Offers `bytes` as a download named after `path`'s file name.
fn download(path: &Path, bytes: &[u8]) -> Result<(), String> {
    let name = path
        .file_name()
        .map_or_else(|| "texplore".into(), |n| n.to_string_lossy().into_owned());
    let array = js_sys::Uint8Array::from(bytes);
    let parts = js_sys::Array::of1(&array);
    let blob =
        web_sys::Blob::new_with_u8_array_sequence(&parts).map_err(|e| js_error(&name, &e))?;
    let url = web_sys::Url::create_object_url_with_blob(&blob).map_err(|e| js_error(&name, &e))?;
    let document = web_sys::window()
        .and_then(|w| w.document())
        .ok_or("no document")?;
    let a: web_sys::HtmlAnchorElement = document
        .create_element("a")
        .map_err(|e| js_error(&name, &e))?
        .dyn_into()
        .map_err(|e| js_error(&name, &e))?;
    a.set_href(&url);
    a.set_download(&name);
    a.click();
    web_sys::Url::revoke_object_url(&url).map_err(|e| js_error(&name, &e))
}

/// Mounts `bytes` as `uploads/NAME` and hands that path to the window as a drop.
fn arrived(name: &str, bytes: Vec<u8>) {
    let path = Path::new(UPLOADS).join(name);
    crate::input::mount(&path, bytes);
    ARRIVED.with(|a| a.borrow_mut().push(path));
    CONTEXT.with(|c| {
        if let Some(ctx) = c.borrow().as_ref() {
            ctx.request_repaint();
        }
    });
}

/// The page's *Browse…*: a file to read opens the browser's dialog, and the file chosen arrives
/// later as a drop (so `None` now); a file to save is named `name` and downloaded when saved.
#[must_use]
pub fn pick(what: BrowseFor, _start: &Path, name: &str) -> Option<PathBuf> {
    let dialog = rfd::AsyncFileDialog::new();
    let dialog = match what {
        BrowseFor::Image => dialog.add_filter("Images", &super::files::IMAGE_EXTENSIONS),
        BrowseFor::Mesh => dialog.add_filter("Meshes (PLY, OBJ)", &["ply", "obj"]),
        BrowseFor::Scene => dialog.add_filter("Presets and texplore PNGs", &["ron", "png"]),
        BrowseFor::Preset | BrowseFor::Screenshot => {
            let fallback = if what == BrowseFor::Preset {
                "scene.ron"
            } else {
                "texplore-shot.png"
            };
            return Some(PathBuf::from(if name.is_empty() { fallback } else { name }));
        }
    };
    wasm_bindgen_futures::spawn_local(async move {
        if let Some(file) = dialog.pick_file().await {
            let bytes = file.read().await;
            arrived(&file.file_name(), bytes);
        }
    });
    None
}

/// A mounted file handed to the window as a drop.
#[derive(Debug)]
struct Mounted(PathBuf);

impl egui::DroppedFile for Mounted {
    fn path(&self) -> &Path {
        &self.0
    }

    fn bytes_async(&self) -> Pin<Box<dyn Future<Output = Result<Vec<u8>, String>> + '_>> {
        let bytes = crate::input::read_input(&self.0, u64::MAX).map_err(|e| e.to_string());
        Box::pin(std::future::ready(bytes))
    }
}

/// The window with the page's frame work around it.
struct WebApp {
    inner: ExplorerApp,
}

impl eframe::App for WebApp {
    fn raw_input_hook(&mut self, ctx: &egui::Context, raw_input: &mut egui::RawInput) {
        // The browser's drops carry no path: read each, mount it, hand it over when it is in.
        for file in std::mem::take(&mut raw_input.dropped_files) {
            let name = file
                .path()
                .file_name()
                .map_or_else(|| "dropped".into(), |n| n.to_string_lossy().into_owned());
            let ctx = ctx.clone();
            wasm_bindgen_futures::spawn_local(async move {
                match file.bytes_async().await {
                    Ok(bytes) => arrived(&name, bytes),
                    Err(e) => log::error!("{name}: {e}"),
                }
                ctx.request_repaint();
            });
        }
        for path in ARRIVED.with(|a| std::mem::take(&mut *a.borrow_mut())) {
            raw_input.dropped_files.push(Arc::new(Mounted(path)));
        }
    }

    fn logic(&mut self, ctx: &egui::Context, frame: &mut eframe::Frame) {
        if crate::render::run_slices(FRAME_BUDGET) {
            ctx.request_repaint();
        }
        self.inner.logic(ctx, frame);
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.inner.ui(ui, frame);
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.inner.save(storage);
    }
}

/// Replaces the page's loading message with `message` (the window could not start).
pub fn show_failure(message: &str) {
    if let Some(e) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("status"))
    {
        e.set_text_content(Some(&format!("texplore could not start: {message}")));
    }
}

/// Starts the window on the canvas with id `canvas_id`: mounts the shipped files, installs the
/// download hook for saves, and runs the window on the Earth (or the scene open last time).
///
/// # Errors
/// The canvas is missing, a shipped file cannot be fetched, or the graphics cannot start.
pub async fn start(canvas_id: &str) -> Result<(), String> {
    // The page's one worker pool is its own thread; made before any parallel iterator runs,
    // so they all run on it (see `render::thread_pool`).
    crate::render::thread_pool(0).map_err(|e| e.to_string())?;
    crate::output::set_save_hook(|path, bytes| {
        download(path, &bytes).map_err(std::io::Error::other)?;
        crate::input::mount(path, bytes);
        Ok(())
    });
    let mounted = mount_shipped_files().await?;
    log::info!("{mounted} shipped files mounted");
    let canvas = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id(canvas_id))
        .ok_or_else(|| format!("no element #{canvas_id} in the page"))?
        .dyn_into::<web_sys::HtmlCanvasElement>()
        .map_err(|_| format!("#{canvas_id} is not a canvas"))?;
    let options = eframe::WebOptions::default();
    eframe::WebRunner::new()
        .start(
            canvas,
            options,
            Box::new(|cc| {
                CONTEXT.with(|c| *c.borrow_mut() = Some(cc.egui_ctx.clone()));
                let app_options = AppOptions {
                    recent_file: None,
                    lesson: None,
                    browser: Browser::default(),
                    // The preset's resolution: the page renders on one thread.
                    follow_viewport: false,
                    simd: crate::scene::SimdMode::Auto,
                    startup_notes: Vec::new(),
                };
                // The scene open last time, if it is a shipped one (uploads do not outlive the
                // page), else the Earth.
                let open = super::Prefs::load(cc.storage)
                    .last_scene
                    .filter(|p| crate::input::is_mounted(p))
                    .or_else(|| Some(PathBuf::from(DEFAULT_PRESET)));
                let inner = ExplorerApp::restore(cc.storage, open, app_options);
                Ok(Box::new(WebApp { inner }))
            }),
        )
        .await
        .map_err(|e| js_error("cannot start the window", &e))?;
    // The window is up: the loading message goes.
    if let Some(status) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("status"))
    {
        status.remove();
    }
    Ok(())
}
