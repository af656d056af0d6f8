//! `agesim --bench-ui`: a scripted run of the real editor window that measures what the
//! artist feels, printed as a table:
//! 1. the UI's frame interval while a 4096² bake runs on the worker;
//! 2. the time from an age-slider change (as a drag: the view in its moving state) until
//!    the frame that shows its bake (preview) has been drawn and presented, and the same
//!    for a shape slider (`shape.cheeks`: the shape field is made again);
//! 3. frames per second while the age plays (scrubbing) with the default head's hair.
//!
//! All in the editor's default layout (the 3D view beside the map view), at the window's
//! default size; scrubbing is measured once more with the 3D view alone, and the slider
//! and the scrubbing once more while a thread of the benchmark's own keeps one core busy
//! (as a second program would: a DCC open beside the editor). The moving frames' quality
//! is the frame-time governor's (`editor::governor`): each scrubbing row says the
//! resolution it settled on.
//!
//! Two yardsticks are measured in the same run: the idle editor's frame interval, and the
//! adapter's floor, the interval of frames in which the app paints nothing (the window is
//! only cleared and presented).
//!
//! Each phase drives the app through the same calls the widgets make.

use std::time::Instant;

/// The phases, in order.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Phase {
    /// Waiting for the first bakes and the first frames that show them.
    Warmup,
    /// Frames with nothing baking and the view still.
    Idle,
    /// Frames in which the app paints nothing (the window cleared to the panel colour):
    /// what this adapter costs per egui frame, whatever the editor draws (the floor).
    Floor,
    BigBake,
    Slider,
    /// A shape region's strength dragged (a new shape field each move).
    ShapeSlider,
    Scrub,
    /// Scrubbing again with the 3D view alone.
    ScrubHeadOnly,
    /// The slider and the scrubbing again (both views), one core kept busy.
    SliderBusy,
    ScrubBusy,
    Done,
}

pub struct BenchUi {
    phase: Phase,
    phase_start: Instant,
    last_frame: Instant,
    intervals_ms: Vec<f64>,
    big_bake_frames: Vec<f64>,
    slider_latencies_ms: Vec<f64>,
    /// The worker's time for each of those bakes (its report), ms.
    slider_bakes_ms: Vec<f64>,
    /// The frames' intervals (ms) and the 3D view's resolution scale while a slider moves.
    slider_frames: Vec<(f64, f32)>,
    /// The slider move waiting to be seen: when it was sent, its job id, and whether the
    /// frame drawing its bake has started (the next frame begins once it is presented).
    slider_sent: Option<(Instant, u64, bool)>,
    scrub_frames: usize,
    scrub_hairs: Vec<u32>,
    /// The most thinning seen while scrubbing: one hair in this many drawn.
    scrub_sparse: u32,
    scrub_years: Vec<f32>,
    results: Vec<String>,
    idle_ms: f64,
    floor_ms: f64,
    /// The 3D view's resolution in each scrubbing frame.
    scrub_scales: Vec<f32>,
    /// The thread keeping one core busy, and its stop flag.
    burner: Option<Burner>,
}

/// A thread that keeps one core busy until dropped.
struct Burner {
    stop: std::sync::Arc<std::sync::atomic::AtomicBool>,
    thread: Option<std::thread::JoinHandle<()>>,
}

impl Burner {
    fn start() -> Self {
        use std::sync::atomic::{AtomicBool, Ordering};
        let stop = std::sync::Arc::new(AtomicBool::new(false));
        let flag = stop.clone();
        let thread = std::thread::spawn(move || {
            let mut x = 1u64;
            while !flag.load(Ordering::Relaxed) {
                for _ in 0..100_000 {
                    x = std::hint::black_box(x.wrapping_mul(6364136223846793005).wrapping_add(1));
                }
            }
        });
        Self {
            stop,
            thread: Some(thread),
        }
    }
}

