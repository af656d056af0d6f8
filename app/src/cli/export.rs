//! `agesim export`: the editor's Export window as a command, sharing its code
//! ([`crate::export`]), so pipelines can batch what an artist does by hand.

use std::path::PathBuf;
use std::time::Instant;

use agesim_core::base::cancel::CancelToken;
use anyhow::bail;

use crate::export::{ExportRequest, GlbOut, MapsOut, RendersOut};

/// Export maps, renders and the aged head (GLB) of a project at an age.
#[derive(Debug, clap::Args)]
pub struct ExportArgs {
    /// Side of the maps and of the GLB's textures, px (1..=16384; beyond 8192 only as far
    /// as memory allows); per tile for a UDIM head, whose maps are written one per tile
    /// (`height.1001.png`, …).
    #[arg(long, default_value_t = 2048, value_name = "N")]
    pub size: u32,
    /// Height map as a 16-bit PNG.
    #[arg(long, value_name = "FILE.png")]
    pub height_png: Option<PathBuf>,
    /// Height map as a 32-bit float EXR.
    #[arg(long, value_name = "FILE.exr")]
    pub height_exr: Option<PathBuf>,
    /// Compression of the height EXR (lossless): rle (usually the fastest), none, zip
    /// (smallest).
    #[arg(long, value_enum, default_value = "rle")]
    pub exr_compression: crate::cli::bake::ExrCompressionArg,
    /// Normal map as an 8-bit PNG.
    #[arg(long, value_name = "FILE.png")]
    pub normal_png: Option<PathBuf>,
    /// The normal map's green channel (default: the project's `normal.convention`).
    #[arg(long, value_enum)]
    pub normal_convention: Option<crate::cli::bake::ConventionArg>,
    /// The aged base colour as an 8-bit PNG (at the head's colour map's size, 1024–2048).
    #[arg(long, value_name = "FILE.png")]
    pub base_colour_png: Option<PathBuf>,
    /// The skin's roughness at the age as an 8-bit grey PNG: drier (rougher) with age,
    /// rougher in the creases (the GLB's metallicRoughnessTexture's green).
    #[arg(long, value_name = "FILE.png")]
    pub roughness_png: Option<PathBuf>,
    /// The creases' cavity occlusion as an 8-bit grey PNG (255 = open skin; the GLB's
    /// occlusionTexture).
    #[arg(long, value_name = "FILE.png")]
    pub ao_png: Option<PathBuf>,
    /// Bake the micro-relief periodic so the maps tile (skin patches).
    #[arg(long)]
    pub tileable: bool,
    /// The aged head as binary glTF (normal map, base colour, roughness and occlusion at
    /// the age; the height map beside it as FILE_wrinkle_height.png).
    #[arg(long, value_name = "FILE.glb")]
    pub glb: Option<PathBuf>,
    /// The aged hair and brows in the GLB, as a mesh named `hair` (each strand a ribbon,
    /// coloured as the view colours it): light (one scalp hair in 4, each 4 times as wide:
    /// the same cover, a quarter of the bytes), full (every hair), or none.
    #[arg(long, value_enum, default_value = "light")]
    pub glb_hair: GlbHairArg,
    /// A render at the age.
    #[arg(long, value_name = "FILE.png")]
    pub render: Option<PathBuf>,
    /// Renders at several ages (years, comma separated; see --years): FILE_0000.png, ….
    #[arg(long, value_name = "FILE.png", requires = "years")]
    pub sequence: Option<PathBuf>,
    /// The ages of --sequence, years.
    #[arg(long, value_delimiter = ',', value_name = "Y,Y,…")]
    pub years: Vec<f32>,
    /// A young | old comparison image at the two ages of --compare-years.
    #[arg(long, value_name = "FILE.png")]
    pub compare: Option<PathBuf>,
    /// The two ages of --compare, years.
    #[arg(
        long,
        value_delimiter = ',',
        default_value = "25,75",
        value_name = "Y0,Y1"
    )]
    pub compare_years: Vec<f32>,
    /// Size of the renders, WxH px.
    #[arg(long, default_value = "1024x1024", value_parser = super::parse_size)]
    pub render_size: (u32, u32),
    /// The project, the head and the age of the export.
    #[command(flatten)]
    pub head: super::HeadArgs,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
pub enum GlbHairArg {
    None,
    Light,
    Full,
}

impl From<GlbHairArg> for crate::export::GlbHair {
    fn from(h: GlbHairArg) -> Self {
        match h {
            GlbHairArg::None => Self::None,
            GlbHairArg::Light => Self::Light,
            GlbHairArg::Full => Self::Full,
        }
    }
}

pub fn run(args: &ExportArgs) -> anyhow::Result<()> {
    let start = Instant::now();
    let project = args.head.resolved()?;
    let years = project.age.mapping().years(args.head.age.t(&project)?);
    let compare = match (&args.compare, args.compare_years.as_slice()) {
        (None, _) => None,
        (Some(path), &[a, b]) => Some((path.clone(), [a, b])),
        (Some(_), other) => bail!(
            "--compare-years takes two ages, Y0,Y1 (got {} values)",
            other.len()
        ),
    };
    let request = ExportRequest {
        years,
        maps: MapsOut {
            size_px: args.size,
            height_png: args.height_png.clone(),
            height_exr: args.height_exr.clone(),
            normal_png: args.normal_png.clone(),
            base_colour_png: args.base_colour_png.clone(),
            roughness_png: args.roughness_png.clone(),
            ao_png: args.ao_png.clone(),
            convention: args.normal_convention.map(Into::into),
            tileable: args.tileable,
            exr_compression: args.exr_compression.into(),
        },
        glb: args.glb.clone().map(|path| GlbOut {
            hair: args.glb_hair.into(),
            path,
            size_px: args.size,
        }),
        renders: RendersOut {
            size: args.render_size,
            image: args.render.clone(),
            sequence: args.sequence.clone().map(|p| (p, args.years.clone())),
            compare,
        },
    };
    let last = std::sync::Mutex::new(String::new());
    let progress = |_: f32, what: &str| {
        let mut last = last.lock().unwrap_or_else(|p| p.into_inner());
        if *last != what {
            eprintln!("  {what}…");
            *last = what.to_owned();
        }
    };
    let files = crate::export::run(&project, None, &request, &progress, &CancelToken::never())?;
    println!(
        "exported {} file(s) at {years:.0} years in {:.0} ms:",
        files.len(),
        start.elapsed().as_secs_f64() * 1e3
    );
    for f in files {
        println!("  {}", f.display());
    }
    Ok(())
}
