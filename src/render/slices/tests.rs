use super::*;
use crate::render::{RenderJob, render_blocking};
use crate::scene::{AdaptiveDesc, AssetCache, DEFAULT_ADAPTIVE_THRESHOLD, SceneDesc, build_scene};
use std::cell::RefCell;
use std::collections::VecDeque;
use std::path::Path;
use std::rc::Rc;

const EARTH: &str = "presets/earth.ron";

fn earth_desc(spp: u32, adaptive: bool) -> SceneDesc {
    let mut desc = crate::scene::load_preset(Path::new(EARTH)).unwrap();
    desc.render.width = 96;
    desc.render.height = 61;
    desc.render.spp = spp;
    desc.render.adaptive = adaptive.then_some(AdaptiveDesc {
        max_spp: 8,
        threshold: DEFAULT_ADAPTIVE_THRESHOLD,
    });
    desc
}

fn build(desc: &SceneDesc, path: &str) -> Arc<Scene> {
    Arc::new(build_scene(desc, Path::new(path), &mut AssetCache::new()).unwrap())
}

fn earth(spp: u32, adaptive: bool) -> Scene {
    let desc = earth_desc(spp, adaptive);
    build_scene(&desc, Path::new(EARTH), &mut AssetCache::new()).unwrap()
}

/// Steps `render` with deadlines already past: one preview or tile per step.
fn run_in_single_tiles(render: &mut SlicedRender) -> usize {
    let mut farm = Farm::new();
    let mut steps = 0;
    while render.step(Instant::now(), &mut farm) {
        steps += 1;
    }
    steps
}

#[test]
fn a_render_in_slices_is_the_render_at_once() {
    for adaptive in [false, true] {
        let scene = Arc::new(earth(3, adaptive));
        let out = Arc::new(Shared::default());
        let generation = Generation::new();
        let options = RenderOptions::default();
        let mut sliced =
            SlicedRender::new(scene.clone(), options, generation, 0, out.clone(), None);
        let steps = run_in_single_tiles(&mut sliced);
        // Two previews (8 and 4), then 8 tiles of 61 rows per pass.
        assert!(steps >= 2 + 3 * 8 - 1, "{steps}");
        let p = out.lock().progress;
        assert!(p.finished && !p.cancelled);
        let whole = render_blocking(&scene, |_| {});
        let film = out.lock().film.clone().unwrap();
        assert_eq!(film.pixels(), whole.pixels(), "adaptive {adaptive}");
        let job = RenderJob::start(scene, options, &Generation::new()).unwrap();
        assert_eq!(p.spp_done, job.wait().spp_done);
    }
}

#[test]
fn a_newer_generation_stops_a_sliced_render_at_the_next_tile() {
    let scene = Arc::new(earth(4, false));
    let out = Arc::new(Shared::default());
    let generation = Generation::new();
    let options = RenderOptions {
        preview: false,
        ..RenderOptions::default()
    };
    let mut farm = Farm::new();
    let mut sliced = SlicedRender::new(scene, options, generation.clone(), 0, out.clone(), None);
    assert!(sliced.step(Instant::now(), &mut farm));
    generation.bump();
    assert!(!sliced.step(Instant::now() + Duration::from_mins(1), &mut farm));
    assert!(out.lock().progress.cancelled);
    assert_eq!(out.lock().serial, 0, "nothing published");
}

// --- Workers, in process: each a `Worker` behind a port that queues its messages. ---

type Inbox = Rc<RefCell<VecDeque<Vec<u8>>>>;

struct Local(Inbox);

impl Port for Local {
    fn post(&self, message: Vec<u8>) {
        self.0.borrow_mut().push_back(message);
    }
}

/// Workers in this thread: what the page's Web Workers do, message for message.
struct Pool {
    farm: Farm,
    workers: Vec<(Worker, Inbox)>,
    /// Chunks each worker rendered.
    chunks: Vec<usize>,
}

impl Pool {
    fn new(n: usize) -> Self {
        let mut farm = Farm::new();
        let mut workers = Vec::new();
        for _ in 0..n {
            let inbox = Inbox::default();
            farm.add(Box::new(Local(inbox.clone())));
            workers.push((Worker::new(|| 0), inbox));
        }
        Self {
            farm,
            workers,
            chunks: vec![0; n],
        }
    }

    /// Every worker reads its messages, then renders at most one chunk; the answers go to the
    /// farm. Returns whether anything happened.
    fn deliver(&mut self) -> bool {
        let mut any = false;
        for (i, (worker, inbox)) in self.workers.iter_mut().enumerate() {
            while let Some(m) = inbox.borrow_mut().pop_front() {
                any = true;
                for answer in worker.receive(&m).unwrap() {
                    self.farm.receive(i, &answer).unwrap();
                }
            }
            if let Some(answer) = worker.work() {
                any = true;
                self.chunks[i] += 1;
                self.farm.receive(i, &answer).unwrap();
            }
        }
        any
    }
}

