//! The editor harness and waits shared by the egui_kittest test files.
#![allow(dead_code, clippy::unwrap_used, clippy::expect_used)]

use std::time::{Duration, Instant};

use agesim::editor::{EditorApp, EditorOptions};
use egui_kittest::Harness;

/// The real app, 1280×800, no GPU needed.
pub fn harness() -> Harness<'static, EditorApp> {
    harness_with(EditorOptions::default())
}

pub fn harness_with(options: EditorOptions) -> Harness<'static, EditorApp> {
    Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |cc| EditorApp::new(cc, options))
}

/// Runs frames until the worker has baked the newest request (bakes run on their own
/// thread, so the test waits in real time).
pub fn settle(h: &mut Harness<'static, EditorApp>) {
    wait_for(h, "the bake", |app| {
        app.idle() && app.snapshot().large.is_some()
    });
    h.run_steps(1);
}

/// Runs frames until `done` holds (threads report in real time), at most two minutes.
pub fn wait_for(
    h: &mut Harness<'static, EditorApp>,
    what: &str,
    done: impl Fn(&EditorApp) -> bool,
) {
    let start = Instant::now();
    loop {
        h.run_steps(1);
        if done(h.state()) {
            return;
        }
        assert!(
            start.elapsed() < Duration::from_secs(120),
            "{what} never finished"
        );
        std::thread::sleep(Duration::from_millis(20));
    }
}

/// The large-wrinkle heights of the last bake.
pub fn large_map(h: &Harness<'static, EditorApp>) -> Vec<f32> {
    h.state()
        .snapshot()
        .large
        .as_ref()
        .unwrap()
        .height
        .data()
        .to_vec()
}

/// Fibres in all the wrinkle files as edited.
pub fn fibre_count(h: &Harness<'static, EditorApp>) -> usize {
    h.state()
        .wrinkles()
        .iter()
        .map(|w| w.file.groups.len())
        .sum()
}

/// Drags with the pointer from `start` to `end` in a few frames, as a hand would.
pub fn drag(h: &mut Harness<'static, EditorApp>, start: egui::Pos2, end: egui::Pos2) {
    h.hover_at(start);
    h.run_steps(1);
    h.drag_at(start);
    h.run_steps(1);
    for k in 1..=5 {
        h.hover_at(start + (end - start) * (k as f32 / 5.0));
        h.run_steps(1);
    }
    h.drop_at(end);
    h.run_steps(1);
}

/// Where the UV point `uv` is on the map view.
pub fn map_point(h: &mut Harness<'static, EditorApp>, uv: [f32; 2]) -> egui::Pos2 {
    let square = h.state_mut().map_view_mut().last_square.unwrap();
    egui::pos2(
        square.left() + uv[0] * square.width(),
        square.top() + (1.0 - uv[1]) * square.height(),
    )
}

/// A virtual X display for the real binary's window, stopped when dropped; `None` when
/// Xvfb is not installed.
pub struct Xvfb {
    child: std::process::Child,
    pub display: String,
}

impl Xvfb {
    /// Starts one on a display number of this process's own (`base` + pid mod 50).
    pub fn start(base: u32) -> Option<Self> {
        use std::process::{Command, Stdio};
        if Command::new("Xvfb")
            .arg("-help")
            .stderr(Stdio::null())
            .status()
            .is_err()
        {
            return None;
        }
        let display = format!(":{}", base + std::process::id() % 50);
        let child = Command::new("Xvfb")
            .args([&display, "-screen", "0", "1280x800x24", "-nolisten", "tcp"])
            .stderr(Stdio::null())
            .spawn()
            .ok()?;
        std::thread::sleep(Duration::from_millis(500));
        Some(Self { child, display })
    }
}

impl Drop for Xvfb {
    fn drop(&mut self) {
        let _ = self.child.kill();
        let _ = self.child.wait();
    }
}
