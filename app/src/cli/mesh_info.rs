//! `agesim mesh-info [FILE]`: what a head mesh contains and what loading it repaired.

use std::path::PathBuf;

use agesim_core::Mesh;
use agesim_core::head::mesh::TangentSource;
use agesim_core::scene::Scene;

/// Print vertex/triangle counts, bounding box and size, which attributes the file had and
/// what was generated or dropped. Without FILE (or with --default-head): the default head.
#[derive(Debug, clap::Args)]
pub struct MeshInfoArgs {
    /// An OBJ, glTF or GLB file (the same as --mesh).
    #[arg(conflicts_with = "mesh")]
    pub file: Option<PathBuf>,
    /// Report the built-in default head (the default when no FILE, --mesh or project
    /// mesh is given).
    #[arg(long, conflicts_with_all = ["file", "mesh", "project", "preset"])]
    pub default_head: bool,
    /// The project, the head and the age (with an age: how many of the hairs are there
    /// then).
    #[command(flatten)]
    pub head: super::HeadArgs,
}

pub fn run(args: &MeshInfoArgs) -> anyhow::Result<()> {
    let mut head = args.head.clone();
    if let Some(file) = &args.file {
        head.mesh_args.mesh = Some(file.clone());
    }
    let project = head.resolved()?;
    let age_t = head.age.given().then(|| head.age.t(&project)).transpose()?;
    // The scene loads the file (once) and decides the units, axes and layout as every
    // command does.
    let mut scene = Scene::new(project)?;
    match scene.project().mesh.path.clone() {
        Some(path) => {
            print!(
                "{}",
                describe(&path.display().to_string(), scene.file_mesh())
            );
            print!("{}", describe_head(&scene));
        }
        None => {
            let mesh = agesim_core::head::default::default_head();
            print!(
                "{}",
                describe("assets/meshes/default-head.glb (built in)", &mesh)
            );
            print!(
                "metres per unit: 1 (metres: a built-in mesh)\naxes:      up +Y, forward +Z\nlayout:    the template itself (its own UVs)\n"
            );
        }
    }
    print!("{}", describe_person(&mut scene)?);
    if let Some(t) = age_t {
        print!("{}", describe_hair_at(&mut scene, t)?);
    }
    Ok(())
}

/// How many of the head's hairs are there at age `t`, as `mesh-info --age` prints it.
fn describe_hair_at(scene: &mut Scene, t: f32) -> anyhow::Result<String> {
    let years = scene.project().age.mapping().years(t);
    if !scene.project().hair.enabled {
        return Ok(format!(
            "at {years:.0} years: no hair (hair.enabled is off)\n"
        ));
    }
    let request = agesim_core::scene::BakeRequest::hair_only(t);
    scene.bake(&request, &agesim_core::base::cancel::CancelToken::never())?;
    let Some(hairs) = scene.hair() else {
        return Ok(format!("at {years:.0} years: no hair on this head\n"));
    };
    let (now, all) = (hairs.count(t), hairs.len());
    Ok(format!(
        "at {years:.0} years: {now} of {all} scalp hairs ({:.0} %)\n",
        100.0 * now as f64 / all.max(1) as f64
    ))
}

