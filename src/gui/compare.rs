//! Comparing antialiasing modes: the A/B split (two modes of the same scene side by side, each
//! with its time and its error against a high-spp reference) and the speed/error plot.

use super::live::LiveImage;
use crate::names::Named as _;
use crate::render::{Generation, RenderJob, RenderOptions, Task};
use crate::report::metrics::{EncodedImage, rmse};
use crate::report::{Mode, ProgressUpdate, ReferenceSettings, ReportConfig, Row, run_scene};
use crate::sampler::PixelSampler;
use crate::scene::{Scene, SceneDesc};
use crate::texture::Filter;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::AtomicBool;
use std::sync::mpsc::{Receiver, channel};
use std::time::Duration;

/// Samples per pixel of the reference both sides are measured against.
pub const REFERENCE_SPP: u32 = 256;

/// The reference of the split and of the speed panel: the report's, at [`REFERENCE_SPP`].
fn reference() -> ReferenceSettings {
    ReferenceSettings {
        spp: REFERENCE_SPP,
        ..ReferenceSettings::default()
    }
}

/// Two antialiasing modes of the same scene, rendered one after the other (so each time is
/// measured on an idle machine), then the reference.
pub struct AbSplit {
    /// Whether the viewport shows the split.
    pub enabled: bool,
    /// Where the divider is, as a fraction of the image width.
    pub split: f32,
    /// The modes left (A) and right (B), as the report names them.
    pub modes: [Mode; 2],
    /// Samples per pixel left (A) and right (B).
    pub spp: [u32; 2],
    jobs: [Option<RenderJob>; 3],
    waiting: [Option<Arc<Scene>>; 3],
    live: [LiveImage; 2],
    errors: [Option<f64>; 2],
    /// The display exposure of the reference, so errors are measured on what is displayed.
    exposure_scale: f32,
    generation: Generation,
    message: Option<String>,
}

impl Default for AbSplit {
    fn default() -> Self {
        Self {
            enabled: false,
            split: 0.5,
            modes: [
                Mode::new(Filter::Nearest, PixelSampler::Regular),
                Mode::new(Filter::Bilinear, PixelSampler::MultiJittered),
            ],
            spp: [1, 16],
            jobs: [None, None, None],
            waiting: [None, None, None],
            live: [LiveImage::new("ab-a"), LiveImage::new("ab-b")],
            errors: [None, None],
            exposure_scale: 1.0,
            generation: Generation::new(),
            message: None,
        }
    }
}

impl AbSplit {
    /// What the split renders of `desc`: side A, side B and the reference.
    #[must_use]
    pub fn descs(&self, desc: &SceneDesc) -> [SceneDesc; 3] {
        [
            self.modes[0].apply(desc, self.spp[0]),
            self.modes[1].apply(desc, self.spp[1]),
            reference().desc(desc, None, None),
        ]
    }

    /// Starts side A of the scenes built from [`AbSplit::descs`] (B and the reference follow),
    /// or shows why they did not build.
    pub fn start_built(
        &mut self,
        scenes: Result<[Arc<Scene>; 3], String>,
        generation: &Generation,
    ) {
        self.stop();
        self.generation = generation.clone();
        match scenes {
            Ok(scenes) => {
                self.waiting = scenes.map(Some);
                self.message = None;
                self.start(0);
            }
            Err(e) => self.message = Some(e),
        }
    }

    fn start(&mut self, slot: usize) {
        if let Some(scene) = self.waiting[slot].take() {
            self.exposure_scale = scene.settings.exposure_scale;
            match RenderJob::start(scene, RenderOptions::default(), &self.generation) {
                Ok(job) => self.jobs[slot] = Some(job),
                Err(e) => self.message = Some(e.to_string()),
            }
            if let Some(live) = self.live.get_mut(slot) {
                live.reset();
            }
        }
    }

    /// Stops every job of the split.
    pub fn stop(&mut self) {
        // Dropping a job cancels it without waiting for its task.
        self.jobs = [None, None, None];
        self.waiting = [None, None, None];
        self.errors = [None, None];
    }

