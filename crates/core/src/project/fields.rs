//! The one table of project fields: JSON path, unit, range, meaning. It drives the type and
//! range checks of [`super::Project`], `--set`, the generated `docs/project-file.md`
//! ([`markdown`]) and the editor's sliders and tooltips. Defaults are not repeated here:
//! they are read from `Project::default()` ([`Field::default_value`]), so there is one copy.

use serde_json::Value;

use super::json::{get_path, type_name};

/// What a field holds, with its valid range.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Kind {
    /// A number in `min..=max`.
    Float {
        min: f32,
        max: f32,
    },
    /// An integer in `min..=max`.
    Int {
        min: u64,
        max: u64,
    },
    /// A number in `min..=max`, or `null` (off / automatic).
    OptFloat {
        min: f32,
        max: f32,
    },
    /// An integer in `min..=max`, or `null`.
    OptInt {
        min: u64,
        max: u64,
    },
    Bool,
    /// One of these names.
    Choice(&'static [&'static str]),
    /// A file path, or `null` for the built-in default.
    Path,
    /// A list of file paths.
    Paths,
    /// An sRGB colour `"#rrggbb"`.
    Colour,
}

/// One field of the project file.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Field {
    /// The JSON path, e.g. `pores.radius_mm.mean`.
    pub path: &'static str,
    /// Unit, or `""` for none.
    pub unit: &'static str,
    pub kind: Kind,
    /// One line: what it does.
    pub doc: &'static str,
}

const fn f(path: &'static str, unit: &'static str, min: f32, max: f32, doc: &'static str) -> Field {
    Field {
        path,
        unit,
        kind: Kind::Float { min, max },
        doc,
    }
}

const fn i(path: &'static str, unit: &'static str, min: u64, max: u64, doc: &'static str) -> Field {
    Field {
        path,
        unit,
        kind: Kind::Int { min, max },
        doc,
    }
}

const fn k(path: &'static str, kind: Kind, doc: &'static str) -> Field {
    Field {
        path,
        unit: "",
        kind,
        doc,
    }
}

const HU: &str = "height units";
const YEARS: &str = "years";
const MAX_SEED: u64 = u64::MAX;
const CURVE_SHAPES: &[&str] = &["smoothstep", "linear"];

macro_rules! curve {
    ($name:literal, $what:literal) => {
        [
            f(
                concat!("age.", $name, ".onset_years"),
                YEARS,
                0.0,
                150.0,
                concat!($what, ": age at which it starts"),
            ),
            f(
                concat!("age.", $name, ".full_years"),
                YEARS,
                0.0,
                150.0,
                concat!($what, ": age at which it is complete (≥ onset)"),
            ),
            k(
                concat!("age.", $name, ".shape"),
                Kind::Choice(CURVE_SHAPES),
                concat!($what, ": ramp between onset and full age"),
            ),
        ]
    };
}

macro_rules! mean_spread {
    ($path:literal, $unit:expr, $lo:expr, $hi:expr, $spread:expr, $what:literal) => {
        [
            f(
                concat!($path, ".mean"),
                $unit,
                $lo,
                $hi,
                concat!($what, ", mean"),
            ),
            f(
                concat!($path, ".spread"),
                $unit,
                0.0,
                $spread,
                concat!($what, ", ± spread (uniform per feature)"),
            ),
        ]
    };
}

