//! The head and project flags: one declaration, flattened into every command that reads a
//! head (`bake`, `hair`, `render`, `export`, `mesh-info`), so the same head is exported as
//! it was rendered with the same words. Documented once, in README "The head and project
//! flags"; a test checks that each command's `--help` lists them all, word for word.

use std::path::PathBuf;

use agesim_core::project::Project;
use serde_json::json;

/// The project, the head and the age a command works on.
#[derive(Clone, Debug, Default, clap::Args)]
#[command(next_help_heading = "Head and project")]
pub struct HeadArgs {
    /// Project file (`*.agesim.json`) with every setting (docs/project-file.md). Default:
    /// a new project on the default head.
    #[arg(long, value_name = "FILE", conflicts_with = "preset")]
    pub project: Option<PathBuf>,
    /// Start from a shipped preset instead: fine, rough, goose-skin, deep-pores,
    /// article-fig14.
    #[arg(long, value_name = "NAME")]
    pub preset: Option<String>,
    #[command(flatten)]
    pub sets: SetArgs,
    #[command(flatten)]
    pub mesh_args: MeshArgs,
    #[command(flatten)]
    pub age: AgeArgs,
}

impl HeadArgs {
    /// The project of `--project`/`--preset` (else a new one) with the head flags put in,
    /// before the command's own flags and the `--set`s ([`SetArgs::apply`]), which come
    /// after them.
    pub fn loaded(&self) -> anyhow::Result<Project> {
        let mut project = load_project_or_preset(self.project.as_deref(), self.preset.as_deref())?;
        self.mesh_args.apply_to(&mut project)?;
        Ok(project)
    }

    /// [`HeadArgs::loaded`] with every `--set` applied: the whole project, for a command
    /// without flags of its own over it.
    pub fn resolved(&self) -> anyhow::Result<Project> {
        self.sets.apply(self.loaded()?)
    }

    /// Where the project came from, in words (`bake.json`, reports).
    pub fn source(&self) -> String {
        match (&self.project, &self.preset) {
            (Some(p), _) => p.display().to_string(),
            (None, Some(name)) => format!("preset {name}"),
            (None, None) => "default project".into(),
        }
    }

    /// The `--mesh` given, if any.
    pub fn mesh(&self) -> Option<&std::path::Path> {
        self.mesh_args.mesh.as_deref()
    }

    /// Whether the command starts from a project or a preset rather than a new project.
    pub fn has_project(&self) -> bool {
        self.project.is_some() || self.preset.is_some()
    }
}

/// The age: one of the two flags, or the project's age.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct AgeArgs {
    /// Age t ∈ [0, 1] (0 = `age.young_years`, 1 = `age.old_years`); default: the
    /// project's `age.t` (0.5 for a new project).
    #[arg(long, value_name = "T", conflicts_with = "age_years")]
    pub age: Option<f32>,
    /// Age in years (mapped to t through the project's `age` section).
    #[arg(long, value_name = "Y")]
    pub age_years: Option<f32>,
}

impl AgeArgs {
    /// The age t these flags ask for, checked; the project's `age.t` when neither is given.
    pub fn t(&self, project: &Project) -> anyhow::Result<f32> {
        Ok(match (self.age, self.age_years) {
            (Some(t), _) if (0.0..=1.0).contains(&t) => t,
            (Some(t), _) => {
                anyhow::bail!("--age {t}: expected an age t in 0..=1 (or use --age-years)")
            }
            (None, Some(y)) if (0.0..=150.0).contains(&y) => project.age.mapping().t(y),
            (None, Some(y)) => anyhow::bail!("--age-years {y}: expected years in 0..=150"),
            (None, None) => project.age.t,
        })
    }

    /// Whether an age was asked for on the command line.
    pub fn given(&self) -> bool {
        self.age.is_some() || self.age_years.is_some()
    }
}

/// `--set PATH=VALUE` (repeatable): one project field by its JSON path.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct SetArgs {
    /// Override one project field by its JSON path, e.g. `--set hair.loss=female` or
    /// `--set pores.count=1000` (repeatable, applied in order after the project and the
    /// other head flags; docs/project-file.md lists the fields).
    #[arg(long = "set", value_name = "PATH=VALUE")]
    pub set: Vec<String>,
}

impl SetArgs {
    /// `project` with every `--set` applied, checked field by field.
    pub fn apply(&self, mut project: Project) -> anyhow::Result<Project> {
        for assignment in &self.set {
            let Some((path, value)) = assignment.split_once('=') else {
                anyhow::bail!(
                    "--set {assignment}: expected PATH=VALUE, e.g. --set hair.loss=female"
                );
            };
            project = project.set(path.trim(), value.trim())?;
        }
        Ok(project)
    }

    /// The field paths the `--set`s name, in order.
    pub fn paths(&self) -> impl Iterator<Item = &str> {
        self.set
            .iter()
            .map(|a| a.split_once('=').map_or(a.as_str(), |(p, _)| p).trim())
    }
}

