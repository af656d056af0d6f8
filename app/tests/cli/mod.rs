//! Running the real `agesim` binary, shared by the command-line test files.
#![allow(dead_code, clippy::expect_used)]

use std::process::{Command, Output};

/// `agesim ARGS…` and its output (with a runtime directory, which the commands that open
/// a GPU adapter want).
pub fn agesim(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_agesim"))
        .args(args)
        .env("XDG_RUNTIME_DIR", std::env::temp_dir())
        .output()
        .expect("the agesim binary runs")
}

pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// The default head re-cut as a two-tile UDIM head: the subject's right (x < 0) moved to
/// tile 1002. Written as OBJ.
pub fn udim_head(dir: &std::path::Path) -> std::path::PathBuf {
    use glam::Vec2;
    let head = agesim_core::head::default::default_head();
    let mut raw = agesim_core::head::mesh::RawMesh::default();
    let mut uvs = Vec::new();
    let mut copies = std::collections::HashMap::new();
    for [a, b, c] in head.triangles() {
        let right = [a, b, c]
            .iter()
            .all(|&i| head.positions()[i as usize].x < 0.0);
        for i in [a, b, c] {
            let v = *copies.entry((i, right)).or_insert_with(|| {
                raw.positions.push(head.positions()[i as usize]);
                uvs.push(head.uvs()[i as usize] + Vec2::new(if right { 1.0 } else { 0.0 }, 0.0));
                raw.positions.len() as u32 - 1
            });
            raw.indices.push(v);
        }
    }
    raw.uvs = Some(uvs);
    let mesh = agesim_core::head::mesh::Mesh::build(raw, "udim head").unwrap();
    assert_eq!(mesh.udim().unwrap().numbers(), [1001, 1002]);
    let path = dir.join("udim.obj");
    std::fs::write(&path, agesim_core::head::mesh::obj::to_obj(&mesh, |p| p)).unwrap();
    path
}