/// Sections in document order, with one line each for the docs page.
pub const SECTIONS: &[(&str, &str)] = &[
    (
        "",
        "Top level: the format version, the skin patch of the micro-relief, the seed.",
    ),
    ("mesh", "The head the maps are made for."),
    (
        "large",
        "Large wrinkles: muscle fibres from wrinkle description files (docs/models.md \"Large wrinkles\").",
    ),
    ("pores", "Pores of the micro-relief ([P] eq. 15, 3, 11)."),
    ("furrows", "Furrows between pores ([P] eq. 16)."),
    ("noise", "Fractal noise added to the heights ([P] eq. 17)."),
    (
        "warp",
        "Domain warp of pores and furrows: the same fBm, its own settings.",
    ),
    ("overlap", "Log-smoothed overlaps of features ([P] eq. 18)."),
    ("normal", "Height map to normal map."),
    (
        "fine",
        "The tileable fine-wrinkle map, blended in with age ([T] §5.2).",
    ),
    (
        "hair",
        "Hair recession (transition texture), instances, graying and Kajiya–Kay shading ([T] §6).",
    ),
    ("skin", "Skin shading and paling with age ([T] §3.1.1)."),
    (
        "age",
        "The age: the current t, the years it stands for, and each layer's age curve (docs/models.md \"Age\").",
    ),
    (
        "view",
        "How the head is shown: POM, light, camera (saved with the project).",
    ),
];

