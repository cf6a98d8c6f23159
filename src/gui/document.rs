//! The document: the scene description the window edits and what belongs to it (the last
//! description that built, the one last opened or saved, the undo history, the file and the
//! asset cache), and the scene builds it asks for.
//!
//! Panels edit the description (directly, or through a [`super::command::Command`]); once per
//! frame the app hands the document what the renders need ([`Document::rebuild`]), and when that
//! differs from what was last asked, one build starts as a [`Task`] on the render pool, so the
//! window stays responsive however long a build takes (a displaced mesh: seconds). A newer
//! request supersedes an older one still running; the app collects the one that lands with
//! [`Document::poll`]. A build that fails leaves the scene as it was: the description goes back
//! to the last one that built.

use super::history::{self, Gesture, History};
use crate::render::Task;
use crate::scene::{AssetCache, CameraDesc, Scene, SceneDesc, build_scene};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, PoisonError};

/// An object's identity in the window: it stays with the object through edits of the list,
/// undo, redo and a lesson's *Apply*, so what an editor remembers about an object (the image it
/// had, the maps switched off) follows it, whatever its index.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct ObjectId(u64);

impl ObjectId {
    /// An id no object has had before.
    #[must_use]
    pub fn fresh() -> Self {
        static NEXT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(1);
        Self(NEXT.fetch_add(1, std::sync::atomic::Ordering::Relaxed))
    }

    /// The id as a number, for editors that key what they keep by a plain number.
    #[must_use]
    pub fn number(self) -> usize {
        usize::try_from(self.0).unwrap_or(usize::MAX)
    }
}

/// A description and its objects' ids: what the history keeps.
#[derive(Clone, Debug, PartialEq)]
pub struct Version {
    /// The description.
    pub desc: SceneDesc,
    /// The id of each of its objects, in order.
    pub ids: Vec<ObjectId>,
}

impl Version {
    /// `desc` with fresh ids (a scene just opened).
    fn fresh(desc: SceneDesc) -> Self {
        let ids = desc.objects.iter().map(|_| ObjectId::fresh()).collect();
        Self { desc, ids }
    }
}

/// What changed from `old` to `new` ([`history::describe`]).
fn describe(old: &Version, new: &Version) -> String {
    history::describe(&old.desc, &new.desc)
}

/// What a build is for: what happens when it lands or fails.
#[derive(Debug)]
pub enum Purpose {
    /// An edit of the open scene: on failure the description goes back to the last good one.
    Edit,
    /// Opening the file at this path: on success it replaces the scene (the document's file,
    /// the saved description, the history); on failure nothing changes.
    Open(PathBuf),
    /// An undo or redo step: on failure the history goes back to this (the step is kept).
    Step(Box<History<Version>>),
}

/// What one build makes: the scene rendered in the viewport and, with the A/B split on, the
/// split's scenes.
#[derive(Clone, PartialEq)]
pub struct Recipe {
    /// The description rendered (the edited one at the view's resolution scale).
    pub render: SceneDesc,
    /// The A/B split's descriptions (side A, side B, the reference), when it is shown.
    pub split: Option<[SceneDesc; 3]>,
    /// Which path the scenes' primary rays take.
    pub simd: crate::scene::SimdMode,
}

/// The scenes of a build.
pub struct Built {
    /// The viewport's scene.
    pub scene: Arc<Scene>,
    /// The split's scenes, or why they do not build.
    pub split: Option<Result<[Arc<Scene>; 3], String>>,
    /// In a page: the shipped files not downloaded yet that the scenes stand in (see [`build`]).
    pub stood_in: Vec<PathBuf>,
    /// What the builds said about their textures ([`AssetCache::notices`]: a footprint filter
    /// reading EWA because its image's summed-area tables did not fit the budget, or cannot
    /// sum its texels), each once.
    pub notices: Vec<String>,
}

/// A build that landed: what it was for and its scenes, or why it failed.
pub struct Landed {
    /// What the build was for.
    pub purpose: Purpose,
    /// Its scenes, or the error.
    pub outcome: Result<Built, String>,
}

/// A build on the pool and what it was asked for.
struct Pending {
    purpose: Purpose,
    version: Version,
    path: PathBuf,
    /// The gesture of the frame that asked for it (its undo step merges with that gesture's).
    gesture: Option<Gesture>,
    recipe: Recipe,
    task: Task<Result<Built, String>>,
}