    /// Uploads new images, starts the next job when one finishes, and computes the errors once
    /// the reference is done. Returns whether anything is still rendering.
    pub fn poll(&mut self, ctx: &egui::Context) -> bool {
        if !self.enabled {
            return false;
        }
        for (job, live) in self.jobs.iter().zip(&mut self.live) {
            if let Some(job) = job {
                live.update(ctx, job);
            }
        }
        let done = |j: &Option<RenderJob>| j.as_ref().is_some_and(|j| j.progress().finished);
        if done(&self.jobs[0]) && self.jobs[1].is_none() {
            self.start(1);
        }
        if done(&self.jobs[1]) && self.jobs[2].is_none() {
            self.start(2);
        }
        if done(&self.jobs[2]) && self.errors[0].is_none() {
            let reference = self.jobs[2].as_ref().and_then(RenderJob::film);
            for side in 0..2 {
                let film = self.jobs[side].as_ref().and_then(RenderJob::film);
                if let (Some(f), Some(r)) = (film, &reference) {
                    let encode = |f| EncodedImage::from_film(f, self.exposure_scale);
                    self.errors[side] = rmse(&encode(r), &encode(&f));
                }
            }
        }
        self.jobs.iter().any(|j| {
            j.as_ref()
                .is_some_and(|j| !j.progress().finished && !j.progress().cancelled)
        }) || self.waiting.iter().any(Option::is_some)
    }

    /// The texture of side 0 (A) or 1 (B).
    #[must_use]
    pub fn texture(&self, side: usize) -> Option<&egui::TextureHandle> {
        self.live.get(side).and_then(LiveImage::texture)
    }

    /// Time spent tracing a side (full passes, no preview), once it is done.
    fn time(&self, side: usize) -> Option<Duration> {
        let p = self.jobs.get(side)?.as_ref()?.progress();
        if !p.finished || p.rays_per_second <= 0.0 {
            return None;
        }
        let rays = f64::from(p.spp_done) * self.pixels(side)?;
        Some(Duration::from_secs_f64(rays / p.rays_per_second))
    }

    fn pixels(&self, side: usize) -> Option<f64> {
        let film = self.jobs.get(side)?.as_ref()?.film()?;
        Some(f64::from(film.width()) * f64::from(film.height()))
    }

    /// The caption drawn over a side: its mode, time and error.
    #[must_use]
    pub fn caption(&self, side: usize) -> String {
        let name = ["A", "B"].get(side).copied().unwrap_or("?");
        let mut s = format!("{name}: {} {} spp", self.modes[side].name(), self.spp[side]);
        match self.time(side) {
            Some(t) => {
                let _ = write!(s, " · {:.0} ms", t.as_secs_f64() * 1e3);
            }
            None => s.push_str(" · rendering"),
        }
        if let Some(e) = self.errors[side] {
            let _ = write!(s, " · RMSE {e:.4}");
        }
        s
    }

    /// The status line while the split is shown.
    #[must_use]
    pub fn status(&self) -> String {
        if let Some(m) = &self.message {
            return m.clone();
        }
        let stage = if self.errors[0].is_some() {
            "done".to_owned()
        } else if self.jobs[2].is_some() {
            let r = reference();
            format!(
                "rendering the reference ({} spp, {}, {}) for the error",
                r.spp,
                r.filter.name(),
                r.sampler.name()
            )
        } else if self.jobs[1].is_some() {
            "rendering B".to_owned()
        } else {
            "rendering A".to_owned()
        };
        format!(
            "A/B split · {stage} · errors are RMSE against the reference on display (sRGB) values, as texplore report measures"
        )
    }