/// Every field of the project, in document order.
pub static FIELDS: std::sync::LazyLock<Vec<Field>> = std::sync::LazyLock::new(|| {
    let mut v = vec![
        i(
            "version",
            "",
            1,
            2,
            "format version (1 is read and migrated)",
        ),
        f(
            "map_size_mm",
            "mm",
            1.0,
            1000.0,
            "side of the square skin patch the micro-relief map covers",
        ),
        i(
            "seed",
            "",
            0,
            MAX_SEED,
            "seed of every random choice of the micro-relief",
        ),
        k(
            "tile",
            Kind::Bool,
            "micro-relief tiles: periodic noise, features wrap around the edges",
        ),
        k(
            "mesh.path",
            Kind::Path,
            "head mesh file (OBJ, glTF, GLB); null = the built-in mesh",
        ),
        k(
            "mesh.builtin",
            Kind::Choice(&["head", "skin-patch"]),
            "built-in mesh used when mesh.path is null",
        ),
        f(
            "mesh.metres_per_unit",
            "m",
            1e-5,
            1000.0,
            "metres per mesh unit (1 for glTF and the built-in meshes)",
        ),
        k(
            "large.enabled",
            Kind::Bool,
            "bake the large-wrinkle layer (--layers overrides)",
        ),
        k(
            "large.wrinkles",
            Kind::Paths,
            "wrinkle description files; empty = the default head's files",
        ),
        k(
            "large.mask",
            Kind::Path,
            "grey mask multiplying the layer; null = the default head's mask with the default files",
        ),
        f("large.gamma", "", 0.01, 10.0, "crest flattening γ"),
        f(
            "large.depth",
            HU,
            0.0,
            10.0,
            "height of a normalised large wrinkle of 1",
        ),
        k("pores.enabled", Kind::Bool, "bake pores"),
        i(
            "pores.count",
            "",
            0,
            200_000,
            "exact number of pores (unless density_per_cm2 is set)",
        ),
        k(
            "pores.density_per_cm2",
            Kind::OptFloat {
                min: 0.0,
                max: 10_000.0,
            },
            "pores per cm²; when set, count = round(density × area)",
        ),
        k(
            "pores.placement",
            Kind::Choice(&["blue-noise", "uniform"]),
            "Poisson disc (minimum spacing) or independent uniform",
        ),
    ];
    v.extend(mean_spread!(
        "pores.radius_mm",
        "mm",
        0.0,
        1.0,
        1.0,
        "pore radius R"
    ));
    v.extend(mean_spread!(
        "pores.depth",
        HU,
        0.0,
        4.0,
        4.0,
        "pore depth dmax"
    ));
    v.extend(mean_spread!(
        "pores.falloff",
        "",
        -1.5,
        1.5,
        1.5,
        "pore falloff α (negative = goose skin)"
    ));
    v.extend([
        k(
            "pores.profile",
            Kind::Choice(&["gaussian", "quadratic", "quartic"]),
            "radial profile: eq. 15, eq. 3 or eq. 11",
        ),
        k(
            "pores.rim",
            Kind::Choice(&["smooth", "exact"]),
            "eq. 15's rim: windowed to 0, or the exact step",
        ),
        k("furrows.enabled", Kind::Bool, "bake furrows"),
        i(
            "furrows.links_per_pore",
            "",
            1,
            8,
            "each pore links to its k nearest neighbours",
        ),
        k(
            "furrows.max_count",
            Kind::OptInt {
                min: 0,
                max: u32::MAX as u64,
            },
            "keep at most this many links (seeded subset); null = all",
        ),
    ]);
    v.extend(mean_spread!(
        "furrows.depth",
        HU,
        0.0,
        2.5,
        2.5,
        "furrow depth A"
    ));
    v.extend(mean_spread!(
        "furrows.width_mm",
        "mm",
        0.0,
        1.5,
        1.5,
        "furrow half-width ω"
    ));
    v.extend([
        f(
            "furrows.direction_deg",
            "degrees",
            -360.0,
            360.0,
            "preferred direction θ, counter-clockwise from +u",
        ),
        f(
            "furrows.direction_strength",
            "",
            0.0,
            1.0,
            "how much shallower links across θ are",
        ),
        f(
            "furrows.taper",
            "",
            0.01,
            0.5,
            "fraction of the length over which each end narrows",
        ),
        f(
            "noise.details",
            "octaves",
            0.0,
            12.0,
            "octaves, fractional allowed; 0 = no noise",
        ),
        f("noise.roughness", "", 0.0, 1.0, "amplitude gain per octave"),
        f(
            "noise.lacunarity",
            "",
            0.1,
            4.0,
            "frequency factor per octave",
        ),
        f(
            "noise.scale_mm",
            "mm",
            0.01,
            1000.0,
            "first-octave lattice cell",
        ),
        f(
            "noise.strength",
            HU,
            0.0,
            10.0,
            "λ: amplitude of the normalised fBm",
        ),
        f(
            "warp.strength_mm",
            "mm",
            0.0,
            10.0,
            "largest displacement per axis; 0 = no warp",
        ),
        f("warp.details", "octaves", 0.0, 6.0, "octaves of the warp"),
        f("warp.roughness", "", 0.0, 1.0, "amplitude gain per octave"),
        f(
            "warp.lacunarity",
            "",
            0.1,
            4.0,
            "frequency factor per octave",
        ),
        f(
            "warp.scale_mm",
            "mm",
            0.01,
            1000.0,
            "first-octave lattice cell",
        ),
        f(
            "overlap.beta",
            "1/height unit",
            0.01,
            40.0,
            "sharpness β; β × the deepest feature ≤ 80",
        ),
        f("overlap.n", "", 1.0, 100.0, "smoothing N"),
        f(
            "normal.strength",
            "UV per height unit",
            0.0,
            1000.0,
            "slope per height step of the exported normal map",
        ),
        k(
            "normal.convention",
            Kind::Choice(&["opengl", "directx"]),
            "green up (OpenGL) or down (DirectX)",
        ),
        k("fine.enabled", Kind::Bool, "show the fine wrinkles"),
        k(
            "fine.tile",
            Kind::Path,
            "tileable grey height image; null = generated from the fields below",
        ),
        f(
            "fine.size_mm",
            "mm",
            1.0,
            500.0,
            "side of one tile on the skin",
        ),
        f(
            "fine.strength",
            "tile UV per height unit",
            0.0,
            1.0,
            "normal strength of the tile",
        ),
        i(
            "fine.size_px",
            "px",
            16,
            8192,
            "resolution of the generated tile",
        ),
        i(
            "fine.creases",
            "",
            1,
            100_000,
            "number of creases in the generated tile",
        ),
        f(
            "fine.length",
            "tile sides",
            0.001,
            0.5,
            "mean crease length",
        ),
        f(
            "fine.width",
            "tile sides",
            0.0001,
            0.05,
            "crease valley half-width σ",
        ),
        f(
            "fine.crossing_deg",
            "degrees",
            0.0,
            180.0,
            "angle between the two crease families",
        ),
        f(
            "fine.spread_deg",
            "degrees",
            0.0,
            90.0,
            "random spread of each crease's direction",
        ),
        i("fine.seed", "", 0, MAX_SEED, "seed of the generated tile"),
        k("hair.enabled", Kind::Bool, "generate and show hair"),
        k(
            "hair.outer_mask",
            Kind::Path,
            "grey mask of the hair at t = 0; null = the default head's",
        ),
        k(
            "hair.inner_mask",
            Kind::Path,
            "grey mask of the hair left at t = 1; null = the default head's",
        ),
        f(
            "hair.density_per_cm2",
            "1/cm²",
            0.0,
            2000.0,
            "hairs per cm² of scalp",
        ),
        k(
            "hair.metric",
            Kind::Choice(&["chebyshev", "euclidean"]),
            "distance of the recession fronts: square or round",
        ),
        k(
            "hair.transition_size_px",
            Kind::OptInt {
                min: 1,
                max: 16_384,
            },
            "transition texture side; null = the masks' size",
        ),
        i("hair.seed", "", 0, MAX_SEED, "seed of the hair placement"),
        f(
            "hair.max_deviation_deg",
            "degrees",
            0.0,
            90.0,
            "random deviation of a hair from the surface normal",
        ),
        f("hair.length_mm", "mm", 0.0, 500.0, "hair length"),
        k("hair.base_colour", Kind::Colour, "colour before graying"),
        k("hair.gray_colour", Kind::Colour, "colour when fully gray"),
        f(
            "hair.graying_onset_min_years",
            YEARS,
            0.0,
            150.0,
            "earliest age at which a hair starts to gray",
        ),
        f(
            "hair.graying_onset_max_years",
            YEARS,
            0.0,
            150.0,
            "latest age at which a hair starts to gray",
        ),
        k(
            "hair.graying_ramp",
            Kind::Choice(&["linear", "smoothstep"]),
            "how a hair grays after its onset",
        ),
        f("hair.k_diff", "", 0.0, 4.0, "Kajiya–Kay diffuse weight"),
        f("hair.k_spec", "", 0.0, 4.0, "Kajiya–Kay specular weight"),
        f(
            "hair.shininess",
            "",
            1.0,
            1000.0,
            "Kajiya–Kay specular exponent",
        ),
        f("hair.k_amb", "", 0.0, 1.0, "ambient term"),
        k("skin.albedo", Kind::Colour, "skin colour at the young end"),
        k(
            "skin.pale_albedo",
            Kind::Colour,
            "the tone skin pales toward",
        ),
        f(
            "skin.pale_amount",
            "",
            0.0,
            1.0,
            "how far toward pale_albedo at full paling",
        ),
        k(
            "skin.subsurface_colour",
            Kind::Colour,
            "colour of light scattered under the skin",
        ),
        f(
            "skin.wrap",
            "",
            0.0,
            1.0,
            "wrap lighting (cheap subsurface scattering)",
        ),
        f("skin.roughness", "", 0.05, 1.0, "specular roughness"),
        f("skin.specular", "", 0.0, 1.0, "specular strength"),
        f(
            "age.t",
            "",
            0.0,
            1.0,
            "current age: 0 = young_years, 1 = old_years",
        ),
        f(
            "age.young_years",
            YEARS,
            0.0,
            150.0,
            "the age t = 0 stands for",
        ),
        f(
            "age.old_years",
            YEARS,
            0.0,
            150.0,
            "the age t = 1 stands for",
        ),
    ]);
    v.extend(curve!(
        "large",
        "large-wrinkle depth (fibres without their own curve)"
    ));
    v.extend(curve!("fine", "fine-wrinkle blend"));
    v.extend(curve!("pores", "pore widening"));
    v.push(f(
        "age.pores_young_scale",
        "",
        0.1,
        1.0,
        "pore radius at the young end, relative to pores.radius_mm",
    ));
    v.extend(curve!("furrows", "furrow deepening"));
    v.push(f(
        "age.furrows_young_scale",
        "",
        0.0,
        1.0,
        "furrow depth at the young end, relative to furrows.depth",
    ));
    v.extend(curve!("pale", "skin paling"));
    v.extend([
        k(
            "view.pom",
            Kind::Choice(&["linear", "binary", "combined", "normal", "displacement"]),
            "relief: POM linear / binary / combined, normal map only, displaced geometry",
        ),
        i("view.linear_steps", "", 1, 256, "POM linear search steps L"),
        i("view.binary_steps", "", 0, 32, "POM binary search steps B"),
        f(
            "view.disp_scale",
            "UV",
            0.0,
            0.1,
            "POM depth of the full large-wrinkle height (dispScale)",
        ),
        f(
            "view.light_yaw_deg",
            "degrees",
            -360.0,
            360.0,
            "light direction around the head",
        ),
        f(
            "view.light_pitch_deg",
            "degrees",
            -90.0,
            90.0,
            "light elevation",
        ),
        f(
            "view.camera_yaw_deg",
            "degrees",
            -360.0,
            360.0,
            "camera orbit angle",
        ),
        f(
            "view.camera_pitch_deg",
            "degrees",
            -89.0,
            89.0,
            "camera elevation",
        ),
        f(
            "view.camera_distance_m",
            "m",
            0.01,
            100.0,
            "camera distance from the head's centre",
        ),
        f(
            "view.fov_deg",
            "degrees",
            5.0,
            120.0,
            "vertical field of view",
        ),
        k("view.show_hair", Kind::Bool, "draw the hair"),
        k(
            "view.wireframe",
            Kind::Bool,
            "draw the mesh's triangle edges over the skin",
        ),
    ]);
    v
});

