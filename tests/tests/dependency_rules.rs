//! The dependency rules of ARCHITECTURE.md, checked with `cargo tree` so they hold for good:
//! agesim-core never depends (even transitively) on a GPU or UI crate, and agesim-render
//! never on a UI or windowing crate (the editor shares its device through the app).
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::process::Command;

const FORBIDDEN_IN_CORE: &[&str] = &["wgpu", "egui", "eframe", "winit", "egui-wgpu", "naga"];
const FORBIDDEN_IN_RENDER: &[&str] = &["egui", "eframe", "winit", "egui-wgpu"];

#[test]
fn core_has_no_gpu_or_ui_dependencies() {
    assert_no_dependency_on("agesim-core", FORBIDDEN_IN_CORE);
}

#[test]
fn render_has_no_ui_dependencies() {
    assert_no_dependency_on("agesim-render", FORBIDDEN_IN_RENDER);
}

/// `cargo tree -p package` (normal and build edges, so dev-dependencies such as naga in
/// tests are allowed) contains none of `forbidden`.
fn assert_no_dependency_on(package: &str, forbidden: &[&str]) {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".into());
    let output = Command::new(cargo)
        .args([
            "tree",
            "-p",
            package,
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
        tree.contains(package),
        "unexpected cargo tree output:\n{tree}"
    );
    let offenders: Vec<&str> = tree
        .lines()
        .filter(|line| {
            let name = line.split_whitespace().next().unwrap_or("");
            forbidden.contains(&name)
        })
        .collect();
    assert!(
        offenders.is_empty(),
        "{package} depends on forbidden crates: {offenders:?}"
    );
}