/// The open scene and its builds.
pub struct Document {
    /// The scene the panels edit, unsaved edits included (`None` until a preset opens).
    pub(super) desc: Option<SceneDesc>,
    /// The id of each object of `desc`, in order (kept in step by [`Document::sync_ids`]).
    pub(super) ids: Vec<ObjectId>,
    /// The last description that built and its ids (restored when an edit fails).
    good: Option<Version>,
    /// The description as last opened or saved (for the unsaved-changes prompt).
    pub(super) saved: Option<SceneDesc>,
    /// The camera as opened, for *Reset view*.
    pub(super) home_camera: Option<CameraDesc>,
    /// Undo and redo over every change of the description that built, whichever panel made it.
    pub(super) history: History<Version>,
    /// The file the scene came from; asset paths are relative to it.
    pub(super) path: PathBuf,
    /// Images and meshes loaded once, shared by every build (locked by the build running).
    cache: Arc<Mutex<AssetCache>>,
    /// What the last build was asked for, so an unchanged frame builds nothing.
    asked: Option<Recipe>,
    /// What the last build that landed was asked for (asked again after a failure).
    built: Option<Recipe>,
    pending: Option<Pending>,
    /// In a page: the files the scene shown stands in (not downloaded yet when it built).
    stand_ins: Vec<PathBuf>,
}

impl Document {
    /// An empty document for the file at `path` (opened with [`Document::open`]).
    #[must_use]
    pub fn new(path: PathBuf) -> Self {
        Self {
            desc: None,
            ids: Vec::new(),
            good: None,
            saved: None,
            home_camera: None,
            history: History::default(),
            path,
            cache: Arc::new(Mutex::new(AssetCache::new())),
            asked: None,
            built: None,
            pending: None,
            stand_ins: Vec::new(),
        }
    }

    /// In a page: the shipped files the scene shown stands in, not downloaded when it built (a
    /// build with them follows once they are in).
    #[cfg(target_arch = "wasm32")]
    #[must_use]
    pub fn stand_ins(&self) -> &[PathBuf] {
        &self.stand_ins
    }

    /// A fresh asset cache under a texture budget of `bytes` for the builds from now on
    /// ([`AssetCache::set_texture_budget`]: tests reach its limits with small images). Fresh,
    /// so no summed-area table built under the old budget is kept.
    pub fn set_texture_budget(&mut self, bytes: u64) {
        let mut cache = AssetCache::new();
        cache.set_texture_budget(bytes);
        self.cache = Arc::new(Mutex::new(cache));
    }

    /// The asset paths' folder: the preset's.
    #[must_use]
    pub fn folder(&self) -> &Path {
        self.path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."))
    }

    /// Whether a build is running.
    #[must_use]
    pub fn building(&self) -> bool {
        self.pending.is_some()
    }

    /// Whether a file is being opened (its scene building): edits wait for it.
    #[must_use]
    pub fn opening(&self) -> bool {
        matches!(
            self.pending,
            Some(Pending {
                purpose: Purpose::Open(_),
                ..
            })
        )
    }

    /// Starts building `desc` from the file at `path` (`recipe` what to build); the scene
    /// replaces the open one when it lands.
    pub fn open(&mut self, path: &Path, desc: SceneDesc, recipe: Recipe) {
        let version = Version::fresh(desc);
        self.start(
            Purpose::Open(path.to_path_buf()),
            version,
            path,
            recipe,
            None,
        );
    }

    /// The description and its ids, the ids first brought in step with the objects.
    pub fn version(&mut self) -> Option<Version> {
        self.sync_ids();
        Some(Version {
            desc: self.desc.clone()?,
            ids: self.ids.clone(),
        })
    }

    /// Puts `version` in place (undo, redo, a failed edit rolled back).
    pub fn restore(&mut self, version: Version) {
        self.desc = Some(version.desc);
        self.ids = version.ids;
    }

    /// One id per object: objects added at the end (*Duplicate*, a lesson's scene) get fresh
    /// ids, ids beyond the last object go (an object removed in place is removed from `ids`
    /// by the panel that removes it).
    pub fn sync_ids(&mut self) {
        let n = self.desc.as_ref().map_or(0, |d| d.objects.len());
        self.ids.truncate(n);
        while self.ids.len() < n {
            self.ids.push(ObjectId::fresh());
        }
    }