/// The field at `path`, or an error naming the closest fields.
pub fn find(path: &str) -> Result<&'static Field, String> {
    if let Some(field) = FIELDS.iter().find(|f| f.path == path) {
        return Ok(field);
    }
    let shown = crate::limits::shorten(path, 80);
    let prefix = format!("{path}.");
    let below: Vec<&str> = FIELDS
        .iter()
        .filter(|f| f.path.starts_with(&prefix))
        .map(|f| f.path)
        .collect();
    if !below.is_empty() {
        return Err(format!(
            "`{shown}` is a group of fields: set one of {}",
            below.join(", ")
        ));
    }
    let section = path.split('.').next().unwrap_or("");
    let near: Vec<&str> = FIELDS
        .iter()
        .filter(|f| f.path.split('.').next() == Some(section))
        .map(|f| f.path)
        .collect();
    Err(if near.is_empty() {
        format!("unknown field `{shown}`; see docs/project-file.md")
    } else {
        format!(
            "unknown field `{shown}`; expected one of: {}",
            near.join(", ")
        )
    })
}

impl Field {
    /// The default value, from `Project::default()`.
    pub fn default_value(&self) -> Value {
        let d = super::Project::default().to_value();
        get_path(&d, self.path).cloned().unwrap_or(Value::Null)
    }

