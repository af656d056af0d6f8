//! The editor's Save is one set: a process killed (SIGKILL) at any point of a save leaves,
//! once the project is opened again, the previous set or the new one, never a mix, and
//! nothing else in the folder once the next save has run.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::path::{Path, PathBuf};
use std::process::Command;

use agesim::editor::files::save_project;
use agesim_core::head::landmarks::Landmarks;
use agesim_core::layers::wrinkles::wrinkle_file::{self, WrinkleFile};
use agesim_core::project::Project;
use agesim_core::scene::WrinkleSource;

/// The three wrinkle files of version `v` (each file's fibres say which version it is).
fn wrinkles(v: u32) -> Vec<WrinkleSource> {
    ["forehead", "cheek", "neck"]
        .iter()
        .enumerate()
        .map(|(i, name)| WrinkleSource {
            name: format!("{name}.wrk"),
            path: Some(PathBuf::from(format!("{name}.wrk"))),
            file: wrinkle_file_of(v, i),
        })
        .collect()
}

fn wrinkle_file_of(v: u32, i: usize) -> WrinkleFile {
    // Binary-exact values, so the text written reads back equal.
    let x = 0.25 + 0.125 * i as f32 + 0.0625 * v as f32;
    wrinkle_file::parse(
        &format!("!\nma={x};0.5\nmb={};0.625\nn=3\n", x + 0.0625),
        Path::new("w.wrk"),
    )
    .unwrap()
}

fn landmarks(v: u32) -> Landmarks {
    let mut l = Landmarks::default();
    l.set("pronasale", glam::Vec3::new(0.0, 0.0, v as f32))
        .unwrap();
    l
}

/// One save of version `v` (a mesh is named so the landmarks are written too).
fn save(dir: &Path, v: u32) {
    let mut project = Project {
        seed: u64::from(v),
        ..Project::default()
    };
    project.mesh.path = Some(dir.join("head.obj"));
    let path = dir.join("p.agesim.json");
    save_project(&path, &project, Some(&wrinkles(v)), Some(&landmarks(v))).unwrap();
}

/// The version the folder holds: the project's, after checking that every file it names
/// is of that version.
fn version_on_disk(dir: &Path) -> u32 {
    let project = Project::load(&dir.join("p.agesim.json")).unwrap();
    let v = project.seed as u32;
    assert_eq!(project.large.wrinkles.len(), 3);
    for (i, path) in project.large.wrinkles.iter().enumerate() {
        let file = wrinkle_file::load(path).unwrap();
        assert_eq!(
            file,
            wrinkle_file_of(v, i),
            "{} is not of version {v}: a mix",
            path.display()
        );
    }
    let l = Landmarks::load(project.mesh.landmark_file().unwrap()).unwrap();
    assert_eq!(l.get("pronasale").unwrap().z, v as f32, "landmarks: a mix");
    v
}

const CHILD_DIR: &str = "AGESIM_SAVE_KILL_DIR";
const CHILD_STEP: &str = "AGESIM_SAVE_KILL_STEP";

#[test]
fn a_save_killed_at_any_point_leaves_the_old_set_or_the_new_one() {
    // The child: saves version 1, then version 2 killing itself at the given step.
    if let Ok(dir) = std::env::var(CHILD_DIR) {
        let dir = PathBuf::from(dir);
        let step: u32 = std::env::var(CHILD_STEP).unwrap().parse().unwrap();
        save(&dir, 1);
        agesim_core::output::export::kill_at_step_for_tests(Some(step));
        save(&dir, 2);
        return;
    }
    let mut killed_old = 0;
    let mut killed_new = 0;
    for step in 0.. {
        let dir = tempfile::tempdir().unwrap();
        let status = Command::new(std::env::current_exe().unwrap())
            .args([
                "a_save_killed_at_any_point_leaves_the_old_set_or_the_new_one",
                "--exact",
                "--nocapture",
            ])
            .env(CHILD_DIR, dir.path())
            .env(CHILD_STEP, step.to_string())
            .status()
            .unwrap();
        use std::os::unix::process::ExitStatusExt as _;
        if status.success() {
            // Past the last step: the save finished.
            assert_eq!(version_on_disk(dir.path()), 2);
            break;
        }
        assert_eq!(
            status.signal(),
            Some(libc::SIGKILL),
            "step {step}: {status}"
        );
        let journal = dir.path().join(".p.agesim.json.agesim-commit").exists();
        let v = version_on_disk(dir.path());
        // Steps 0–5 stage the six files; from step 6 the journal is on the disk and the
        // new set wins.
        assert_eq!(v, if step < 6 { 1 } else { 2 }, "step {step}");
        assert!(!journal || v == 2, "step {step}");
        if v == 1 {
            killed_old += 1;
        } else {
            killed_new += 1;
        }
        // The next save leaves only the set's files in the folder.
        save(dir.path(), 3);
        assert_eq!(version_on_disk(dir.path()), 3);
        let mut names: Vec<String> = std::fs::read_dir(dir.path())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(
            names,
            [
                "p-cheek.wrk",
                "p-forehead.wrk",
                "p-landmarks.json",
                "p-neck.wrk",
                "p-wrinkle-mask.png",
                "p.agesim.json"
            ],
            "step {step}"
        );
        assert!(step < 100, "the save never finished");
    }
    eprintln!("killed with the old set: {killed_old}, with the new set: {killed_new}");
    // Six files staged (three wrinkle files, the mask, the landmarks, the project), the
    // journal, six moved aside, six placed…: both kinds are hit.
    assert!(
        killed_old >= 6 && killed_new >= 12,
        "{killed_old} / {killed_new}"
    );
}