    /// Once a frame, after the panels: starts a build when `recipe` (what the renders need
    /// now) differs from what was last asked. `gesture` is the frame's: the undo step of the
    /// change merges with its gesture's.
    pub fn rebuild(&mut self, recipe: Recipe, gesture: Option<Gesture>) {
        if self.opening() || self.asked.as_ref() == Some(&recipe) {
            return;
        }
        let Some(version) = self.version() else {
            return;
        };
        let purpose = match self.pending.take() {
            // A step superseded by an edit of the step's result stays a step: if the edit
            // fails, the history still matches the description restored.
            Some(Pending {
                purpose: Purpose::Step(kept),
                ..
            }) => Purpose::Step(kept),
            _ => Purpose::Edit,
        };
        let path = self.path.clone();
        self.start(purpose, version, &path, recipe, gesture);
    }

    /// Starts an undo or redo step's build: the description is already restored, `kept` is the
    /// history before the step.
    pub fn step(&mut self, kept: History<Version>, recipe: Recipe) {
        if let Some(version) = self.version() {
            let path = self.path.clone();
            self.start(Purpose::Step(Box::new(kept)), version, &path, recipe, None);
        }
    }

    fn start(
        &mut self,
        purpose: Purpose,
        version: Version,
        path: &Path,
        recipe: Recipe,
        gesture: Option<Gesture>,
    ) {
        self.start_after(purpose, version, path, recipe, gesture, Vec::new());
    }

    /// [`Document::start`] once the shipped files `wait_for` are downloaded (in a page; the
    /// build that follows one that stood them in). Any other build starts at once: in a page
    /// the files it reads download meanwhile, and it stands in those not in yet ([`build`]).
    fn start_after(
        &mut self,
        purpose: Purpose,
        version: Version,
        path: &Path,
        recipe: Recipe,
        gesture: Option<Gesture>,
        wait_for: Vec<PathBuf>,
    ) {
        self.asked = Some(recipe.clone());
        let (cache, task_path, asked) = (self.cache.clone(), path.to_path_buf(), recipe.clone());
        let work = move |cancel: &std::sync::atomic::AtomicBool| {
            // A newer request may have superseded this one while it waited for the pool or
            // for the cache (which the build before holds).
            let stop = || cancel.load(std::sync::atomic::Ordering::Relaxed);
            if stop() {
                return None;
            }
            let mut cache = cache.lock().unwrap_or_else(PoisonError::into_inner);
            if stop() {
                return None;
            }
            Some(build(&asked, &task_path, &mut cache))
        };
        // Dropping the older task cancels it.
        self.pending = None;
        let task = if wait_for.is_empty() {
            #[cfg(target_arch = "wasm32")]
            crate::input::want(&needs(&recipe, path));
            Task::spawn(work)
        } else {
            Task::spawn_reading(wait_for, work)
        };
        match task {
            Ok(task) => {
                self.pending = Some(Pending {
                    purpose,
                    version,
                    path: path.to_path_buf(),
                    gesture,
                    recipe,
                    task,
                });
            }
            Err(e) => {
                let message = e.to_string();
                self.settle(
                    purpose,
                    version,
                    path,
                    gesture,
                    recipe,
                    &Err::<(), _>(message),
                );
            }
        }
    }

    /// The build that landed since the last call, if any, with the document updated: on
    /// success the description built is the good one (an opened file replaces the scene), on
    /// failure the description goes back to the last good one.
    pub fn poll(&mut self) -> Option<Landed> {
        let p = self.pending.as_ref()?;
        let outcome = match p.task.take() {
            Some(outcome) => outcome,
            None if p.task.is_running() => return None,
            None => Err(p.task.failure().map_or_else(
                || "the scene build stopped".to_owned(),
                |what| format!("the scene build stopped: {what}"),
            )),
        };
        let Pending {
            purpose,
            version,
            path,
            gesture,
            recipe,
            ..
        } = self.pending.take()?;
        // A scene that stood in files not downloaded yet is shown, and built again once they
        // are in (an edit of nothing: the history does not change).
        let again = match &outcome {
            Ok(built) if !built.stood_in.is_empty() => {
                Some((built.stood_in.clone(), version.clone(), recipe.clone()))
            }
            _ => None,
        };
        if let Ok(built) = &outcome {
            self.stand_ins.clone_from(&built.stood_in);
        }
        let purpose = self.settle(purpose, version, &path, gesture, recipe, &outcome);
        if let Some((files, version, recipe)) = again {
            self.start_after(Purpose::Edit, version, &path, recipe, None, files);
        }
        Some(Landed { purpose, outcome })
    }