    /// The range for messages and docs.
    pub fn range_text(&self) -> String {
        match self.kind {
            Kind::Float { min, max } => format!("{min}..={max}"),
            Kind::Int { min, max } if max == u64::MAX => format!("an integer ≥ {min}"),
            Kind::Int { min, max } => format!("an integer in {min}..={max}"),
            Kind::OptFloat { min, max } => format!("{min}..={max} or null"),
            Kind::OptInt { min, max } => format!("an integer in {min}..={max} or null"),
            Kind::Bool => "true or false".into(),
            Kind::Choice(names) => format!("one of {}", names.join(", ")),
            Kind::Path => "a path or null".into(),
            Kind::Paths => "a list of paths".into(),
            Kind::Colour => "\"#rrggbb\"".into(),
        }
    }

    /// What a JSON value of this field must look like (its type, not its range).
    fn type_text(&self) -> &'static str {
        match self.kind {
            Kind::Float { .. } => "a number",
            Kind::Int { .. } => "an integer",
            Kind::OptFloat { .. } => "a number or null",
            Kind::OptInt { .. } => "an integer or null",
            Kind::Bool => "true or false",
            Kind::Choice(_) => "a name",
            Kind::Path => "a path (string) or null",
            Kind::Paths => "a list of paths",
            Kind::Colour => "a colour \"#rrggbb\"",
        }
    }

    fn type_ok(&self, v: &Value) -> bool {
        match self.kind {
            Kind::Float { .. } => v.is_number(),
            Kind::Int { .. } => v.is_u64(),
            Kind::OptFloat { .. } => v.is_number() || v.is_null(),
            Kind::OptInt { .. } => v.is_u64() || v.is_null(),
            Kind::Bool => v.is_boolean(),
            Kind::Choice(_) | Kind::Colour => v.is_string(),
            Kind::Path => v.is_string() || v.is_null(),
            Kind::Paths => v.as_array().is_some_and(|a| a.iter().all(Value::is_string)),
        }
    }

    /// The range problem of a well-typed value, if any.
    fn range_problem(&self, v: &Value) -> Option<String> {
        let ok = match self.kind {
            Kind::Float { min, max } | Kind::OptFloat { min, max } => match v.as_f64() {
                None => true,
                Some(x) => x >= min as f64 && x <= max as f64,
            },
            Kind::Int { min, max } | Kind::OptInt { min, max } => match v.as_u64() {
                None => v.is_null(),
                Some(x) => x >= min && x <= max,
            },
            Kind::Choice(names) => v.as_str().is_some_and(|s| names.contains(&s)),
            Kind::Colour => v.as_str().and_then(super::Colour::parse).is_some(),
            Kind::Bool | Kind::Path | Kind::Paths => true,
        };
        (!ok).then(|| {
            format!(
                "{} = {} is out of range: expected {}",
                self.path,
                quote(v),
                self.range_text()
            )
        })
    }

    /// Reads a value typed on the command line as this field's type.
    pub fn parse_text(&self, text: &str) -> Result<Value, String> {
        // A JSON string literal (`"a b.wrk"`) stands for its contents.
        let decoded = serde_json::from_str::<String>(text.trim()).ok();
        let t = decoded.as_deref().unwrap_or(text.trim());
        let bad = || {
            format!(
                "{}: expected {} ({}), found `{}`",
                self.path,
                self.type_text(),
                self.range_text(),
                crate::limits::shorten(t, 60)
            )
        };
        let number = || {
            t.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite())
                .and_then(serde_json::Number::from_f64)
                .map(Value::Number)
        };
        let value = match self.kind {
            Kind::Float { .. } => number(),
            Kind::OptFloat { .. } if t == "null" => Some(Value::Null),
            Kind::OptFloat { .. } => number(),
            Kind::Int { .. } => t.parse::<u64>().ok().map(Value::from),
            Kind::OptInt { .. } if t == "null" => Some(Value::Null),
            Kind::OptInt { .. } => t.parse::<u64>().ok().map(Value::from),
            Kind::Bool => t.parse::<bool>().ok().map(Value::Bool),
            Kind::Choice(_) | Kind::Colour => Some(Value::String(t.to_owned())),
            Kind::Path if t == "null" => Some(Value::Null),
            Kind::Path => Some(Value::String(t.to_owned())),
            Kind::Paths => serde_json::from_str::<Vec<String>>(t)
                .ok()
                .or_else(|| Some(t.split(',').map(|s| s.trim().to_owned()).collect()))
                .map(|v| v.into_iter().map(Value::String).collect()),
        };
        let value = value.ok_or_else(bad)?;
        match self.range_problem(&value) {
            Some(p) => Err(p),
            None => Ok(value),
        }
    }
}

