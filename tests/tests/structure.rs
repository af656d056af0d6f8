//! The structure of the house (ARCHITECTURE.md), checked on the source tree so it holds for
//! good: agesim-core's rooms import only downward (base ← maps ← age ← head ← layers ←
//! output ← project ← scene), no aging layer imports another, core has at most 12
//! top-level entries, every folder module is a `mod.rs`, and no source file is longer than
//! 800 lines before its tests.

use std::path::{Path, PathBuf};

/// The workspace root.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("..")
}

/// Every `.rs` file under `dir`, sorted.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        let Ok(entries) = std::fs::read_dir(&d) else {
            continue;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }
    out.sort();
    out
}

/// A test file: `tests.rs`, `*_tests.rs`, or any file under a `tests` folder.
fn is_test_file(path: &Path) -> bool {
    let name = path.file_name().and_then(|n| n.to_str()).unwrap_or("");
    name == "tests.rs"
        || name.ends_with("_tests.rs")
        || path.components().any(|c| c.as_os_str() == "tests")
}

/// The lines of `text` before its first `#[cfg(test)]` (the code, without its tests).
fn code_lines(text: &str) -> Vec<&str> {
    text.lines()
        .take_while(|l| l.trim() != "#[cfg(test)]")
        .collect()
}

/// The floor of each room of agesim-core: a room imports only rooms on its floor or below.
const FLOORS: &[(&str, u32)] = &[
    ("base", 0),
    ("maps", 1),
    ("age", 2),
    ("head", 3),
    ("defaults", 3),
    ("layers", 4),
    ("output", 5),
    ("project", 6),
    ("scene", 7),
];

fn floor_of(room: &str) -> Option<u32> {
    FLOORS.iter().find(|(r, _)| *r == room).map(|(_, f)| *f)
}

/// The rooms named by `crate::room` paths in the code lines of `text` (comments skipped):
/// (room, the path's next segment, line number).
fn imports(text: &str) -> Vec<(String, String, usize)> {
    let mut out = Vec::new();
    for (i, line) in code_lines(text).iter().enumerate() {
        let code = line.split("//").next().unwrap_or("");
        let mut rest = code;
        while let Some(at) = rest.find("crate::") {
            let after = &rest[at + "crate::".len()..];
            let mut segments = after
                .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == ':'))
                .next()
                .unwrap_or("")
                .split("::");
            let room = segments.next().unwrap_or("").to_owned();
            let next = segments.next().unwrap_or("").to_owned();
            out.push((room, next, i + 1));
            rest = after;
        }
    }
    out
}

#[test]
fn core_imports_only_downward_and_no_layer_imports_another() {
    let src = root().join("crates/core/src");
    let mut problems = Vec::new();
    for path in rust_files(&src) {
        if is_test_file(&path) {
            continue;
        }
        let rel = path.strip_prefix(&src).unwrap_or(&path);
        let mut parts = rel.iter().map(|p| p.to_string_lossy().into_owned());
        let first = parts.next().unwrap_or_default();
        let room = first.trim_end_matches(".rs").to_owned();
        let Some(floor) = floor_of(&room) else {
            continue; // lib.rs, test_util.rs
        };
        let layer = (room == "layers").then(|| parts.next()).flatten();
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        for (target, next, line) in imports(&text) {
            let Some(to) = floor_of(&target) else {
                continue; // crate::Error and the other names lib.rs hands on
            };
            if to > floor {
                problems.push(format!(
                    "{}:{line}: {room} (floor {floor}) imports {target} (floor {to})",
                    rel.display()
                ));
            }
            if let Some(layer) = &layer
                && target == "layers"
                && *layer != next
            {
                problems.push(format!(
                    "{}:{line}: the {layer} layer imports the {next} layer",
                    rel.display()
                ));
            }
        }
    }
    assert!(problems.is_empty(), "{}", problems.join("\n"));
}

#[test]
fn core_has_at_most_twelve_top_level_entries() {
    let entries: Vec<String> = std::fs::read_dir(root().join("crates/core/src"))
        .map(|d| {
            d.flatten()
                .map(|e| e.file_name().to_string_lossy().into_owned())
                .collect()
        })
        .unwrap_or_default();
    assert!(
        (1..=12).contains(&entries.len()),
        "{} entries: {entries:?}",
        entries.len()
    );
}

/// The source folders of the workspace's crates.
fn source_dirs() -> Vec<PathBuf> {
    [
        "crates/core/src",
        "crates/render/src",
        "app/src",
        "tests/src",
    ]
    .iter()
    .map(|d| root().join(d))
    .collect()
}

#[test]
fn no_source_file_is_over_800_lines_before_its_tests() {
    let mut long = Vec::new();
    for dir in source_dirs() {
        for path in rust_files(&dir) {
            if is_test_file(&path) {
                continue;
            }
            let text = std::fs::read_to_string(&path).unwrap_or_default();
            let n = code_lines(&text).len();
            if n > 800 {
                long.push(format!("{}: {n} lines", path.display()));
            }
        }
    }
    assert!(long.is_empty(), "{}", long.join("\n"));
}

#[test]
fn every_folder_module_is_a_mod_rs() {
    let mut pairs = Vec::new();
    for dir in source_dirs() {
        for path in rust_files(&dir) {
            if path.with_extension("").is_dir() {
                pairs.push(format!(
                    "{} beside its folder: move it to {}/mod.rs",
                    path.display(),
                    path.with_extension("").display()
                ));
            }
        }
    }
    assert!(pairs.is_empty(), "{}", pairs.join("\n"));
}

/// The checks themselves: an upward import and a layer's import of another are seen.
#[test]
fn the_import_check_sees_what_it_must() {
    let text = "use crate::base::error::Error;\n// crate::scene in a comment\nuse crate::scene::Scene;\nuse crate::layers::shape::REGIONS;\n#[cfg(test)]\nuse crate::project::Project;\n";
    let found = imports(text);
    assert_eq!(
        found,
        vec![
            ("base".to_owned(), "error".to_owned(), 1),
            ("scene".to_owned(), "Scene".to_owned(), 3),
            ("layers".to_owned(), "shape".to_owned(), 4),
        ]
    );
    assert!(floor_of("scene") > floor_of("layers"));
}
