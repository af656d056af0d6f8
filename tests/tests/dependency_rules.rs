//! The dependency rules of ARCHITECTURE.md, checked with `cargo tree` so they hold for good:
//! agesim-core never depends (even transitively) on a GPU or UI crate.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::process::Command;

const FORBIDDEN_IN_CORE: &[&str] = &["wgpu", "egui", "eframe", "winit", "egui-wgpu", "naga"];

#[test]
fn core_has_no_gpu_or_ui_dependencies() {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let output = Command::new(cargo)
        .args([
            "tree",
            "-p",
            "agesim-core",
            "-e",
            "normal,build",
            "--prefix",
            "none",
            "--format",
            "{p}",
        ])
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("cargo tree runs");
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let tree = String::from_utf8_lossy(&output.stdout);
    assert!(
        tree.contains("agesim-core"),
        "unexpected cargo tree output:\n{tree}"
    );
    let offenders: Vec<&str> = tree
        .lines()
        .filter(|line| {
            let name = line.split_whitespace().next().unwrap_or("");
            FORBIDDEN_IN_CORE.contains(&name)
        })
        .collect();
    assert!(
        offenders.is_empty(),
        "agesim-core depends on GPU/UI crates: {offenders:?}"
    );
}