/// The person's colours and hair loss as `mesh-info` prints them: measured on the head's
/// colour map, else what the aging uses instead.
pub fn describe_person(scene: &mut Scene) -> anyhow::Result<String> {
    use agesim_core::base::lab::{ita_degrees, ita_group};
    use agesim_core::scene::describe_measured;
    let cancel = agesim_core::base::cancel::CancelToken::never();
    let own = scene.own_colours(&cancel)?;
    let person = scene.person();
    let hex = |c: [f32; 3]| {
        let s = c.map(|c| {
            (agesim_core::maps::mask::linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0).round() as u8
        });
        agesim_core::project::Colour(s).to_string()
    };
    let skin = match own.skin {
        Some(m) => {
            let ita = ita_degrees(m.lab);
            format!(
                "{}, ITA {ita:.0}°: {} (measured on the cheeks)",
                describe_measured(&m),
                ita_group(ita)
            )
        }
        None => format!(
            "{} (no colour map: the project's skin.albedo)",
            scene.project().skin.albedo
        ),
    };
    let colour = |c: [f32; 3],
                  m: Option<agesim_core::layers::skin_colour::Measured>,
                  source: agesim_core::scene::Source,
                  on: &str,
                  default: &str| match (source, m) {
        (agesim_core::scene::Source::Measured, Some(m)) => format!(
            "{} (measured on the colour map's {on})",
            describe_measured(&m)
        ),
        (s, _) => format!("{} ({})", hex(c), s.describe(on, default)),
    };
    let c = own.contrast;
    let value = |v: Option<f32>| v.map_or_else(|| "—".to_owned(), |v| format!("{v:.2}"));
    let contrast = if c.brows.is_none() && c.lips.is_none() {
        "no colour map to measure".to_owned()
    } else {
        format!(
            "brows {}, lips {} (luminance, against the cheeks)",
            value(c.brows),
            value(c.lips)
        )
    };
    Ok(format!(
        "skin tone: {skin}\nhair colour: {}\nbrow colour: {}\nhair grays: {:.0} years later than the project's range (hair.graying_onset_*_years)\nhair loss: {}\nhair curl: {}\nfacial contrast: {contrast}\nlips: {}\neyes: {}\n",
        colour(
            person.hair,
            own.hair,
            person.hair_source,
            "scalp",
            "a dark brown"
        ),
        colour(
            person.brows,
            own.brows,
            person.brow_source,
            "brows",
            "the hair's, darker",
        ),
        person.graying_delay_years,
        person.loss.describe(),
        describe_curl(&person),
        describe_lips(scene),
        describe_eyes(scene),
    ))
}

/// How far the head's lips thin with age, as `mesh-info` prints it (docs/models.md §13
/// "Measured on the head").
fn describe_lips(scene: &Scene) -> String {
    let f = scene.layout().lip_fullness;
    if scene.layout().fit.is_none() {
        return "thin as the template's (the head is not fitted)".to_owned();
    }
    let reach = scene.layout().lower_lip_reach;
    let lower = if reach >= 0.005 {
        format!(
            ", the lower lip's reaching {reach:.2} of the face frame further down than the template's (by its mentolabial sulcus)"
        )
    } else {
        String::new()
    };
    format!(
        "deflate {f:.2} × as far as the template's (by how far they stand out in front of the subnasale–chin line; shape.lips scales it); their red keeps {:.0} % of the micro-relief{lower}",
        100.0 * agesim_core::layers::micro::weight::ON_LIPS
    )
}

/// How far the head's eyes are open and what that makes of the lids' and brows' descent,
/// as `mesh-info` prints it (docs/models.md §13 "Measured on the head").
fn describe_eyes(scene: &Scene) -> String {
    use agesim_core::layers::shape::anatomy;
    let Some(mm) = scene.layout().eye_opening_mm else {
        return "the lids come down their whole move (the eyes are closed, or the head is not fitted)".to_owned();
    };
    let lids = anatomy::lid_share(Some(mm));
    format!(
        "open {mm:.1} mm (scaled to the template's size): the upper lids come down {lids:.2} × their move, the brows {:.2} × (shape.lids, shape.brows scale them)",
        anatomy::brow_share(lids)
    )
}

/// The hair's curl as `mesh-info` prints it: its value, and whether it was guessed.
fn describe_curl(person: &agesim_core::scene::Person) -> String {
    let name = if person.curl >= 0.75 {
        "coiled"
    } else if person.curl > 0.25 {
        "curly"
    } else {
        "straight"
    };
    match person.curl_guessed {
        Some(ita) => format!(
            "{name} {:.1} (guessed from the skin's tone, ITA {ita:.0}°, coiled under {:.0}°; set hair.curl to change)",
            person.curl,
            agesim_core::layers::hair::COILED_UNDER_ITA
        ),
        None => format!("{name} {:.1} (set in the project)", person.curl),
    }
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