impl Drop for Burner {
    fn drop(&mut self) {
        self.stop.store(true, std::sync::atomic::Ordering::Relaxed);
        if let Some(t) = self.thread.take() {
            let _ = t.join();
        }
    }
}

/// What the bench asks the app to do this frame.
pub enum Action {
    None,
    /// Bake the maps at full size 4096².
    BigBake,
    /// Set the age (preview bake), remembering the job id.
    SetAge(f32),
    /// Drag a project field to a value (preview bake), remembering the job id.
    Drag(&'static str, f32),
    Play,
    /// Show the 3D view alone (no map view) and play.
    PlayHeadOnly,
    Stop,
    /// Stop and show both views again.
    StopBoth,
    Quit,
}

/// Idle frames measured for the baseline.
const IDLE_FRAMES: usize = 40;

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn max(v: &[f64]) -> f64 {
    v.iter().copied().fold(f64::NAN, f64::max)
}

impl BenchUi {
    pub fn new() -> Self {
        Self {
            phase: Phase::Warmup,
            phase_start: Instant::now(),
            last_frame: Instant::now(),
            intervals_ms: Vec::new(),
            big_bake_frames: Vec::new(),
            slider_latencies_ms: Vec::new(),
            slider_bakes_ms: Vec::new(),
            slider_frames: Vec::new(),
            slider_sent: None,
            scrub_frames: 0,
            scrub_hairs: Vec::new(),
            scrub_sparse: 1,
            scrub_years: Vec::new(),
            results: Vec::new(),
            idle_ms: f64::NAN,
            floor_ms: f64::NAN,
            scrub_scales: Vec::new(),
            burner: None,
        }
    }

