//! The window in a browser (wasm32): the same [`ExplorerApp`] on a canvas through eframe's
//! [`WebRunner`](eframe::WebRunner), with what a page does differently.
//!
//! - **Files.** The page has no file system. Before the window starts, the list of shipped
//!   files beside the page (`files.txt`, written by `scripts/build-web.sh`: each path and its
//!   size) is fetched; the lessons and presets are fetched and mounted in memory
//!   ([`crate::input::mount`]), and the images and meshes are listed (*deferred*) and fetched
//!   when a scene needs them ([`fetched_later`]: the scene stands them in until they are in,
//!   then builds again, `gui::document`). A file dropped on
//!   the page or chosen in the browser's dialog is read, mounted under `uploads/`, and handed
//!   to the window as a drop: presets and texplore PNGs open, images and meshes go on the
//!   selected object, as on the desktop.
//! - **Saves** (a preset, a screenshot PNG with its preset inside) are downloads, and stay
//!   mounted under their name so the page can open them again.
//! - **Threads.** Renders run on Web Workers ([`workers`]: one per core but one), each its own
//!   instance of the module with its own copy of the scene; scene builds, coverage passes and
//!   the tiles no worker can take run on the page's thread between frames
//!   ([`crate::render::run_slices`]).
//! - **Keys.** The browser's default for the app's shortcuts (F1, F5, Ctrl+S, Ctrl+O, Ctrl+Z,
//!   the UI scale's Ctrl+=/-/0) is prevented: F5 would reload the page.
//! - **Persistence.** eframe keeps the preferences and the panels in the browser's local
//!   storage; they are also written when the page is hidden or left (`visibilitychange`,
//!   `pagehide`), so a reload keeps the lesson (and its experiment) and the panels.
//! - **Links.** A link in the address (`#texplore1-...`, [`crate::link`]) opens its scene or
//!   lesson when the page opens from it, or when it is pasted in the address bar of the open
//!   page (`hashchange`); a reload restores where the page was instead.

pub mod widgets;
pub mod workers;

use super::files::BrowseFor;
use super::{AppOptions, Browser, DEFAULT_PRESET, ExplorerApp};
use std::cell::RefCell;
use std::future::Future;
use std::path::{Path, PathBuf};
use std::pin::Pin;
use std::sync::Arc;
use std::time::Duration;
use wasm_bindgen::closure::Closure;
use wasm_bindgen::{JsCast as _, JsValue};
use wasm_bindgen_futures::JsFuture;

/// The list of shipped files beside the page: a relative path and its size in bytes a line.
pub const MANIFEST: &str = "files.txt";
/// Where files the user drops or chooses are mounted.
pub const UPLOADS: &str = "uploads";
/// The time each frame gives the background work (queued tasks, tiles no worker takes).
pub const FRAME_BUDGET: Duration = Duration::from_millis(12);
/// The shipped files fetched when a scene needs them, not before the window starts: the images
/// and meshes, whatever their size (a scene stands them in until they are in, and a lesson's
/// check stands them in unread: `scene::stand_in`). The lessons, presets and material
/// libraries, 60 KB in all, are fetched at once: the window opens on them.
#[must_use]
pub fn fetched_later(path: &Path) -> bool {
    path.extension()
        .map(|e| e.to_string_lossy().to_ascii_lowercase())
        .is_some_and(|e| {
            super::files::IMAGE_EXTENSIONS.contains(&e.as_str()) || e == "ply" || e == "obj"
        })
}

thread_local! {
    /// Files mounted since the last frame, to hand to the window as drops.
    static ARRIVED: RefCell<Vec<PathBuf>> = const { RefCell::new(Vec::new()) };
    /// The window's context, to ask for a frame when a file arrives.
    static CONTEXT: RefCell<Option<egui::Context>> = const { RefCell::new(None) };
    /// What eframe's storage would hold now (the preferences, the panels), written to local
    /// storage when the page is hidden or left.
    static SNAPSHOT: RefCell<Vec<(String, String)>> = const { RefCell::new(Vec::new()) };
    /// Links put in the address bar of the open page (its fragment changed), to open.
    static FOLLOW: RefCell<Vec<String>> = const { RefCell::new(Vec::new()) };
}

