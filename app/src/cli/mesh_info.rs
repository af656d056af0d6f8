//! `agesim mesh-info [FILE]`: what a head mesh contains and what loading it repaired.

use std::path::PathBuf;

use agesim_core::Mesh;
use agesim_core::head::mesh::TangentSource;
use agesim_core::project::Project;
use agesim_core::scene::Scene;

/// Print vertex/triangle counts, bounding box and size, which attributes the file had and
/// what was generated or dropped. Without FILE (or with --default-head): the default head.
#[derive(Debug, clap::Args)]
pub struct MeshInfoArgs {
    /// An OBJ, glTF or GLB file.
    pub file: Option<PathBuf>,
    /// Report the built-in default head (the default when no FILE is given).
    #[arg(long, conflicts_with = "file")]
    pub default_head: bool,
    /// The head's landmark file: its outer eye corners set the units, its face the axes.
    #[arg(long, value_name = "FILE")]
    pub landmarks: Option<PathBuf>,
}

pub fn run(args: &MeshInfoArgs) -> anyhow::Result<()> {
    let (name, mesh) = match &args.file {
        Some(path) if !args.default_head => (path.display().to_string(), Mesh::load(path)?),
        _ => (
            "assets/meshes/default-head.glb (built in)".to_owned(),
            agesim_core::head::default::default_head(),
        ),
    };
    print!("{}", describe(&name, &mesh));
    match &args.file {
        Some(path) if !args.default_head => {
            // The scene decides the units, axes and layout as every command does.
            let mut project = Project::default();
            project.mesh.path = Some(path.clone());
            project.mesh.metres_per_unit = None;
            project.mesh.landmarks = args.landmarks.clone().map(Into::into);
            print!("{}", describe_head(&Scene::new(project)?));
        }
        _ => {
            if args.landmarks.is_some() {
                anyhow::bail!("--landmarks describes a FILE: give the mesh file too");
            }
            print!(
                "metres per unit: 1 (metres: a built-in mesh)\naxes:      up +Y, forward +Z\nlayout:    the template itself (its own UVs)\n"
            );
        }
    }
    Ok(())
}

/// The units, axes and layout a scene decided for its mesh file, as `mesh-info` prints
/// them.
pub fn describe_head(scene: &Scene) -> String {
    let u = scene.units();
    let a = scene.axes();
    let how = scene.axes_how();
    let axes = format!("up {}, forward {} ({how})", a.up.name(), a.forward.name());
    let textures = match scene.file_textures() {
        [] => "none named by its material".to_owned(),
        named => named.join(", "),
    };
    format!(
        "metres per unit: {} ({})\naxes:      {axes}\nlayout:    {}\ntextures:  {textures}\n",
        u.metres_per_unit,
        u.how,
        scene.layout().how
    )
}

/// The report printed by `mesh-info`, one fact per line.
pub fn describe(name: &str, mesh: &Mesh) -> String {
    use std::fmt::Write as _;
    let mut s = String::new();
    let b = mesh.bounds();
    let r = mesh.report();
    let origin = |generated: bool, what: &str| {
        if generated {
            format!("generated ({what})")
        } else {
            "from the file".to_owned()
        }
    };
    let _ = writeln!(s, "mesh:      {name}");
    let _ = writeln!(s, "vertices:  {}", mesh.vertex_count());
    let _ = writeln!(s, "triangles: {}", mesh.triangle_count());
    let _ = writeln!(
        s,
        "bounds:    min ({:.4}, {:.4}, {:.4}) max ({:.4}, {:.4}, {:.4})",
        b.min.x, b.min.y, b.min.z, b.max.x, b.max.y, b.max.z
    );
    let size = b.size();
    let _ = writeln!(
        s,
        "size:      {:.4} × {:.4} × {:.4} (file units; metres for glTF and the default head)",
        size.x, size.y, size.z
    );
    let _ = writeln!(
        s,
        "normals:   {}",
        origin(r.normals_generated, "angle-weighted smooth")
    );
    let uv = if r.uvs_generated {
        format!(
            "generated (inverse spherical mapping, docs/models.md §6; {} seam/pole vertices added)",
            r.seam_vertices_added
        )
    } else {
        "from the file".to_owned()
    };
    let _ = writeln!(s, "uvs:       {uv}");
    if let Some(u) = mesh.udim() {
        let split = match r.udim_split_vertices {
            0 => String::new(),
            n => format!("; {n} vertices split where tiles met"),
        };
        let _ = writeln!(
            s,
            "udim:      tiles {} (baked side by side, {g} × {g}; maps written per tile{split})",
            u.numbers()
                .iter()
                .map(u32::to_string)
                .collect::<Vec<_>>()
                .join(", "),
            g = u.grid()
        );
    }
    let tangents = match r.tangent_source {
        Some(TangentSource::File) => "from the file".to_owned(),
        Some(TangentSource::Analytic) => "generated (exact frame of a flat UV grid)".to_owned(),
        _ => format!(
            "generated (MikkTSpace; {} vertices split at UV seams/mirrors)",
            r.tangent_split_vertices
        ),
    };
    let _ = writeln!(s, "tangents:  {tangents}");
    let _ = writeln!(s, "parts:     {}", mesh.parts().len());
    for part in mesh.parts().iter().take(20) {
        let skin = if part.is_skin() {
            ""
        } else {
            ", not skin: no hair"
        };
        let _ = writeln!(
            s,
            "  - {} ({} triangles{skin})",
            part.name, part.triangle_count
        );
    }
    if mesh.parts().len() > 20 {
        let _ = writeln!(s, "  … {} more", mesh.parts().len() - 20);
    }
    if r.warnings.is_empty() {
        let _ = writeln!(s, "repairs:   none");
    } else {
        let _ = writeln!(s, "repairs:");
        for w in &r.warnings {
            let _ = writeln!(s, "  - {w}");
        }
    }
    s
}