    /// The two modes' controls (sampler, spp, filter); a change changes [`AbSplit::descs`], so
    /// the split is built and rendered again.
    pub fn controls(&mut self, ui: &mut egui::Ui) {
        for side in 0..2 {
            let name = ["A", "B"][side];
            ui.horizontal(|ui| {
                let (m, spp) = (&mut self.modes[side], &mut self.spp[side]);
                super::widgets::enum_combo(ui, &format!("{name} sampler"), &mut m.sampler);
                ui.horizontal(|ui| {
                    let l = ui.label(format!("{name} spp"));
                    ui.add(egui::DragValue::new(spp).range(1..=1024))
                        .labelled_by(l.id);
                });
                super::widgets::enum_combo(ui, &format!("{name} filter"), &mut m.filter);
            });
        }
    }
}

/// What the measuring task tells the window as it goes.
enum Measured {
    /// One (mode, spp) measured.
    Row(Box<Row>),
    /// Camera samples done and planned.
    Progress(u64, u64),
}

/// A measurement running on the render pool: its rows and progress as they come, and the task
/// (whose result says whether it failed).
struct Measuring {
    updates: Receiver<Measured>,
    task: Task<Result<(), String>>,
}

/// The speed/error panel: the report's runs (`report::run_scene`) for the current scene at a
/// small resolution, on demand as a [`Task`] on the render pool, plotted live as time against
/// RMSE.
#[derive(Default)]
pub struct SpeedPanel {
    /// Whether the window is open.
    pub open: bool,
    rows: Vec<Row>,
    running: Option<Measuring>,
    progress: (u64, u64),
    error: Option<String>,
    /// Which path the measured renders' primary rays take.
    simd: crate::scene::SimdMode,
}

/// The colour of the `i`-th mode's curve: egui_plot's own automatic palette (hues a golden
/// angle apart), given explicitly so a mode's line, points and legend entry share it.
fn series_color(i: usize) -> egui::Color32 {
    let hue = (i as f32 * (std::f32::consts::GOLDEN_RATIO - 1.0)).fract();
    egui::ecolor::Hsva::new(hue, 0.85, 0.5, 1.0).into()
}

/// Sample counts measured per mode.
const SPEED_SPP: [u32; 5] = [1, 2, 4, 8, 16];
/// Resolution of the measurement renders.
const SPEED_SIZE: (u32, u32) = (160, 120);

impl SpeedPanel {
    /// A closed panel whose measurements take the path `simd`.
    #[must_use]
    pub fn new(simd: crate::scene::SimdMode) -> Self {
        Self {
            simd,
            ..Self::default()
        }
    }