/// Asks the window for a frame (a file or a worker's answer arrived).
pub fn repaint() {
    CONTEXT.with(|c| {
        if let Some(ctx) = c.borrow().as_ref() {
            ctx.request_repaint();
        }
    });
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

/// The lines of the manifest: each shipped file's path and size.
fn manifest_entries(text: &str) -> Vec<(PathBuf, u64)> {
    text.lines()
        .filter_map(|l| {
            let l = l.trim();
            let (path, size) = l.rsplit_once(' ').unwrap_or((l, "0"));
            (!path.is_empty()).then(|| (PathBuf::from(path), size.parse().unwrap_or(0)))
        })
        .collect()
}

/// Puts `text` in the page's loading message (while the window is not up).
fn loading(text: &str) {
    if let Some(e) = web_sys::window()
        .and_then(|w| w.document())
        .and_then(|d| d.get_element_by_id("status-text"))
    {
        e.set_text_content(Some(text));
    }
}

/// Fetches [`MANIFEST`], mounts the files not [`fetched_later`] and defers the others; returns
/// how many were mounted and deferred.
///
/// # Errors
/// The list or one of the files mounted cannot be fetched.
pub async fn mount_shipped_files() -> Result<(usize, usize), String> {
    let list = fetch_bytes(MANIFEST).await?;
    let list = String::from_utf8(list).map_err(|_| format!("{MANIFEST}: not UTF-8"))?;
    let entries = manifest_entries(&list);
    let (now, later): (Vec<_>, Vec<_>) = entries
        .into_iter()
        .partition(|(path, _)| !fetched_later(path));
    loading(&format!(
        "Loading texplore: the lessons and presets ({} files)…",
        now.len()
    ));
    // All at once: the slowest fetch, not their sum.
    let promises = js_sys::Array::new();
    for (path, _) in &now {
        let path = path.clone();
        promises.push(&wasm_bindgen_futures::future_to_promise(async move {
            let bytes = fetch_bytes(&path.to_string_lossy())
                .await
                .map_err(|e| JsValue::from_str(&e))?;
            crate::input::mount(&path, bytes);
            Ok(JsValue::UNDEFINED)
        }));
    }
    JsFuture::from(js_sys::Promise::all(&promises))
        .await
        .map_err(|e| js_error("the shipped files", &e))?;
    for (path, size) in &later {
        crate::input::defer(path, *size);
    }
    Ok((now.len(), later.len()))
}

/// Starts the downloads of the deferred files a scene asked for.
fn fetch_wanted() {
    for (path, _) in crate::input::take_wanted() {
        wasm_bindgen_futures::spawn_local(async move {
            let url = path.to_string_lossy().into_owned();
            crate::input::fetched(&path, fetch_bytes(&url).await);
            repaint();
        });
    }
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

/// What eframe's storage would be given: kept to write when the page is hidden or left.
#[derive(Default)]
struct Snapshot(Vec<(String, String)>);

impl eframe::Storage for Snapshot {
    fn get_string(&self, key: &str) -> Option<String> {
        self.0
            .iter()
            .find(|(k, _)| k == key)
            .map(|(_, v)| v.clone())
    }

    fn set_string(&mut self, key: &str, value: String) {
        self.0.retain(|(k, _)| k != key);
        self.0.push((key.to_owned(), value));
    }

    fn remove_string(&mut self, key: &str) {
        self.0.retain(|(k, _)| k != key);
    }

    fn flush(&mut self) {}
}

/// Writes the last snapshot to local storage, where eframe reads it on the next visit
/// (eframe's own save runs every 30 s only: its unload listener never fires).
fn save_snapshot() {
    let Some(storage) = web_sys::window().and_then(|w| w.local_storage().ok().flatten()) else {
        return;
    };
    SNAPSHOT.with(|s| {
        for (k, v) in s.borrow().iter() {
            let _ = storage.set_item(k, v);
        }
    });
}

/// The window with the page's frame work around it.
struct WebApp {
    inner: ExplorerApp,
    /// The serial of the snapshot's frame: one snapshot every few frames is plenty.
    frames: u32,
}

impl WebApp {
    /// The render's state for scripts (`globalThis.texploreStatus`: the browser test reads the
    /// passes, the rays per second, the workers and the film's size against the image's from
    /// it); `ppp` is the screen pixels per point.
    fn publish_status(&self, ppp: f32) {
        let status = js_sys::Object::new();
        let set = |k: &str, v: f64| {
            let _ = js_sys::Reflect::set(&status, &k.into(), &v.into());
        };
        if let Some(p) = self.inner.viewer.progress() {
            set("spp", f64::from(p.spp_done));
            set("sppTarget", f64::from(p.spp_target));
            set("raysPerSecond", p.rays_per_second);
            set("finished", f64::from(u8::from(p.finished)));
            set("elapsed", p.elapsed.as_secs_f64());
        }
        // Frames drawn so far: the browser test's frame rate while the workers render.
        set("frames", f64::from(self.frames));
        let memory = crate::render::worker_memory();
        set(
            "workers",
            memory.iter().filter(|(_, _, alive)| *alive).count() as f64,
        );
        let (bytes, chunks) = (js_sys::Array::new(), js_sys::Array::new());
        for (m, c, _) in &memory {
            bytes.push(&JsValue::from_f64(*m as f64));
            chunks.push(&JsValue::from_f64(*c as f64));
        }
        let _ = js_sys::Reflect::set(&status, &"workerMemory".into(), &bytes);
        let _ = js_sys::Reflect::set(&status, &"workerChunks".into(), &chunks);
        // The film rendered and the image as drawn, in screen pixels: in presentation mode
        // the film follows the image (the browser test checks it).
        if let Some(scene) = self.inner.viewer.scene() {
            set("filmWidth", f64::from(scene.settings.width));
            set("filmHeight", f64::from(scene.settings.height));
        }
        if let Some(rect) = self.inner.image_rect() {
            let ppp = f64::from(ppp);
            set("imageWidth", f64::from(rect.width()) * ppp);
            set("imageHeight", f64::from(rect.height()) * ppp);
        }
        set("presenting", f64::from(u8::from(self.inner.presenting())));
        // The files the scene shown stands in (not downloaded when it built).
        set("standIns", self.inner.doc.stand_ins().len() as f64);
        // The scene's file (it changes when an opened scene has built).
        let scene = self.inner.doc.path.to_string_lossy().into_owned();
        let _ = js_sys::Reflect::set(&status, &"scene".into(), &scene.into());
        // The error the window shows, if any.
        let error = self.inner.error.clone().unwrap_or_default();
        let _ = js_sys::Reflect::set(&status, &"error".into(), &error.into());
        let lesson = self.inner.lessons.active_lesson().unwrap_or_default();
        let _ = js_sys::Reflect::set(&status, &"lesson".into(), &lesson.into());
        let _ = js_sys::Reflect::set(&js_sys::global(), &"texploreStatus".into(), &status);
    }

    /// The files being downloaded for the scene, over the window.
    fn downloads(ctx: &egui::Context) {
        let files = crate::input::downloading();
        if files.is_empty() {
            return;
        }
        let bytes: u64 = files.iter().map(|(_, b)| b).sum();
        let names: Vec<String> = files
            .iter()
            .map(|(p, _)| p.to_string_lossy().into_owned())
            .collect();
        egui::Area::new(egui::Id::unique("texplore-downloads"))
            .anchor(egui::Align2::CENTER_BOTTOM, [0.0, -40.0])
            .show(ctx, |ui| {
                egui::Frame::popup(ui.style()).show(ui, |ui| {
                    ui.label(format!(
                        "Downloading {} ({}) for this scene: grey until it is in…",
                        names.join(", "),
                        download_size(bytes)
                    ));
                });
            });
    }
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
        for link in FOLLOW.with(|f| std::mem::take(&mut *f.borrow_mut())) {
            self.inner.files.links.follow(link);
        }
        fetch_wanted();
        if crate::render::run_slices(FRAME_BUDGET) {
            ctx.request_repaint();
        }
        self.inner.logic(ctx, frame);
        fetch_wanted();
        self.frames = self.frames.wrapping_add(1);
        if self.frames % 10 == 1 {
            let mut snapshot = Snapshot::default();
            self.inner.save(&mut snapshot);
            SNAPSHOT.with(|s| *s.borrow_mut() = snapshot.0);
        }
        self.publish_status(ctx.pixels_per_point());
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        self.inner.ui(ui, frame);
        Self::downloads(ui.ctx());
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        self.inner.save(storage);
    }
}

/// `bytes` as the page's loading message says sizes: megabytes to a tenth, or kilobytes.
fn download_size(bytes: u64) -> String {
    if bytes >= 1_000_000 {
        format!("{:.1} MB", bytes as f64 / 1e6)
    } else {
        format!("{} KB", bytes.div_ceil(1000))
    }
}

/// Whether the app takes the key of `event` (its browser default is then prevented): the
/// function keys and the Ctrl (Cmd) shortcuts of the shortcuts list, F5 included. Plain letters
/// are left alone: they type into the text fields.
fn takes(event: &web_sys::KeyboardEvent) -> bool {
    use super::help;
    let Some(key) = egui::Key::from_name(&event.key()) else {
        return false;
    };
    let command = event.ctrl_key() || event.meta_key();
    let name = key.name();
    let function =
        name.len() > 1 && name.starts_with('F') && name[1..].chars().all(|c| c.is_ascii_digit());
    if key == egui::Key::F5 && !command {
        return true;
    }
    [
        help::UNDO,
        help::REDO,
        help::REDO_Y,
        help::OPEN,
        help::SAVE,
        help::SHORTCUTS_KEY,
        help::PRESENT,
        help::INSPECTOR,
        help::SCALE_UP,
        help::SCALE_UP_PLUS,
        help::SCALE_DOWN,
        help::SCALE_RESET,
    ]
    .iter()
    .any(|s| {
        let wants_command = s.modifiers.command || s.modifiers.ctrl || s.modifiers.mac_cmd;
        s.logical_key == key
            && if wants_command {
                command && s.modifiers.shift == event.shift_key()
            } else {
                function && !command
            }
    })
}

/// Listens on the window: the app's keys lose their browser default, the page's state is
/// written when it is hidden or left, and a link put in the address bar opens.
fn install_listeners() -> Result<(), String> {
    let window = web_sys::window().ok_or("no window")?;
    let keys = Closure::<dyn FnMut(web_sys::KeyboardEvent)>::new(|e: web_sys::KeyboardEvent| {
        if takes(&e) {
            e.prevent_default();
        }
    });
    let capture = web_sys::AddEventListenerOptions::new();
    capture.set_capture(true);
    window
        .add_event_listener_with_callback_and_add_event_listener_options(
            "keydown",
            keys.as_ref().unchecked_ref(),
            &capture,
        )
        .map_err(|e| js_error("keydown", &e))?;
    keys.forget();
    let save = Closure::<dyn FnMut(web_sys::Event)>::new(|_: web_sys::Event| save_snapshot());
    for event in ["pagehide", "visibilitychange"] {
        window
            .add_event_listener_with_callback(event, save.as_ref().unchecked_ref())
            .map_err(|e| js_error(event, &e))?;
    }
    save.forget();
    // A link pasted in the address bar of the open page changes only its fragment: no reload.
    let follow = Closure::<dyn FnMut(web_sys::Event)>::new(|_: web_sys::Event| {
        if let Some(hash) = web_sys::window()
            .and_then(|w| w.location().hash().ok())
            .filter(|h| h.contains("#texplore"))
        {
            FOLLOW.with(|f| f.borrow_mut().push(hash));
            repaint();
        }
    });
    window
        .add_event_listener_with_callback("hashchange", follow.as_ref().unchecked_ref())
        .map_err(|e| js_error("hashchange", &e))?;
    follow.forget();
    Ok(())
}

/// Whether the page was reloaded (not opened from a link or the address bar): the browser's
/// navigation timing says so.
fn reloaded() -> bool {
    let Some(performance) = web_sys::window().and_then(|w| w.performance()) else {
        return false;
    };
    performance
        .get_entries_by_type("navigation")
        .iter()
        .any(|e| {
            js_sys::Reflect::get(&e, &"type".into())
                .ok()
                .and_then(|t| t.as_string())
                .is_some_and(|t| t == "reload")
        })
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
    let (mounted, deferred) = mount_shipped_files().await?;
    log::info!("{mounted} shipped files mounted, {deferred} fetched when a scene needs them");
    let workers = workers::start(workers::count());
    log::info!("{workers} render workers");
    install_listeners()?;
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
                if widgets::asked() {
                    widgets::install(&cc.egui_ctx);
                }
                let prefs = super::Prefs::load(cc.storage);
                // A link in the page's address opens its scene, or its lesson at its
                // experiment; a reload, or no link, opens the lesson open last time on the
                // experiment it showed, else the scene open last time (the address's link
                // made again, so a link's scene reopens).
                let hash = web_sys::window()
                    .and_then(|w| w.location().hash().ok())
                    .filter(|h| h.contains("#texplore"));
                let link = match hash {
                    Some(h) if reloaded() => {
                        let _ = crate::link::materialise(&h);
                        None
                    }
                    Some(h) => Some(crate::link::resolve(&h)),
                    None => None,
                };
                let (linked, lesson, experiment) = match &link {
                    Some(Ok(crate::link::Target::Scene(path))) => (Some(path.clone()), None, None),
                    Some(Ok(crate::link::Target::Lesson(l, k))) => (None, Some((**l).clone()), *k),
                    Some(Err(_)) => (None, None, None),
                    None => {
                        let lesson = prefs.lesson.as_deref().and_then(|name| {
                            let loaded = crate::lesson::load_default();
                            crate::lesson::find(&loaded.lessons, name).ok().cloned()
                        });
                        (None, lesson, prefs.experiment)
                    }
                };
                let app_options = AppOptions {
                    recent_file: None,
                    lesson: lesson.clone(),
                    browser: Browser::default(),
                    // The preset's resolution.
                    follow_viewport: false,
                    simd: crate::scene::SimdMode::Auto,
                    startup_notes: Vec::new(),
                };
                // The link's scene, the lesson's, the scene open last time if it is a shipped
                // one (uploads do not outlive the page), else the Earth.
                let open = linked
                    .or_else(|| lesson.as_ref().map(|l| l.preset.clone()))
                    .or_else(|| {
                        prefs
                            .last_scene
                            .filter(|p| crate::input::exists(p) && !p.starts_with(UPLOADS))
                            .or_else(|| Some(PathBuf::from(DEFAULT_PRESET)))
                    });
                let mut inner = ExplorerApp::restore(cc.storage, open, app_options);
                if lesson.is_some() {
                    inner.lessons.then_experiment(experiment);
                }
                if let Some(Err(e)) = link {
                    inner.error = Some(e.to_string());
                }
                Ok(Box::new(WebApp { inner, frames: 0 }))
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