/// A sliced render of `desc` (read as from `path`) on `pool`'s workers: the page's thread may
/// render a tile per step only while `page_helps`.
fn on_workers(desc: &SceneDesc, path: &str, pool: &mut Pool, page_helps: bool) -> Arc<Film> {
    let scene = build(desc, path);
    describe(&scene, desc, Path::new(path));
    let source = source_of(&scene).expect("described");
    let out = Arc::new(Shared::default());
    let mut r = SlicedRender::new(
        scene,
        RenderOptions::default(),
        Generation::new(),
        0,
        out.clone(),
        Some(source),
    );
    for _ in 0..100_000 {
        if page_helps {
            r.step(Instant::now(), &mut pool.farm);
        } else {
            while matches!(r.stage, Stage::Preview(_)) {
                r.step(Instant::now(), &mut pool.farm);
            }
            r.pump(&mut pool.farm);
        }
        if r.is_done() {
            break;
        }
        pool.deliver();
    }
    assert!(r.is_done(), "the render ends");
    let p = out.lock().progress;
    assert!(p.finished && !p.cancelled, "{p:?}");
    out.lock().film.clone().unwrap()
}

#[test]
fn a_render_on_workers_is_the_threaded_render_bit_for_bit() {
    for adaptive in [false, true] {
        let desc = earth_desc(4, adaptive);
        let whole = render_blocking(&build(&desc, EARTH), |_| {});
        for (workers, page_helps) in [(1, false), (2, false), (3, true)] {
            let mut pool = Pool::new(workers);
            let film = on_workers(&desc, EARTH, &mut pool, page_helps);
            assert!(
                film.pixels() == whole.pixels() && film.stats() == whole.stats(),
                "adaptive {adaptive}, {workers} workers, the page helping: {page_helps}"
            );
            assert!(
                pool.chunks.iter().all(|&c| c > 0),
                "every worker rendered: {:?}",
                pool.chunks
            );
        }
    }
}

#[test]
fn every_shipped_preset_renders_the_same_on_workers() {
    let mut pool = Pool::new(2);
    for path in crate::scene::list_presets(Path::new("presets")).unwrap() {
        let mut desc = crate::scene::load_preset(&path).unwrap();
        desc.render.width = 48;
        desc.render.height = 20;
        desc.render.spp = 2;
        if let Some(a) = &mut desc.render.adaptive {
            a.max_spp = 3;
        }
        let p = path.to_string_lossy().into_owned();
        let whole = render_blocking(&build(&desc, &p), |_| {});
        let film = on_workers(&desc, &p, &mut pool, false);
        assert!(film.pixels() == whole.pixels(), "{p}");
    }
}

#[test]
fn an_edit_cancels_the_chunks_waiting_in_workers() {
    let desc = earth_desc(16, false);
    let scene = build(&desc, EARTH);
    describe(&scene, &desc, Path::new(EARTH));
    let mut pool = Pool::new(1);
    let generation = Generation::new();
    let out = Arc::new(Shared::default());
    let options = RenderOptions {
        preview: false,
        ..RenderOptions::default()
    };
    let source = source_of(&scene);
    let mut r = SlicedRender::new(scene, options, generation.clone(), 0, out.clone(), source);
    // The worker builds the scene, then takes two chunks.
    r.pump(&mut pool.farm);
    let (worker, inbox) = &mut pool.workers[0];
    while let Some(m) = inbox.borrow_mut().pop_front() {
        for a in worker.receive(&m).unwrap() {
            pool.farm.receive(0, &a).unwrap();
        }
    }
    r.pump(&mut pool.farm);
    while let Some(m) = inbox.borrow_mut().pop_front() {
        assert!(worker.receive(&m).unwrap().is_empty());
    }
    assert!(worker.has_work(), "chunks wait in the worker");
    generation.bump();
    r.pump(&mut pool.farm);
    assert!(r.is_done() && out.lock().progress.cancelled);
    while let Some(m) = inbox.borrow_mut().pop_front() {
        worker.receive(&m).unwrap();
    }
    assert!(!worker.has_work(), "the edit dropped the waiting chunks");
    assert_eq!(out.lock().serial, 0, "nothing published");
}