/// The head: its mesh, units, landmarks and maps.
#[derive(Clone, Debug, Default, clap::Args)]
pub struct MeshArgs {
    /// Head mesh (OBJ, glTF, GLB; `mesh.path`). Default: the project's, else the built-in
    /// default head (metres).
    #[arg(long, value_name = "FILE")]
    pub mesh: Option<PathBuf>,
    /// Length of one mesh unit in metres (0.01 for a mesh in centimetres). Default: for
    /// --mesh, detected from --landmarks or from the head's size (`agesim mesh-info`
    /// says how); otherwise the project's.
    #[arg(long, value_name = "M")]
    pub metres_per_unit: Option<f32>,
    /// The head's landmark file (`{"landmarks": {"exocanthion_r": [x, y, z], …}}`, in the
    /// mesh file's units): its outer eye corners set the units. Default: found
    /// automatically.
    #[arg(long, value_name = "FILE")]
    pub landmarks: Option<PathBuf>,
    /// The head's base colour map (any image) over its own UVs: shown and aged instead
    /// of the skin colour, and its skin, hair and brow colours measured on it.
    #[arg(long, value_name = "FILE")]
    pub colour_map: Option<PathBuf>,
    /// The head's tangent-space normal map (green up) over its own UVs: the wrinkles and
    /// skin relief are combined onto it.
    #[arg(long, value_name = "FILE")]
    pub normal_map: Option<PathBuf>,
    /// Turn --colour-map and --normal-map upside down (a head whose UVs use the other v
    /// convention).
    #[arg(long)]
    pub maps_flip_v: bool,
}

impl MeshArgs {
    /// Puts the flags into `p`, each checked as its project field and named as typed: a
    /// --mesh with its own units (measured unless --metres-per-unit is given) and its own
    /// --landmarks (a project's landmarks belong to the project's mesh).
    pub fn apply_to(&self, p: &mut Project) -> anyhow::Result<()> {
        if self.landmarks.is_some() && self.mesh.is_none() && p.mesh.path.is_none() {
            anyhow::bail!("--landmarks describes a --mesh: give the mesh too");
        }
        let mut edits: Vec<(&str, String, String)> = Vec::new();
        if let Some(m) = &self.mesh {
            let typed = format!("--mesh {}", m.display());
            edits.push(("mesh.path", json!(m).to_string(), typed.clone()));
            edits.push(("mesh.metres_per_unit", "null".into(), typed.clone()));
            edits.push(("mesh.landmarks", "null".into(), typed));
        }
        if let Some(l) = &self.landmarks {
            let typed = format!("--landmarks {}", l.display());
            edits.push(("mesh.landmarks", json!(l).to_string(), typed));
        }
        if let Some(m) = self.metres_per_unit {
            let typed = format!("--metres-per-unit {m}");
            edits.push(("mesh.metres_per_unit", m.to_string(), typed));
        }
        if let Some(c) = &self.colour_map {
            let typed = format!("--colour-map {}", c.display());
            edits.push(("mesh.colour_map", json!(c).to_string(), typed));
        }
        if let Some(n) = &self.normal_map {
            let typed = format!("--normal-map {}", n.display());
            edits.push(("mesh.normal_map", json!(n).to_string(), typed));
        }
        if self.maps_flip_v {
            edits.push(("mesh.maps_flip_v", "true".into(), "--maps-flip-v".into()));
        }
        for (path, value, typed) in edits {
            *p = p.set_as(path, &value, &typed)?;
        }
        Ok(())
    }

    /// Says how the mesh's units were decided when they were measured, and how it was
    /// turned when its axes are not agesim's.
    pub fn report_units(scene: &agesim_core::scene::Scene) {
        let p = scene.project();
        if p.mesh.metres_per_unit.is_none() && p.mesh.path.is_some() {
            let units = scene.units();
            println!("metres per unit: {} ({})", units.metres_per_unit, units.how);
        }
        if p.mesh.path.is_some() {
            println!("layout: {}", scene.layout().how);
        }
        let axes = scene.axes();
        if axes != agesim_core::head::mesh::units::Axes::STANDARD {
            println!(
                "axes: up {}, forward {} (turned to +Y up, +Z forward)",
                axes.up.name(),
                axes.forward.name()
            );
        }
    }
}

/// The project a command starts from: `--project FILE`, else `--preset NAME`, else the
/// default project.
fn load_project_or_preset(
    project: Option<&std::path::Path>,
    preset: Option<&str>,
) -> anyhow::Result<Project> {
    use agesim_core::defaults;
    Ok(match (project, preset) {
        (Some(path), _) => Project::load(path)?,
        (None, Some(name)) => {
            let Some((file, text)) = defaults::preset(name) else {
                anyhow::bail!(
                    "unknown preset `{name}`: expected one of {}",
                    defaults::preset_names().join(", ")
                );
            };
            Project::from_json_str(text, file)?
        }
        (None, None) => Project::default(),
    })
}