    fn measure(&mut self, desc: &SceneDesc, path: &Path) {
        let (tx, rx) = channel();
        let (desc, path): (SceneDesc, PathBuf) = (desc.clone(), path.to_path_buf());
        let config = ReportConfig {
            modes: Mode::default_set(),
            spp: SPEED_SPP.to_vec(),
            // The median of three runs: a shared machine's timing noise shows otherwise.
            repeat: 3,
            time_budget: Duration::from_millis(500),
            width: Some(SPEED_SIZE.0),
            height: Some(SPEED_SIZE.1),
            reference: reference(),
            heatmap_spp: None,
            simd: self.simd,
        };
        let work = move |stop: &AtomicBool| {
            let mut progress = move |u: &ProgressUpdate<'_>| {
                if let Some(row) = u.row {
                    let _ = tx.send(Measured::Row(Box::new(row.clone())));
                }
                let _ = tx.send(Measured::Progress(u.done, u.total));
            };
            let name = path
                .file_stem()
                .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
            let r = run_scene(&name, &desc, &path, &config, &mut progress, stop)
                .map(|_| ())
                .map_err(|e| e.to_string());
            Some(r)
        };
        match Task::spawn(work) {
            Ok(task) => {
                self.rows.clear();
                self.progress = (0, 1);
                self.error = None;
                self.running = Some(Measuring { updates: rx, task });
            }
            Err(e) => self.error = Some(format!("cannot start the measurement: {e}")),
        }
    }

    fn receive(&mut self) {
        let Some(m) = &self.running else {
            return;
        };
        while let Ok(u) = m.updates.try_recv() {
            match u {
                Measured::Row(r) => self.rows.push(*r),
                Measured::Progress(d, t) => self.progress = (d, t.max(1)),
            }
        }
        if !m.task.is_running() {
            self.error = match m.task.take() {
                Some(r) => r.err(),
                None => m
                    .task
                    .failure()
                    .map(|f| format!("the measurement stopped: {f}")),
            };
            self.running = None;
        }
    }

    /// The window, when open.
    pub fn window(&mut self, ctx: &egui::Context, desc: Option<&SceneDesc>, path: &Path) {
        self.receive();
        if !self.open {
            // Dropping the task cancels it.
            self.running = None;
            return;
        }
        let mut open = self.open;
        egui::Window::new("Speed and error")
            .open(&mut open)
            .default_pos([340.0, 80.0])
            .default_size([560.0, 420.0])
            .show(ctx, |ui| {
                ui.horizontal(|ui| {
                    let busy = self.running.is_some();
                    if ui
                        .add_enabled(!busy && desc.is_some(), egui::Button::new("Measure"))
                        .on_hover_text("Time every filter with the jittered sampler and every sampler with the bilinear filter at 1 to 16 spp (160 x 120), and compare each with a 256-spp reference")
                        .clicked()
                        && let Some(d) = desc
                    {
                        self.measure(d, path);
                    }
                    if busy {
                        let (d, t) = self.progress;
                        ui.add(
                            egui::ProgressBar::new(d as f32 / t as f32)
                                .desired_width(200.0)
                                .show_percentage(),
                        );
                        if ui.button("Stop").on_hover_text("Cancel the measurement").clicked()
                            && let Some(m) = &self.running
                        {
                            m.task.cancel();
                        }
                        ctx.request_repaint_after(Duration::from_millis(100));
                    }
                });
                if let Some(e) = &self.error {
                    ui.colored_label(egui::Color32::LIGHT_RED, e);
                }
                ui.label(format!(
                    "log-log: x = log10 of the render time (ms) at {}x{}, y = log10 of the RMSE against {REFERENCE_SPP} spp; points are 1, 2, 4, 8, 16 spp (the report's runs).",
                    SPEED_SIZE.0, SPEED_SIZE.1
                ));
                let mut modes: Vec<Mode> = Vec::new();
                for r in &self.rows {
                    if !modes.contains(&r.mode) {
                        modes.push(r.mode);
                    }
                }
                egui_plot::Plot::new("speed-error")
                    .legend(
                        // Small text in the bottom-left corner: fast and accurate, where no
                        // mode's curve goes (curves fall from top left to bottom right), so the
                        // eleven entries hide no point. In insertion order, the report's.
                        egui_plot::Legend::default()
                            .text_style(egui::TextStyle::Small)
                            .position(egui_plot::Corner::LeftBottom)
                            .follow_insertion_order(true),
                    )
                    .x_axis_label("log10 time (ms)")
                    .y_axis_label("log10 RMSE")
                    .show(ui, |plot| {
                        for (i, mode) in modes.iter().enumerate() {
                            let pts: Vec<[f64; 2]> = self
                                .rows
                                .iter()
                                .filter(|r| r.mode == *mode && r.metrics.rmse > 0.0)
                                .map(|r| {
                                    [
                                        (r.time.as_secs_f64() * 1e3).max(1e-3).log10(),
                                        r.metrics.rmse.log10(),
                                    ]
                                })
                                .collect();
                            if pts.is_empty() {
                                continue;
                            }
                            // One colour for the mode's line, points and legend entry: left
                            // automatic, egui_plot gives the line and the points two colours
                            // and draws their shared legend entry grey.
                            let color = series_color(i);
                            plot.line(egui_plot::Line::new(mode.name(), pts.clone()).color(color));
                            plot.points(
                                egui_plot::Points::new(mode.name(), pts)
                                    .radius(3.0)
                                    .color(color),
                            );
                        }
                    });
            });
        self.open = open;
    }
}