#[test]
fn a_lost_worker_s_tiles_are_rendered_again() {
    let desc = earth_desc(3, false);
    let whole = render_blocking(&build(&desc, EARTH), |_| {});
    let scene = build(&desc, EARTH);
    describe(&scene, &desc, Path::new(EARTH));
    let mut pool = Pool::new(2);
    let out = Arc::new(Shared::default());
    let source = source_of(&scene);
    let options = RenderOptions {
        preview: false,
        ..RenderOptions::default()
    };
    let mut r = SlicedRender::new(scene, options, Generation::new(), 0, out.clone(), source);
    let mut lost = false;
    for round in 0..100_000 {
        r.pump(&mut pool.farm);
        if r.is_done() {
            break;
        }
        if round == 3 && !lost {
            // Worker 1 crashes with chunks in hand: they go back to the render.
            pool.farm.lost(1);
            pool.workers[1].1.borrow_mut().clear();
            pool.workers.truncate(1);
            lost = true;
        }
        if !pool.deliver() {
            r.step(Instant::now(), &mut pool.farm);
        }
    }
    assert!(lost && r.is_done());
    let film = out.lock().film.clone().unwrap();
    assert!(film.pixels() == whole.pixels());
}

#[test]
fn hostile_messages_are_refused_not_trusted() {
    let mut farm = Farm::new();
    farm.add(Box::new(Local(Inbox::default())));
    assert!(farm.receive(0, b"\xff\xff\xff").is_err());
    let mut w = Worker::new(|| 0);
    assert!(w.receive(&[200, 1, 2]).is_err());
    // A chunk for a scene the worker has not built is given back, not rendered.
    let chunk = protocol::encode(&ToWorker::Render(Chunk {
        job: 1,
        scene: 99,
        pass: 0,
        first: 0,
        tiles: 1,
        mask: None,
    }));
    w.receive(&chunk).unwrap();
    let answer = w.work().unwrap();
    assert!(matches!(
        protocol::decode::<FromWorker>(&answer).unwrap(),
        FromWorker::Skipped { job: 1, .. }
    ));
    // Rows whose lengths do not match their pixel count are not added to a film.
    let rows = TileRows {
        pixels: 4,
        sums: vec![0; 3],
        stats: Vec::new(),
        keys: Vec::new(),
    };
    assert!(!rows.is_whole());
}

#[test]
fn a_scene_a_worker_cannot_build_renders_on_the_page_and_says_why() {
    // The workers read the scene's files from a folder that has none of them: they answer
    // that they cannot build it, and the page's thread renders it alone, the same film.
    let desc = earth_desc(2, false);
    let whole = render_blocking(&build(&desc, EARTH), |_| {});
    let scene = build(&desc, EARTH);
    let dir = tempfile::tempdir().unwrap();
    describe(&scene, &desc, &dir.path().join("earth.ron"));
    let mut pool = Pool::new(2);
    let out = Arc::new(Shared::default());
    let source = source_of(&scene);
    let mut r = SlicedRender::new(
        scene,
        RenderOptions::default(),
        Generation::new(),
        0,
        out.clone(),
        source,
    );
    for _ in 0..100_000 {
        r.step(Instant::now(), &mut pool.farm);
        if r.is_done() {
            break;
        }
        pool.deliver();
    }
    assert!(r.is_done());
    let film = out.lock().film.clone().unwrap();
    assert!(film.pixels() == whole.pixels());
    let errors = pool.farm.take_errors();
    assert_eq!(errors.len(), 2, "{errors:?}");
    assert!(
        errors[0].starts_with("a render worker could not build the scene: ")
            && errors[0].contains("earth_2048x1024.jpg"),
        "{errors:?}"
    );
    assert!(pool.farm.take_errors().is_empty(), "said once");
    // Both workers alive, having rendered nothing.
    assert_eq!(pool.farm.memory(), vec![(0, 0, true); 2]);
}

#[test]
fn a_scene_no_render_uses_is_dropped_in_the_workers() {
    let desc = earth_desc(1, false);
    let mut pool = Pool::new(1);
    let scene = build(&desc, EARTH);
    describe(&scene, &desc, Path::new(EARTH));
    let id = source_of(&scene).unwrap().id;
    pool.farm.prepare(&source_of(&scene).unwrap());
    pool.deliver();
    assert_eq!(pool.farm.ready(id), 1, "built");
    let chunk = |job| {
        protocol::encode(&ToWorker::Render(Chunk {
            job,
            scene: id,
            pass: 0,
            first: 0,
            tiles: 1,
            mask: None,
        }))
    };
    let answer = |pool: &mut Pool, job| {
        let (worker, inbox) = &mut pool.workers[0];
        while let Some(m) = inbox.borrow_mut().pop_front() {
            worker.receive(&m).unwrap();
        }
        worker.receive(&chunk(job)).unwrap();
        protocol::decode::<FromWorker>(&worker.work().unwrap()).unwrap()
    };
    pool.farm.forget_unused();
    assert!(matches!(
        answer(&mut pool, 1),
        FromWorker::Rendered { job: 1, .. }
    ));
    // The window dropped the scene (an edit built another): the worker drops its copy.
    drop(scene);
    pool.farm.forget_unused();
    let a = answer(&mut pool, 2);
    assert!(matches!(a, FromWorker::Skipped { job: 2, .. }), "{a:?}");
}