    /// Called once per frame with the worker state: whether it is idle, the newest job id
    /// that reported and how long its bake took (ms, on the worker), the hairs: count(t)
    /// and one in how many of them the frame drew, the age shown and the 3D view's
    /// resolution scale. Returns what to do.
    pub fn frame(
        &mut self,
        idle: bool,
        (reported, bake_ms): (u64, f64),
        latest: u64,
        (hairs, sparse): (u32, u32),
        years: f32,
        scale: f32,
    ) -> Action {
        let now = Instant::now();
        let dt = (now - self.last_frame).as_secs_f64() * 1e3;
        self.last_frame = now;
        let elapsed = (now - self.phase_start).as_secs_f64();
        match self.phase {
            Phase::Warmup => {
                // The worker is idle and the uploads and first frames are done.
                if !idle {
                    self.phase_start = now;
                } else if elapsed > 1.0 {
                    self.next(Phase::Idle);
                }
            }
            Phase::Idle => {
                self.intervals_ms.push(dt);
                if self.intervals_ms.len() >= IDLE_FRAMES {
                    let frames = self.intervals_ms.len();
                    let med = median(&mut self.intervals_ms);
                    self.idle_ms = med;
                    self.results.push(format!(
                        "| baseline: UI frame interval, nothing baking, view still ({frames} frames) | median {med:.1} ms | — |"
                    ));
                    self.intervals_ms.clear();
                    self.next(Phase::Floor);
                }
            }
            Phase::Floor => {
                // The first floor frame's interval still holds a whole editor frame: it
                // is dropped.
                self.intervals_ms.push(dt);
                if self.intervals_ms.len() > IDLE_FRAMES {
                    self.intervals_ms.remove(0);
                    let med = median(&mut self.intervals_ms);
                    self.floor_ms = med;
                    self.results.push(format!(
                        "| adapter floor: an empty egui frame (clear and present) ({IDLE_FRAMES} frames) | median {med:.1} ms ({:.0} % of the baseline) | — |",
                        100.0 * med / self.idle_ms
                    ));
                    self.intervals_ms.clear();
                    self.next(Phase::BigBake);
                    return Action::BigBake;
                }
            }
            Phase::BigBake => {
                if elapsed > 0.05 {
                    self.big_bake_frames.push(dt);
                }
                if idle && elapsed > 0.2 {
                    let frames = self.big_bake_frames.len();
                    let worst = max(&self.big_bake_frames);
                    let med = median(&mut self.big_bake_frames);
                    self.results.push(format!(
                        "| UI frame interval while a 4096² bake runs ({elapsed:.1} s, {frames} frames) | median {med:.1} ms ({:.1}× the baseline, {:.1}× the floor), worst {worst:.1} ms | ≤ 50 ms |",
                        med / self.idle_ms,
                        med / self.floor_ms
                    ));
                    self.next(Phase::Slider);
                }
            }
            Phase::ShapeSlider => {
                self.slider_frames.push((dt, scale));
                if self.waiting(now, reported, bake_ms) {
                    return Action::None;
                }
                let k = self.slider_latencies_ms.len();
                if k < 12 {
                    self.slider_sent = Some((now, latest + 1, false));
                    // Round the default strength (1), a new field each move; the last
                    // move back to it, for the phases after.
                    let value = if k == 11 { 1.0 } else { 0.7 + 0.05 * k as f32 };
                    return Action::Drag("shape.cheeks", value);
                }
                let worst = max(&self.slider_latencies_ms);
                let med = median(&mut self.slider_latencies_ms);
                let bake = median(&mut self.slider_bakes_ms);
                self.slider_bakes_ms.clear();
                let frames = self.slider_frames_summary();
                self.results.push(format!(
                    "| shape slider (`shape.cheeks`) dragged → the frame showing it presented (a preview bake at the governor's size with a new shape field, 12 moves) | median {med:.0} ms, worst {worst:.0} ms (the worker's bake of each: median {bake:.0} ms; {frames}) | ≤ 150 ms |"
                ));
                self.slider_latencies_ms.clear();
                self.next(Phase::Scrub);
                return Action::Play;
            }
            Phase::Slider | Phase::SliderBusy => {
                self.slider_frames.push((dt, scale));
                if self.waiting(now, reported, bake_ms) {
                    return Action::None;
                }
                if self.slider_latencies_ms.len() < 12 {
                    let k = self.slider_latencies_ms.len();
                    self.slider_sent = Some((now, latest + 1, false));
                    return Action::SetAge(0.2 + 0.05 * k as f32);
                }
                let worst = max(&self.slider_latencies_ms);
                let med = median(&mut self.slider_latencies_ms);
                let bake = median(&mut self.slider_bakes_ms);
                self.slider_bakes_ms.clear();
                let (busy, target) = if self.phase == Phase::SliderBusy {
                    (", one core kept busy", "≤ 100 ms")
                } else {
                    ("", "≤ 80 ms")
                };
                let frames = self.slider_frames_summary();
                self.results.push(format!(
                    "| age slider dragged → the frame showing it presented (a preview bake at the governor's size, 12 moves{busy}) | median {med:.0} ms, worst {worst:.0} ms (the worker's bake of each: median {bake:.0} ms; {frames}) | {target} |"
                ));
                self.slider_latencies_ms.clear();
                if self.phase == Phase::SliderBusy {
                    self.next(Phase::ScrubBusy);
                    return Action::Play;
                }
                self.next(Phase::ShapeSlider);
            }
            Phase::Scrub | Phase::ScrubHeadOnly | Phase::ScrubBusy => {
                self.scrub_frames += 1;
                self.scrub_scales.push(scale);
                self.scrub_hairs.push(hairs);
                self.scrub_sparse = self.scrub_sparse.max(sparse);
                self.scrub_years.push(years);
                self.intervals_ms.push(dt);
                if elapsed > 5.0 {
                    let fps = self.scrub_frames as f64 / elapsed;
                    let most = self.scrub_hairs.iter().copied().max().unwrap_or(0);
                    let least = self.scrub_hairs.iter().copied().min().unwrap_or(0);
                    let med = median(&mut self.intervals_ms);
                    let y0 = self
                        .scrub_years
                        .iter()
                        .copied()
                        .fold(f32::INFINITY, f32::min);
                    let y1 = self.scrub_years.iter().copied().fold(0.0, f32::max);
                    let (layout, target) = match self.phase {
                        Phase::Scrub => ("3D view and map view", "≥ 20 fps"),
                        Phase::ScrubBusy => {
                            ("3D view and map view, one core kept busy", "≥ 15 fps")
                        }
                        _ => ("3D view alone", "≥ 20 fps"),
                    };
                    // The resolution the governor settled on: the last second's median.
                    let last = self
                        .scrub_scales
                        .len()
                        .saturating_sub(self.scrub_frames.min(20));
                    let mut settled: Vec<f64> = self.scrub_scales[last..]
                        .iter()
                        .map(|&s| f64::from(s))
                        .collect();
                    let settled = median(&mut settled) * 100.0;
                    self.results.push(format!(
                        "| scrubbing the age, {layout} (playing {y0:.0}–{y1:.0} years, {least}–{most} hairs of the age, one in {} drawn while it plays; the view at {settled:.0} % resolution at the end) | {fps:.1} fps (median frame {med:.1} ms, {:.1}× the floor) | {target} |",
                        self.scrub_sparse,
                        med / self.floor_ms
                    ));
                    self.scrub_scales.clear();
                    self.scrub_frames = 0;
                    self.scrub_sparse = 1;
                    self.scrub_hairs.clear();
                    self.scrub_years.clear();
                    self.intervals_ms.clear();
                    match self.phase {
                        Phase::Scrub => {
                            self.next(Phase::ScrubHeadOnly);
                            return Action::PlayHeadOnly;
                        }
                        Phase::ScrubHeadOnly => {
                            self.burner = Some(Burner::start());
                            self.next(Phase::SliderBusy);
                            return Action::StopBoth;
                        }
                        _ => {
                            self.burner = None;
                            self.next(Phase::Done);
                            return Action::Stop;
                        }
                    }
                }
            }
            Phase::Done => {
                println!("| figure | measured | target |\n|---|---|---|");
                for r in &self.results {
                    println!("{r}");
                }
                return Action::Quit;
            }
        }
        Action::None
    }