/// A value quoted for a message, cut to a readable length.
fn quote(v: &Value) -> String {
    crate::limits::shorten(&v.to_string(), 60)
}

/// Type errors of every field present in `doc` (a parsed, shape-checked document), and
/// bad names and colours (which the typed parse would report without their path).
pub(crate) fn check_types(doc: &Value, out: &mut Vec<String>) {
    for field in FIELDS.iter() {
        let Some(v) = get_path(doc, field.path) else {
            continue;
        };
        if !field.type_ok(v) {
            out.push(format!(
                "{}: expected {}, found {} {}",
                field.path,
                field.type_text(),
                type_name(v),
                quote(v)
            ));
        } else if matches!(field.kind, Kind::Choice(_) | Kind::Colour)
            && let Some(p) = field.range_problem(v)
        {
            out.push(p);
        }
    }
}

/// Range errors of every field of a whole project document.
pub(crate) fn check_ranges(doc: &Value, out: &mut Vec<String>) {
    for field in FIELDS.iter().filter(|f| f.path != "version") {
        if let Some(v) = get_path(doc, field.path)
            && let Some(p) = field.range_problem(v)
        {
            out.push(p);
        }
    }
}

/// A default value as the docs show it.
fn default_text(v: &Value) -> String {
    match v {
        Value::Null => "null".into(),
        Value::String(s) => format!("`{s}`"),
        Value::Array(a) if a.is_empty() => "[]".into(),
        other => other.to_string(),
    }
}