#[cfg(test)]
mod tests {
    use clap::{CommandFactory as _, Parser as _};

    use crate::cli::{Cli, Command};

    /// The commands that read a head.
    const COMMANDS: [&str; 5] = ["bake", "hair", "render", "export", "mesh-info"];

    /// The "Head and project" section of a command's `--help`.
    fn head_section(name: &str) -> String {
        let mut cli = Cli::command();
        let sub = cli
            .find_subcommand_mut(name)
            .unwrap_or_else(|| panic!("no subcommand {name}"));
        let help = sub.render_long_help().to_string();
        let start = help
            .find("Head and project:")
            .unwrap_or_else(|| panic!("{name} --help has no head flags:\n{help}"));
        let section = &help[start..];
        // The section runs to the next heading (a line without indent) or the end.
        let end = section
            .lines()
            .skip(1)
            .position(|l| !l.is_empty() && !l.starts_with(' '))
            .map_or(section.len(), |n| {
                section.lines().take(n + 1).map(|l| l.len() + 1).sum()
            });
        section[..end].trim_end().to_owned()
    }

    #[test]
    fn every_command_that_reads_a_head_lists_the_same_head_and_project_flags() {
        let first = head_section(COMMANDS[0]);
        for flag in [
            "--project",
            "--preset",
            "--set",
            "--mesh",
            "--landmarks",
            "--metres-per-unit",
            "--colour-map",
            "--normal-map",
            "--maps-flip-v",
            "--age ",
            "--age-years",
        ] {
            assert!(first.contains(flag), "{flag} missing:\n{first}");
        }
        for name in &COMMANDS[1..] {
            assert_eq!(
                head_section(name),
                first,
                "{name}'s head flags differ from bake's"
            );
        }
    }

    /// The same words give the same project on every command: a head exported as it was
    /// rendered.
    #[test]
    fn the_head_flags_resolve_to_the_same_project_on_every_command() {
        let head = [
            "--preset",
            "fine",
            "--mesh",
            "head.obj",
            "--metres-per-unit",
            "0.01",
            "--landmarks",
            "head.landmarks.json",
            "--colour-map",
            "skin.tga",
            "--normal-map",
            "normal.png",
            "--maps-flip-v",
            "--set",
            "hair.loss=female",
            "--age-years",
            "70",
        ];
        let mut resolved = Vec::new();
        for name in COMMANDS {
            let mut argv = vec!["agesim", name];
            argv.extend(head);
            match name {
                "bake" | "hair" => argv.extend(["--out", "o"]),
                "render" => argv.extend(["--out", "o.png"]),
                _ => {}
            }
            let cli =
                Cli::try_parse_from(&argv).unwrap_or_else(|e| panic!("{}: {e}", argv.join(" ")));
            let args = match cli.command {
                Some(Command::Bake(a)) => a.head,
                Some(Command::Hair(a)) => a.head,
                Some(Command::Render(a)) => a.head,
                Some(Command::Export(a)) => a.head,
                Some(Command::MeshInfo(a)) => a.head,
                other => panic!("{name} parsed as {other:?}"),
            };
            let project = args.resolved().expect("resolves");
            let t = args.age.t(&project).expect("an age");
            let years = project.age.mapping().years(t);
            assert!((years - 70.0).abs() < 1e-3, "{name}: {years} years");
            resolved.push((name, project.to_value(), t));
        }
        let (_, p, t) = &resolved[0];
        assert_eq!(p["mesh"]["path"], "head.obj");
        assert_eq!(p["mesh"]["metres_per_unit"].as_f64(), Some(0.01f32 as f64));
        assert_eq!(p["mesh"]["landmarks"], "head.landmarks.json");
        assert_eq!(p["mesh"]["colour_map"], "skin.tga");
        assert_eq!(p["mesh"]["normal_map"], "normal.png");
        assert_eq!(p["mesh"]["maps_flip_v"], true);
        assert_eq!(p["hair"]["loss"], "female");
        for (name, q, u) in &resolved[1..] {
            assert_eq!(q, p, "{name} resolves the head flags differently");
            assert_eq!(u, t, "{name}'s age");
        }
    }

    #[test]
    fn a_head_flag_s_bad_value_is_named_as_typed() {
        let cli =
            Cli::try_parse_from(["agesim", "export", "--metres-per-unit=-3"]).expect("parses");
        let Some(Command::Export(a)) = cli.command else {
            panic!("export");
        };
        let e = a.head.resolved().expect_err("a negative unit").to_string();
        assert!(e.contains("--metres-per-unit -3"), "{e}");
        let cli = Cli::try_parse_from(["agesim", "hair", "--landmarks", "l.json", "--out", "o"])
            .expect("parses");
        let Some(Command::Hair(a)) = cli.command else {
            panic!("hair");
        };
        let e = a
            .head
            .resolved()
            .expect_err("landmarks without a mesh")
            .to_string();
        assert!(e.contains("--landmarks"), "{e}");
    }
}