    /// Whether the script is dragging a slider (the view draws its moving frames).
    pub fn dragging(&self) -> bool {
        matches!(
            self.phase,
            Phase::Slider | Phase::ShapeSlider | Phase::SliderBusy
        )
    }

    /// Whether the app should paint nothing but an empty panel this frame.
    pub fn floor(&self) -> bool {
        self.phase == Phase::Floor
    }

    /// Whether a slider move is still waiting to be seen (this frame one step further:
    /// the frame that draws its bake, then its latency once that frame is presented);
    /// `false` when none is, and the next may be sent.
    fn waiting(&mut self, now: Instant, reported: u64, bake_ms: f64) -> bool {
        match &mut self.slider_sent {
            Some((sent, _, true)) => {
                // The frame that drew the bake has been presented.
                self.slider_latencies_ms
                    .push((now - *sent).as_secs_f64() * 1e3);
                self.slider_sent = None;
            }
            Some((_, id, shown)) => {
                // This frame draws the bake (the app uploads before drawing).
                *shown = reported >= *id;
                if *shown {
                    self.slider_bakes_ms.push(bake_ms);
                }
            }
            None => return false,
        }
        true
    }

    /// The frames drawn while a slider moved, in words (their median interval and the 3D
    /// view's median resolution), and cleared for the next phase.
    fn slider_frames_summary(&mut self) -> String {
        let mut dt: Vec<f64> = self.slider_frames.iter().map(|f| f.0).collect();
        let mut scale: Vec<f64> = self.slider_frames.iter().map(|f| f64::from(f.1)).collect();
        self.slider_frames.clear();
        format!(
            "frames every {:.0} ms at {:.0} % resolution",
            median(&mut dt),
            100.0 * median(&mut scale)
        )
    }

    fn next(&mut self, phase: Phase) {
        self.phase = phase;
        self.phase_start = Instant::now();
    }
}
