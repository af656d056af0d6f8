//! `agesim landmarks --mesh FILE --out L.json`: the head's facial landmarks found
//! automatically (the template aligned to it, `agesim_core::head::fit::auto`), written as a
//! landmark file in the mesh file's own coordinates, to check, correct and pass back with
//! `--landmarks`.

use std::path::PathBuf;

use agesim_core::head::landmarks::{Landmarks, NAMES};
use agesim_core::project::Project;
use agesim_core::scene::Scene;
use anyhow::Context as _;

/// Find the facial landmarks of a head automatically and write them as a landmark file.
#[derive(Debug, clap::Args)]
pub struct LandmarksArgs {
    /// The head: an OBJ, glTF or GLB file (upright; its axes and units are detected).
    #[arg(long, value_name = "FILE")]
    pub mesh: PathBuf,
    /// Where to write the landmark file (JSON, in the mesh file's coordinates).
    #[arg(long, value_name = "FILE")]
    pub out: PathBuf,
}

pub fn run(args: &LandmarksArgs) -> anyhow::Result<()> {
    let mut project = Project::default();
    project.mesh.path = Some(args.mesh.clone());
    project.mesh.metres_per_unit = None;
    let scene = Scene::new(project)?;
    let layout = scene.layout();
    let Some(found) = layout.landmarks.as_deref().filter(|_| layout.found) else {
        anyhow::bail!(
            "{}: no landmarks found: {}; nothing was written",
            args.mesh.display(),
            layout.how
        );
    };
    // The scene's mesh is turned to +Y up, +Z forward: back to the file's coordinates.
    let back = scene
        .axes()
        .to_standard()
        .map_or(glam::Mat3::IDENTITY, |r| r.transpose());
    let mut file = Landmarks::default();
    for name in NAMES {
        if let Some(p) = found.get(name) {
            file.set(name, back * p)?;
        }
    }
    let text = file.to_json_pretty();
    let outputs = agesim_core::output::export::OutputSet::new();
    outputs
        .stage(&args.out, |w| std::io::Write::write_all(w, text.as_bytes()))
        .with_context(|| format!("cannot write {}", args.out.display()))?;
    outputs.commit()?;
    println!("{}", layout.how);
    let units = scene.units();
    println!("metres per unit: {} ({})", units.metres_per_unit, units.how);
    println!(
        "{} landmarks written to {} (the mesh file's coordinates)",
        file.len(),
        args.out.display()
    );
    Ok(())
}