    /// Updates the document for a build of `version` that ended with `outcome`.
    fn settle<T>(
        &mut self,
        purpose: Purpose,
        version: Version,
        path: &Path,
        gesture: Option<Gesture>,
        recipe: Recipe,
        outcome: &Result<T, String>,
    ) -> Purpose {
        if outcome.is_ok() {
            self.built = Some(recipe);
        } else {
            // The scene stays the last one built: asking for it again builds nothing.
            self.asked.clone_from(&self.built);
        }
        match (&purpose, outcome.is_ok()) {
            (Purpose::Open(_), true) => {
                self.path = path.to_path_buf();
                self.home_camera = Some(version.desc.camera);
                self.saved = Some(version.desc.clone());
                self.history.reset(Some(&version));
                self.good = Some(version.clone());
                self.restore(version);
            }
            (Purpose::Open(_), false) => {}
            (_, true) => {
                self.history.observe(Some(&version), gesture, describe);
                self.good = Some(version);
            }
            (Purpose::Edit | Purpose::Step(_), false) => {
                if let Some(good) = self.good.clone() {
                    self.restore(good);
                }
            }
        }
        match purpose {
            Purpose::Step(kept) if outcome.is_err() => {
                self.history = *kept;
                Purpose::Edit
            }
            other => other,
        }
    }

    /// Records the description as it is now, built or not (before an undo or redo, so a change
    /// still building is a step of its own).
    pub fn record(&mut self) {
        let version = self.version();
        self.history.observe(version.as_ref(), None, describe);
    }

    /// Blocks until the build running has ended, or `deadline` has passed (for tests and
    /// scripted screenshots); the app collects it on its next frame.
    ///
    /// # Errors
    /// The build was still running at the deadline.
    pub fn wait(&self, deadline: std::time::Duration) -> Result<(), String> {
        let start = web_time::Instant::now();
        while let Some(p) = &self.pending {
            if !p.task.is_running() {
                break;
            }
            if start.elapsed() > deadline {
                return Err(format!(
                    "the scene build was still running after {:.1} s",
                    deadline.as_secs_f64()
                ));
            }
            std::thread::sleep(std::time::Duration::from_millis(5));
        }
        Ok(())
    }
}

/// The files `recipe`'s scenes read: in a page, their download starts with the build.
#[cfg(target_arch = "wasm32")]
fn needs(recipe: &Recipe, path: &Path) -> Vec<PathBuf> {
    let dir = path.parent().unwrap_or(Path::new(""));
    let mut files = crate::scene::asset_paths(&recipe.render, dir);
    for d in recipe.split.iter().flatten() {
        files.extend(crate::scene::asset_paths(d, dir));
    }
    files
}

/// Builds the scenes of `recipe` (on a pool thread); in a page, each is described for the
/// render workers, which rebuild it from its text (`render::describe_scene`).
///
/// In a page, a shipped file not downloaded yet is stood in (`AssetCache::stand_in`; its
/// download is under way): such a scene renders on the page's thread alone (the workers have
/// not got the file) and is followed by a build with the file once it is in ([`Document::poll`]).
fn build(recipe: &Recipe, path: &Path, cache: &mut AssetCache) -> Result<Built, String> {
    let simd = recipe.simd;
    cache.stand_in(cfg!(target_arch = "wasm32"));
    let _ = cache.take_stood_in();
    let mut stood_in: Vec<PathBuf> = Vec::new();
    let mut notices: Vec<String> = Vec::new();
    let mut one = |desc: &SceneDesc, cache: &mut AssetCache| -> Result<Arc<Scene>, String> {
        let mut scene = build_scene(desc, path, cache).map_err(|e| e.to_string())?;
        for n in cache.notices() {
            if !notices.contains(n) {
                notices.push(n.clone());
            }
        }
        scene.settings.simd = simd;
        let scene = Arc::new(scene);
        let missing = cache.take_stood_in();
        #[cfg(target_arch = "wasm32")]
        if missing.is_empty() {
            crate::render::describe_scene(&scene, desc, path);
        }
        for m in missing {
            if !stood_in.contains(&m) {
                stood_in.push(m);
            }
        }
        Ok(scene)
    };
    let scene = one(&recipe.render, cache)?;
    let split = recipe.split.as_ref().map(|descs| {
        let mut scenes = Vec::with_capacity(3);
        for d in descs {
            scenes.push(one(d, cache)?);
        }
        <[Arc<Scene>; 3]>::try_from(scenes).map_err(|_| "three scenes".to_owned())
    });
    Ok(Built {
        scene,
        split,
        stood_in,
        notices,
    })
}