/// The docs page `docs/project-file.md`, generated from [`FIELDS`].
pub fn markdown() -> String {
    use std::fmt::Write as _;
    let mut out = String::from(include_str!("project-file-intro.md"));
    for (section, about) in SECTIONS {
        let title = if section.is_empty() {
            "top level"
        } else {
            section
        };
        let _ = write!(out, "\n## `{title}`\n\n{about}\n\n");
        out.push_str("| field | unit | range | default | meaning |\n|---|---|---|---|---|\n");
        for field in FIELDS.iter().filter(|f| match f.path.split_once('.') {
            Some((s, _)) => s == *section,
            None => section.is_empty(),
        }) {
            let _ = writeln!(
                out,
                "| `{}` | {} | {} | {} | {} |",
                field.path,
                if field.unit.is_empty() {
                    "—"
                } else {
                    field.unit
                },
                field.range_text(),
                default_text(&field.default_value()),
                field.doc
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every leaf of the default project, by path.
    fn leaves(v: &Value, at: &str, out: &mut Vec<String>) {
        match v {
            Value::Object(m) => {
                for (k, c) in m {
                    leaves(c, &super::super::json::join(at, k), out);
                }
            }
            _ => out.push(at.to_owned()),
        }
    }

    #[test]
    fn the_table_covers_every_field_of_the_project_exactly_once() {
        let mut paths = Vec::new();
        leaves(&super::super::Project::default().to_value(), "", &mut paths);
        let table: Vec<&str> = FIELDS.iter().map(|f| f.path).collect();
        for p in &paths {
            assert_eq!(
                table.iter().filter(|t| *t == p).count(),
                1,
                "{p} must be in the table once"
            );
        }
        assert_eq!(
            paths.len(),
            table.len(),
            "table has fields the project lacks"
        );
    }

    #[test]
    fn every_default_is_valid_for_its_own_field() {
        for field in FIELDS.iter() {
            let v = field.default_value();
            assert!(field.type_ok(&v), "{}: {v}", field.path);
            assert_eq!(field.range_problem(&v), None, "{}", field.path);
        }
    }

    #[test]
    fn every_choice_name_deserialises() {
        for field in FIELDS.iter() {
            if let Kind::Choice(names) = field.kind {
                for name in names {
                    let p = super::super::Project::default()
                        .set(field.path, name)
                        .unwrap_or_else(|e| panic!("{}={name}: {e}", field.path));
                    assert_eq!(
                        get_path(&p.to_value(), field.path),
                        Some(&Value::String(name.to_string()))
                    );
                }
            }
        }
    }

    #[test]
    fn the_docs_page_is_generated_from_the_table_and_up_to_date() {
        let path =
            std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/project-file.md");
        let want = markdown();
        if std::env::var_os("UPDATE_DOCS").is_some() {
            std::fs::write(&path, &want).unwrap();
        }
        let have = std::fs::read_to_string(&path).unwrap_or_default();
        assert!(
            have == want,
            "docs/project-file.md is stale: run `UPDATE_DOCS=1 cargo test -p agesim-core the_docs_page` and commit it"
        );
        for field in FIELDS.iter() {
            assert!(
                want.contains(&format!("`{}`", field.path)),
                "{}",
                field.path
            );
        }
    }
}
