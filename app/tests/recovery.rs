//! Autosave and crash recovery: an edit is written to the recovery folder, a session
//! killed with SIGKILL leaves it, and the next start offers it back (or restores it with
//! `--recover`); a clean exit leaves nothing behind.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use agesim::editor::{EditorApp, EditorOptions};
use egui::accesskit::Role;
use egui_kittest::Harness;
use egui_kittest::kittest::Queryable as _;

mod common;
use common::{settle, wait_for};

fn harness(data_dir: &Path, edit: Option<&str>) -> Harness<'static, EditorApp> {
    harness_with(data_dir, edit, Duration::ZERO)
}

fn harness_with(
    data_dir: &Path,
    edit: Option<&str>,
    autosave_delay: Duration,
) -> Harness<'static, EditorApp> {
    let data_dir = data_dir.to_owned();
    let edit = edit.map(str::to_owned);
    Harness::builder()
        .with_size([1280.0, 800.0])
        .build_eframe(move |cc| {
            EditorApp::new(
                cc,
                EditorOptions {
                    autosave_seconds: 0.2,
                    autosave_delay,
                    data_dir: Some(data_dir.clone()),
                    edit: edit.clone(),
                    config_dir: Some(data_dir.join("config")),
                    ..EditorOptions::default()
                },
            )
        })
}

/// The sessions in the recovery folder (one folder per editor).
fn sessions(dir: &Path) -> Vec<String> {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return Vec::new();
    };
    entries
        .flatten()
        .filter_map(|e| {
            std::fs::read_to_string(e.path().join(agesim::editor::recovery::SESSION_FILE)).ok()
        })
        .collect()
}

fn session_says(dir: &Path, needle: &str) -> bool {
    sessions(dir).iter().any(|t| t.contains(needle))
}

// The values are exact in binary: the project file writes f32 fields as f64 digits.

/// An edit is autosaved; the editor "crashes" (dropped without exiting); the next one
/// offers the session back, and Restore brings the edit back, marked unsaved.
#[test]
fn an_autosaved_edit_is_offered_back_after_a_crash() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("recovery");
    let mut h = harness(&rec, Some("noise.strength=0.75"));
    settle(&mut h);
    wait_for(&mut h, "the autosave", |_| session_says(&rec, "0.75"));
    drop(h);
    let mut h = harness(&rec, None);
    h.run_steps(3);
    h.get_by_role_and_label(Role::Button, "Restore").click();
    wait_for(&mut h, "the recovered bake", |app| {
        app.project().noise.strength == 0.75 && app.idle()
    });
    assert!(h.state().modified(), "the recovered work is unsaved");
}

/// A clean exit while an autosave is still being written waits for it, then removes the
/// folder: the write cannot put the session back after the exit removed it. (The soak run
/// once left a folder this way.)
#[test]
fn a_clean_exit_during_an_autosave_leaves_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let rec = dir.path().join("recovery");
    // A slow disk: the write starts two seconds after the autosave does (longer than a
    // frame of this harness takes, so the exit meets the write still running).
    let mut h = harness_with(&rec, Some("noise.strength=0.75"), Duration::from_secs(2));
    let start = Instant::now();
    while !h.state().autosaving() {
        assert!(start.elapsed() < Duration::from_secs(60), "no autosave");
        h.step();
    }
    eframe::App::on_exit(h.state_mut());
    assert!(!h.state().autosaving());
    // Whatever the thread was still doing, it is done: the folder stays empty.
    std::thread::sleep(Duration::from_millis(2500));
    let left = std::fs::read_dir(&rec).map_or(0, |d| d.count());
    assert_eq!(left, 0, "{}", rec.display());
}

/// The real binary under Xvfb, killed with SIGKILL after an edit was autosaved: the
/// recovery folder holds the edit, and `--recover` restores it.
#[test]
fn a_killed_editor_leaves_its_work_and_recover_restores_it() {
    let Some(xvfb) = common::Xvfb::start(140) else {
        return agesim_render::ci::skip_or_fail(
            "a_killed_editor_leaves_its_work_and_recover_restores_it",
            "Xvfb is not installed",
        );
    };
    let display = xvfb.display.clone();
    let dir = tempfile::tempdir().unwrap();
    let data = dir.path().join("data");
    let rec = data.join("agesim/recovery");
    let run = |args: &[&str]| {
        let mut c = Command::new(env!("CARGO_BIN_EXE_agesim"));
        c.args(args)
            .env("DISPLAY", &display)
            .env("XDG_RUNTIME_DIR", dir.path())
            .env("XDG_DATA_HOME", &data)
            .env("XDG_CONFIG_HOME", dir.path().join("config"))
            .env_remove("WAYLAND_DISPLAY");
        c
    };
    let mut editor = run(&["--autosave-seconds", "1", "--edit", "noise.strength=0.625"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while !session_says(&rec, "0.625") {
        if let Ok(Some(status)) = editor.try_wait() {
            let mut err = String::new();
            std::io::Read::read_to_string(&mut editor.stderr.take().unwrap(), &mut err).unwrap();
            if err.contains("could not be opened") {
                return agesim_render::ci::skip_or_fail(
                    "a_killed_editor_leaves_its_work_and_recover_restores_it",
                    &format!("no window: {err}"),
                );
            }
            panic!("the editor exited ({status}): {err}");
        }
        assert!(start.elapsed() < Duration::from_secs(120), "no autosave");
        std::thread::sleep(Duration::from_millis(200));
    }
    // SIGKILL: no exit code runs.
    unsafe { libc::kill(editor.id() as i32, libc::SIGKILL) };
    let _ = editor.wait();
    assert!(session_says(&rec, "0.625"), "the work outlives the kill");
    let out = run(&[
        "--recover",
        "--screenshot",
        dir.path().join("s.png").to_str().unwrap(),
        "--frames",
        "2",
    ])
    .output()
    .unwrap();
    drop(xvfb);
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(stdout.contains("recovered"), "{stdout}");
    // That editor exited cleanly: nothing left to recover.
    assert!(sessions(&rec).is_empty());
}
